// Implementation of the memory budget (see memory_budget.hpp).
#include "core/memory_budget.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <atomic>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <relume/error.hpp>
#include <sstream>

#include "core/text_numbers.hpp"

namespace relume {
namespace {

std::atomic<std::uint64_t> limit{0};

constexpr std::uint64_t unknown = std::numeric_limits<std::uint64_t>::max();

std::uint64_t mem_available() {
  std::ifstream in("/proc/meminfo");
  for (std::string key; in >> key;) {
    std::uint64_t kilobytes = 0;
    in >> kilobytes;
    if (key == "MemAvailable:") return kilobytes * 1024;
    in.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
  }
  return unknown;
}

// A cgroup v2 file holding a number or "max"; `unknown` when absent or "max".
std::uint64_t cgroup_value(const std::string& name) {
  std::ifstream in("/sys/fs/cgroup/" + name);
  std::string text;
  if (!(in >> text) || text == "max") return unknown;
  const auto value = parse_unsigned(text);
  return value ? *value : unknown;
}

std::uint64_t cgroup_free() {
  const std::uint64_t max = cgroup_value("memory.max");
  if (max == unknown) return unknown;
  const std::uint64_t current = cgroup_value("memory.current");
  return current == unknown || current >= max ? 0 : max - current;
}

// The process's mapped bytes (for the address-space limit) from /proc/self/statm.
std::uint64_t mapped_bytes() {
  std::ifstream in("/proc/self/statm");
  std::uint64_t pages = 0;
  in >> pages;
  return pages * std::uint64_t(::sysconf(_SC_PAGESIZE));
}

std::uint64_t rlimit_free(int resource) {
  rlimit value{};
  if (::getrlimit(resource, &value) != 0 || value.rlim_cur == RLIM_INFINITY) return unknown;
  const std::uint64_t used = mapped_bytes();
  return used >= value.rlim_cur ? 0 : value.rlim_cur - used;
}

}  // namespace

void set_memory_limit(std::uint64_t bytes) noexcept { limit.store(bytes); }

MemoryBudget memory_budget() {
  if (const std::uint64_t set = limit.load()) return {set, "--memory-limit"};
  MemoryBudget budget{unknown, "no limit known"};
  for (const auto& [bytes, source] :
       {std::pair{mem_available(), "MemAvailable"}, std::pair{cgroup_free(), "the cgroup limit"},
        std::pair{rlimit_free(RLIMIT_AS), "ulimit -v"},
        std::pair{rlimit_free(RLIMIT_DATA), "ulimit -d"}})
    if (bytes < budget.bytes) budget = {bytes, source};
  return budget;
}

std::uint64_t resident_memory_bytes() {
  std::ifstream in("/proc/self/statm");
  std::uint64_t pages = 0, resident = 0;
  in >> pages >> resident;
  return resident * std::uint64_t(::sysconf(_SC_PAGESIZE));
}

std::string byte_size_text(std::uint64_t bytes) {
  char text[32];
  if (bytes < 1024) return std::to_string(bytes) + " bytes";
  const char* units[] = {"KB", "MB", "GB", "TB", "PB", "EB"};
  double value = double(bytes) / 1024;
  int unit = 0;
  while (value >= 1024 && unit < 5) value /= 1024, ++unit;
  std::snprintf(text, sizeof text, "%.1f %s", value, units[unit]);
  return text;
}

void check_memory_need(std::uint64_t bytes, const std::string& what) {
  const MemoryBudget budget = memory_budget();
  if (bytes <= budget.bytes) return;
  throw Error(what + " needs about " + byte_size_text(bytes) + ", more than the " +
              byte_size_text(budget.bytes) + " available (" + budget.source +
              "); free memory or set --memory-limit if the estimate is too cautious");
}

std::uint64_t parse_byte_size(const std::string& text) {
  std::size_t end = 0;
  while (end < text.size() &&
         (std::isdigit(static_cast<unsigned char>(text[end])) || text[end] == '.'))
    ++end;
  const auto number = parse_finite_double(text.substr(0, end));
  std::string unit = text.substr(end);
  for (char& c : unit) c = char(std::toupper(static_cast<unsigned char>(c)));
  if (unit.ends_with("IB")) unit.erase(unit.size() - 2, 1);
  if (unit.size() == 2 && unit[1] == 'B') unit.pop_back();
  const std::string powers = "KMGT";
  const std::size_t power = unit.empty() ? 0 : powers.find(unit[0]) + 1;
  if (!number || *number < 0 || unit.size() > 1 || (!unit.empty() && unit != "B" && power == 0))
    throw Error("'" + text + "' is not a size in bytes (expected for example 8G, 512M or 1000000)");
  const double bytes = *number * std::pow(1024.0, unit == "B" ? 0.0 : double(power));
  if (!(bytes >= 1 && bytes < 1.8e19))
    throw Error("'" + text + "' is not a size between 1 byte and 16 EB");
  return std::uint64_t(bytes);
}

}  // namespace relume
