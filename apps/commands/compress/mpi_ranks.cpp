// The MPI ranks of `mpirun -n N relume ...` (see mpi_ranks.hpp). Messages go in chunks of at most
// 256 MB (MPI counts are ints); every exchange is timed and its bytes counted for the report.
// Every exchange starts with all ranks arriving at a barrier that sleeps between polls: OpenMPI's
// blocking calls poll without pause, so a rank waiting for the root (while the root clusters the
// sample on the cores of every rank on its machine, or writes the file) would hold a core the
// root could use. Once all have arrived, the transfers run blocking, at full speed.
#include "commands/compress/mpi_ranks.hpp"

#include <mpi.h>
#include <sched.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <relume/error.hpp>
#include <thread>

#include "core/elapsed_time.hpp"
#include "core/ranks.hpp"

namespace relume {
namespace {

constexpr std::size_t chunk_bytes = std::size_t(1) << 28;

class MpiRanks final : public Ranks {
 public:
  MpiRanks() {
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
    MPI_Comm local;
    MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &local);
    MPI_Comm_size(local, &local_size_);
    // This rank's cores (mpirun usually binds it to one) and those of every rank on its machine.
    CPU_ZERO(&own_cores_);
    CPU_ZERO(&local_cores_);
    if (sched_getaffinity(0, sizeof own_cores_, &own_cores_) == 0) {
      std::vector<cpu_set_t> cores(static_cast<std::size_t>(local_size_));
      MPI_Allgather(&own_cores_, sizeof(cpu_set_t), MPI_BYTE, cores.data(), sizeof(cpu_set_t),
                    MPI_BYTE, local);
      for (cpu_set_t& rank_cores : cores) CPU_OR(&local_cores_, &local_cores_, &rank_cores);
    }
    MPI_Comm_free(&local);
  }
  int rank() const override { return rank_; }
  int size() const override { return size_; }
  int local_size() const override { return local_size_; }

  void use_local_cores(bool all) override {
    if (CPU_COUNT(&own_cores_) > 0)
      sched_setaffinity(0, sizeof(cpu_set_t), all ? &local_cores_ : &own_cores_);
  }

  void sum_to_root(double* values, std::size_t count) override {
    const Timer timer(this);
    arrive();
    for (std::size_t done = 0; done < count;) {
      const int n = int(std::min(count - done, chunk_bytes / sizeof(double)));
      MPI_Reduce(rank_ == 0 ? MPI_IN_PLACE : values + done, values + done, n, MPI_DOUBLE, MPI_SUM,
                 0, MPI_COMM_WORLD);
      if (rank_ != 0) sent_ += std::uint64_t(n) * sizeof(double);
      done += std::size_t(n);
    }
  }

