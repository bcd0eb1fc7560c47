// The process's ranks (see ranks.hpp): one process unless the command installs MPI's.
#include "core/ranks.hpp"

namespace relume {
namespace {

Ranks single_process;
Ranks* installed = &single_process;

}  // namespace

Ranks& process_ranks() { return *installed; }

void set_process_ranks(Ranks* ranks) { installed = ranks ? ranks : &single_process; }

}  // namespace relume
