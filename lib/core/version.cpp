// The version strings of relume/version.hpp. RELUME_VERSION comes from the CMake project; the
// commit from the header cmake/git_commit.cmake regenerates at every build.
#include <relume/version.hpp>

#include "relume_git_commit.hpp"  // RELUME_GIT_COMMIT, generated in the build folder

namespace relume {

std::string version() { return RELUME_VERSION; }

std::string git_commit() { return RELUME_GIT_COMMIT; }

std::string version_line() { return "relume " + version() + " (commit " + git_commit() + ")"; }

}  // namespace relume