  void sum_everywhere(double* values, std::size_t count) override {
    const Timer timer(this);
    arrive();
    for (std::size_t done = 0; done < count;) {
      const int n = int(std::min(count - done, chunk_bytes / sizeof(double)));
      MPI_Allreduce(MPI_IN_PLACE, values + done, n, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
      if (size_ > 1) sent_ += std::uint64_t(n) * sizeof(double);
      done += std::size_t(n);
    }
  }

  void broadcast(std::string& bytes) override {
    const Timer timer(this);
    arrive();
    std::uint64_t size = bytes.size();
    MPI_Bcast(&size, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
    bytes.resize(size);
    for (std::size_t done = 0; done < size;) {
      const int n = int(std::min<std::size_t>(size - done, chunk_bytes));
      MPI_Bcast(bytes.data() + done, n, MPI_CHAR, 0, MPI_COMM_WORLD);
      done += std::size_t(n);
    }
    if (rank_ == 0) sent_ += size * std::uint64_t(size_ - 1);
  }

  std::vector<std::string> gather_to_root(const std::string& bytes) override {
    const Timer timer(this);
    arrive();
    std::vector<std::string> parts;
    if (rank_ != 0) {
      send(bytes, 0);
      return parts;
    }
    parts.push_back(bytes);
    for (int from = 1; from < size_; ++from) parts.push_back(receive(from));
    return parts;
  }

  std::string scatter_from_root(std::vector<std::string> parts) override {
    const Timer timer(this);
    arrive();
    if (rank_ != 0) return receive(0);
    for (int to = 1; to < size_; ++to) send(parts.at(std::size_t(to)), to);
    return std::move(parts.at(0));
  }

  // Pairwise: at step d every rank sends to the rank d after it and receives from the one d
  // before, both at once, so that no two ranks wait on each other.
  std::vector<std::string> exchange(std::vector<std::string> to) override {
    const Timer timer(this);
    arrive();
    std::vector<std::string> from(static_cast<std::size_t>(size_));
    from[std::size_t(rank_)] = std::move(to.at(std::size_t(rank_)));
    for (int d = 1; d < size_; ++d) {
      const int to_rank = (rank_ + d) % size_, from_rank = (rank_ - d + size_) % size_;
      const std::string& out = to.at(std::size_t(to_rank));
      std::string& in = from[std::size_t(from_rank)];
      std::uint64_t out_size = out.size(), in_size = 0;
      MPI_Sendrecv(&out_size, 1, MPI_UINT64_T, to_rank, 1, &in_size, 1, MPI_UINT64_T, from_rank, 1,
                   MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      in.resize(in_size);
      // Each side cuts its own message into the same chunks.
      std::vector<MPI_Request> requests;
      for (std::size_t done = 0; done < out_size; done += chunk_bytes)
        MPI_Isend(out.data() + done, int(std::min<std::size_t>(out_size - done, chunk_bytes)),
                  MPI_CHAR, to_rank, 1, MPI_COMM_WORLD, &requests.emplace_back());
      for (std::size_t done = 0; done < in_size; done += chunk_bytes)
        MPI_Irecv(in.data() + done, int(std::min<std::size_t>(in_size - done, chunk_bytes)),
                  MPI_CHAR, from_rank, 1, MPI_COMM_WORLD, &requests.emplace_back());
      MPI_Waitall(int(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
      sent_ += out_size;
    }
    return from;
  }

  std::uint64_t bytes_sent() const override { return sent_; }
  double exchange_seconds() const override { return exchange_seconds_; }

 private:
  // Bytes to one rank: their size, then chunks.
  void send(const std::string& bytes, int to) {
    std::uint64_t size = bytes.size();
    MPI_Send(&size, 1, MPI_UINT64_T, to, 0, MPI_COMM_WORLD);
    for (std::size_t done = 0; done < size;) {
      const int n = int(std::min<std::size_t>(size - done, chunk_bytes));
      MPI_Send(bytes.data() + done, n, MPI_CHAR, to, 0, MPI_COMM_WORLD);
      done += std::size_t(n);
    }
    sent_ += size;
  }

  // What send() sent from one rank.
  std::string receive(int from) {
    std::uint64_t size = 0;
    MPI_Recv(&size, 1, MPI_UINT64_T, from, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    std::string bytes(size, '\0');
    for (std::size_t done = 0; done < size;) {
      const int n = int(std::min<std::size_t>(size - done, chunk_bytes));
      MPI_Recv(bytes.data() + done, n, MPI_CHAR, from, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      done += std::size_t(n);
    }
    return bytes;
  }

  // Returns once every rank has called it: polls for 50 microseconds (ranks in step meet within
  // them), then sleeps between polls, each sleep twice the last, up to a millisecond.
  static void arrive() {
    using namespace std::chrono_literals;
    MPI_Request request;
    MPI_Ibarrier(MPI_COMM_WORLD, &request);
    const auto start = std::chrono::steady_clock::now();
    auto pause = 10us;
    for (int done = 0;;) {
      MPI_Test(&request, &done, MPI_STATUS_IGNORE);
      if (done) return;
      if (std::chrono::steady_clock::now() - start < 50us) continue;
      std::this_thread::sleep_for(pause);
      pause = std::min<std::chrono::microseconds>(2 * pause, 1000us);
    }
  }

  // Adds the time of one exchange to exchange_seconds_.
  struct Timer {
    explicit Timer(MpiRanks* ranks) : ranks_(ranks), start_(Clock::now()) {}
    ~Timer() { ranks_->exchange_seconds_ += seconds_since(start_); }
    MpiRanks* ranks_;
    Clock::time_point start_;
  };

  int rank_ = 0, size_ = 1, local_size_ = 1;
  cpu_set_t own_cores_, local_cores_;
  std::uint64_t sent_ = 0;
  double exchange_seconds_ = 0;
};

MpiRanks* installed = nullptr;

// Started by mpirun: OpenMPI's launcher, or a PMI one (Slurm, Hydra).
bool started_by_mpirun() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
    if (std::getenv(name)) return true;
  return false;
}

}  // namespace

MpiRun::MpiRun(int* argc, char*** argv) {
  if (!started_by_mpirun()) return;
  int provided = 0;
  MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided);
  // Errors end the job with a message rather than returning codes nobody checks.
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_ARE_FATAL);
  joined_ = true;
  installed = new MpiRanks;
  set_process_ranks(installed);
}

MpiRun::~MpiRun() {
  if (!joined_) return;
  set_process_ranks(nullptr);
  delete installed;
  installed = nullptr;
  MPI_Finalize();
}

bool MpiRun::several() const { return size() > 1; }
int MpiRun::rank() const { return process_ranks().rank(); }
int MpiRun::size() const { return process_ranks().size(); }

void MpiRun::abort_all(int code) {
  MPI_Abort(MPI_COMM_WORLD, code);
  std::exit(code);  // MPI_Abort does not return; this keeps [[noreturn]] honest
}

}  // namespace relume
