// Implementation of the output checks.
#include "output_paths.hpp"

#include <relume/error.hpp>

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
  if (!fs::exists(folder)) return;
  if (!fs::is_directory(folder)) throw Error(folder.string() + " exists and is not a folder");
  if (!overwrite && !fs::is_empty(folder))
    throw Error("output folder " + folder.string() +
                " is not empty: pass -y/--overwrite to write into it (files of the same names "
                "are replaced)");
}

}  // namespace relume
