// The memory budget of one run: before a big allocation (a field, a reconstruction, a decoded
// container, an output image) the work estimates what it needs and refuses with the numbers when
// that is more than the budget, instead of ending in std::bad_alloc or the kernel's OOM killer.
// The budget is --memory-limit when given, else what the system says is available: the least of
// MemAvailable (/proc/meminfo), the cgroup's memory.max less its memory.current, and the address
// space and data segment limits (ulimit -v / -d) less what the process already maps.
#pragma once

#include <cstdint>
#include <string>

namespace relume {

// Sets the budget (bytes); 0 goes back to the available memory.
void set_memory_limit(std::uint64_t bytes) noexcept;

struct MemoryBudget {
  std::uint64_t bytes = 0;
  std::string source;  // "--memory-limit", "MemAvailable", "the cgroup limit", "ulimit -v", ...
};
MemoryBudget memory_budget();

// Throws Error("<what> needs about 12.3 GB, more than the 4.1 GB available (MemAvailable); ...")
// when `bytes` is above the budget.
void check_memory_need(std::uint64_t bytes, const std::string& what);

// The process's resident memory now (/proc/self/statm): its code, libraries and data.
std::uint64_t resident_memory_bytes();

// "1.5 GB", "640 MB", "12 KB", "100 bytes".
std::string byte_size_text(std::uint64_t bytes);

// "8G", "512M", "2.5GB", "1000000" (bytes; K, M, G, T are powers of 1024, an optional B or iB
// follows). Throws Error naming the text.
std::uint64_t parse_byte_size(const std::string& text);

}  // namespace relume
