// A dynamic parallel loop over [0, count): worker threads take the next indices from an atomic
// counter (one at a time when there are few, in runs when there are many), so uneven work (LP
// solves, image decodes) balances itself. The first exception thrown by any worker stops the loop
// and is rethrown on the calling thread. Starting threads fails soft: when the system refuses a
// thread (a memory or process limit), the loop runs on the workers it has, the calling thread at
// least.
#pragma once

#include <cstddef>
#include <functional>

namespace relume {

// The most worker threads a user may ask for (`--threads`): far above any machine's cores, far
// below what exhausts a process's memory for thread stacks.
inline constexpr unsigned max_worker_threads = 1024;

// Number of worker threads to use when the user asked for `requested` (0 = all cores). Throws
// Error naming the value when it is above max_worker_threads.
unsigned resolve_thread_count(unsigned requested);

// The cores the calling thread may run on (its affinity: mpirun binds a rank to its own cores).
unsigned cores_of_this_thread();

// Calls body(index, worker) for every index; worker is in [0, threads) and lets a body keep
// per-thread state (for example one GLPK problem per worker).
void parallel_for(std::size_t count, unsigned threads,
                  const std::function<void(std::size_t index, unsigned worker)>& body);

}  // namespace relume
