// The published page's own files, web/* (index.html, the ES modules, the style sheet), embedded
// at build time by cmake/embed_folder.cmake so that an installed relume publishes without its
// source tree.
#pragma once

#include <map>
#include <string>

namespace relume {

// File name (for example "index.html") -> text.
const std::map<std::string, std::string>& web_assets();

}  // namespace relume
