// Outputs are never replaced silently: every command checks its output paths before it starts
// work and refuses an existing file, or a non-empty output folder, unless the global
// -y/--overwrite (as in ffmpeg) allows it. Writes themselves stay atomic (core/atomic_file.hpp).
#pragma once

#include <filesystem>
#include <string>

namespace relume {

// Set once by main.cpp from -y/--overwrite.
void allow_overwrite();
bool overwrite_allowed();

// Throws Error naming `path` when it exists (as a file or anything else) and overwriting is not
// allowed. An empty path (an optional output not asked for) passes. Whether it can be written is
// core/atomic_file.hpp's check_output_file_location.
void check_new_output(const std::filesystem::path& path);

// Throws Error naming `folder` when it exists and is not an empty folder, unless overwriting is
// allowed (then files of the same names are replaced), or when it could not be written (a file in
// its place, an unwritable parent: check_output_folder_location).
void check_output_folder(const std::filesystem::path& folder);

}  // namespace relume
