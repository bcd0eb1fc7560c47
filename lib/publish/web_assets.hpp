// The published page's own files, web/ (index.html, the ES modules, the style sheet, and the
// JPEG 2000 decoder web/openjpeg/j2k_decode.js and .wasm.gz), embedded at build time by
// cmake/embed_folder.cmake so that an installed relume publishes without its source tree.
#pragma once

#include <map>
#include <string>

namespace relume {

// Path relative to web/ (for example "index.html", "openjpeg/j2k_decode.wasm.gz") -> bytes.
const std::map<std::string, std::string>& web_assets();

}  // namespace relume
