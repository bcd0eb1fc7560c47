// The viewer's page, embedded in the binary at build time from apps/commands/view/page/ by
// cmake/embed_text.cmake (plain HTML, JavaScript and CSS: no build step, nothing fetched from
// elsewhere, so it works offline).
#pragma once

#include <string>

namespace relume {

const std::string& viewer_page_html();    // page/index.html
const std::string& viewer_page_script();  // page/viewer.js
const std::string& viewer_page_style();   // page/viewer.css

}  // namespace relume
