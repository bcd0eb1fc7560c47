// Atomic output: everything relume writes goes to a temporary file beside the target, is fsynced,
// then renamed over the target, so an interrupted or failed run never leaves a half-written file.
#pragma once

#include <filesystem>
#include <functional>
#include <string>

namespace relume {

// Calls write(temp_path) and, if it returns normally, fsyncs temp_path and renames it to `target`.
// On any exception the temporary file is removed and the exception propagates.
void write_atomically(const std::filesystem::path& target,
                      const std::function<void(const std::filesystem::path& temp)>& write);

// Writes `bytes` to `target` atomically.
void write_file_atomically(const std::filesystem::path& target, const std::string& bytes);

// Reads a whole file; throws Error naming the file when it cannot be read.
std::string read_file(const std::filesystem::path& path);

}  // namespace relume
