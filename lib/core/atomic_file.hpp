// Atomic output: everything relume writes goes to a temporary file beside the target
// (core/temporary_files.hpp), is fsynced, then renamed over the target, so an interrupted or failed
// run never leaves a half-written file. While a temporary exists it is registered for the signal
// handler (core/signals.hpp); stale temporaries that a killed run left beside the same target are
// removed before a new write. An interruption requested while the data was written
// (core/interruption.hpp) discards it instead of renaming: the previous file stays.
#pragma once

#include <filesystem>
#include <functional>
#include <string>

namespace relume {

// The checks write_atomically makes of `target` before it writes, for commands to make before
// they start long work: its folder exists and this process can create files in it (a probe file
// is made and removed: /proc passes access() for root), and `target` is not a folder. Throws
// Error naming `target`, and its folder when that is a file or does not exist.
void check_output_file_location(const std::filesystem::path& target);

// The same for write_folder_atomically: `folder` is not a file, and the folder itself or, when
// it does not exist yet, its nearest existing parent is a folder this process may write in.
void check_output_folder_location(const std::filesystem::path& folder);

// Calls write(temp_path) and, if it returns normally and no interruption was requested, fsyncs
// temp_path and renames it to `target`. On any exception the temporary file is removed and the
// exception propagates (relume::Interrupted for an interruption). Throws Error naming `target`
// when its folder does not exist or `target` is a folder.
void write_atomically(const std::filesystem::path& target,
                      const std::function<void(const std::filesystem::path& temp)>& write);

// Writes `bytes` to `target` atomically; a failed write (a full disk) names the target and why.
void write_file_atomically(const std::filesystem::path& target, const std::string& bytes);

// The same for a folder: write(temp_folder) fills a new temporary folder beside `target` (its
// parents are created); then, unless an interruption was requested, the folder is renamed to
// `target`, or, when `target` already is a folder, its entries are moved into it (replacing
// entries of the same names; a folder replaces the old folder of its name with all its files). On any exception the temporary folder is removed whole, so a failed
// or interrupted run exposes nothing.
void write_folder_atomically(const std::filesystem::path& target,
                             const std::function<void(const std::filesystem::path& temp)>& write);

// Reads a whole file; throws Error naming the file when it cannot be read.
std::string read_file(const std::filesystem::path& path);

}  // namespace relume
