// Implementation of the output checks.
#include "options/output_paths.hpp"

#include <relume/error.hpp>

#include "core/atomic_file.hpp"

namespace relume {
namespace fs = std::filesystem;

namespace {
bool overwrite = false;
}  // namespace

void allow_overwrite() { overwrite = true; }
bool overwrite_allowed() { return overwrite; }

void check_new_output(const fs::path& path) {
  if (path.empty() || overwrite || !fs::exists(path)) return;
  throw Error(path.string() + " exists: pass -y/--overwrite to replace it");
}

void check_output_folder(const fs::path& folder) {
  check_output_folder_location(folder);
  if (!overwrite && fs::is_directory(folder) && !fs::is_empty(folder))
    throw Error("output folder " + folder.string() +
                " is not empty: pass -y/--overwrite to write into it (files of the same names "
                "are replaced)");
}

}  // namespace relume
