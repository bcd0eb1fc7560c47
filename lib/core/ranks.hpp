// The processes that share one run. A plain run is one process; `mpirun -n N relume compress ...`
// (the command built with MPI, apps/commands/compress/mpi_ranks.*) makes it N ranks, over which a
// streamed compression splits its pixel rows (compress/streamed_compression.hpp). The library only
// knows this interface: one process by default, so it needs no MPI itself.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace relume {

class Ranks {
 public:
  virtual ~Ranks() = default;

  virtual int rank() const { return 0; }
  virtual int size() const { return 1; }
  // The ranks on this machine, this one included: they share its memory.
  virtual int local_size() const { return 1; }
  // true: this thread, and the threads it starts, may run on the cores of every rank on its
  // machine (under mpirun each rank is usually bound to its own), while the others wait for it;
  // false: on this rank's own again.
  virtual void use_local_cores(bool /*all*/) {}
  bool root() const { return rank() == 0; }

  // Element-wise sums over the ranks: into the root's `values` (the others' are left as they
  // were), or into every rank's.
  virtual void sum_to_root(double* /*values*/, std::size_t /*count*/) {}
  virtual void sum_everywhere(double* /*values*/, std::size_t /*count*/) {}
  // The root's bytes to every rank (resized on the others).
  virtual void broadcast(std::string& /*bytes*/) {}
  // Every rank's bytes, in rank order, at the root; empty elsewhere.
  virtual std::vector<std::string> gather_to_root(const std::string& bytes) { return {bytes}; }
  // The root's parts[r] to rank r (`parts` has one per rank at the root, is ignored elsewhere):
  // this rank's part.
  virtual std::string scatter_from_root(std::vector<std::string> parts) {
    return std::move(parts.at(0));
  }
  // Every rank's to[r] to rank r, all at once: from[q] is what rank q sent this one (`to` has one
  // entry per rank; a rank's entry for itself comes back as it is).
  virtual std::vector<std::string> exchange(std::vector<std::string> to) { return to; }
  // Bytes this rank has sent to the others so far, and the seconds it spent in the exchanges
  // (sending, receiving and waiting for the others).
  virtual std::uint64_t bytes_sent() const { return 0; }
  virtual double exchange_seconds() const { return 0; }
};

// use_local_cores(true) for its lifetime: the root clusters the sample and writes the file on
// the cores of the ranks that wait for it.
class LocalCoresLease {
 public:
  explicit LocalCoresLease(Ranks& ranks);
  ~LocalCoresLease() { ranks_.use_local_cores(false); }
  LocalCoresLease(const LocalCoresLease&) = delete;
  LocalCoresLease& operator=(const LocalCoresLease&) = delete;

  // The cores this thread may run on now.
  unsigned cores() const { return cores_; }
  // The threads to run for ranks of `threads` each (0: every core, returned as it is): as many for
  // every rank on this machine, at most the cores and no fewer than `threads`.
  unsigned threads(unsigned threads) const;

 private:
  Ranks& ranks_;
  unsigned cores_ = 1;
};

// Rank `rank`'s share [first, end) of `count` items split over the ranks in rank order.
struct RankShare {
  int first = 0, end = 0;
};
RankShare rank_share(const Ranks& ranks, int count, int rank);
inline RankShare rank_share(const Ranks& ranks, int count) {
  return rank_share(ranks, count, ranks.rank());
}

// `parts` consecutive shares of items weighted `weights` (for example the stored functions of
// every pixel row), as even in weight as whole items allow: parts + 1 boundaries, from 0 to
// weights.size(); share r is [boundaries[r], boundaries[r + 1]). Boundary r is the item boundary
// nearest to where the weight before it is r / parts of the total; with no weight at all the
// items are split evenly by count.
std::vector<int> weighted_shares(const std::vector<std::uint64_t>& weights, int parts);

// The ranks of this process's run: one process unless set_process_ranks installed others (the
// command does, under mpirun).
Ranks& process_ranks();
void set_process_ranks(Ranks* ranks);

}  // namespace relume
