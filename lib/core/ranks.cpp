// The process's ranks (see ranks.hpp): one process unless the command installs MPI's.
#include "core/ranks.hpp"

#include <algorithm>

#include "core/parallel.hpp"

namespace relume {
namespace {

Ranks single_process;
Ranks* installed = &single_process;

}  // namespace

LocalCoresLease::LocalCoresLease(Ranks& ranks) : ranks_(ranks) {
  ranks_.use_local_cores(true);
  cores_ = cores_of_this_thread();
}

unsigned LocalCoresLease::threads(unsigned threads) const {
  if (threads == 0) return 0;
  return std::min(threads * unsigned(ranks_.local_size()), std::max(threads, cores_));
}

RankShare rank_share(const Ranks& ranks, int count, int rank) {
  return {int(std::int64_t(count) * rank / ranks.size()),
          int(std::int64_t(count) * (rank + 1) / ranks.size())};
}

std::vector<int> weighted_shares(const std::vector<std::uint64_t>& weights, int parts) {
  const int count = int(weights.size());
  std::uint64_t total = 0;
  for (const std::uint64_t weight : weights) total += weight;
  std::vector<int> boundaries{0};
  int item = 0;
  std::uint64_t reached = 0;  // weight of items [0, item)
  for (int r = 1; r < parts; ++r) {
    if (total == 0) {
      boundaries.push_back(int(std::int64_t(count) * r / parts));
      continue;
    }
    const double goal = double(total) * r / parts;
    while (item < count && double(reached + weights[std::size_t(item)]) <= goal)
      reached += weights[std::size_t(item++)];
    // Past the goal with the next item: take it when that lands nearer to the goal.
    if (item < count &&
        goal - double(reached) > double(reached + weights[std::size_t(item)]) - goal)
      reached += weights[std::size_t(item++)];
    boundaries.push_back(item);
  }
  boundaries.push_back(count);
  return boundaries;
}

Ranks& process_ranks() { return *installed; }

void set_process_ranks(Ranks* ranks) { installed = ranks ? ranks : &single_process; }

}  // namespace relume
