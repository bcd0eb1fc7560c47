// The process's ranks (see ranks.hpp): one process unless the command installs MPI's.
#include "core/ranks.hpp"

namespace relume {
namespace {

Ranks single_process;
Ranks* installed = &single_process;

}  // namespace

RankShare rank_share(const Ranks& ranks, int count, int rank) {
  return {int(std::int64_t(count) * rank / ranks.size()),
          int(std::int64_t(count) * (rank + 1) / ranks.size())};
}

Ranks& process_ranks() { return *installed; }

void set_process_ranks(Ranks* ranks) { installed = ranks ? ranks : &single_process; }

}  // namespace relume
