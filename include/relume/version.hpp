// relume/version.hpp: the library's version and the git commit it was built from, as `relume
// --version`, every JSON report, every container's parameters and every written image's Software
// attribute record them.
#pragma once

#include <string>

namespace relume {

// "MAJOR.MINOR.PATCH" of the CMake project.
std::string version();
// The commit's short hash, with "-dirty" when the work tree had uncommitted changes; "unknown"
// when the sources were not built from a git checkout.
std::string git_commit();
// "relume 0.1.0 (commit 1a2b3c4d)".
std::string version_line();

}  // namespace relume
