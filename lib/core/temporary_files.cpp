// Implementation of the temporary-path registry and the stale-temporary cleanup.
#include "core/temporary_files.hpp"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <string>
#include <system_error>

namespace relume {
namespace fs = std::filesystem;

namespace {

constexpr int slot_count = 256;
constexpr std::size_t slot_path_bytes = 1024;

// A slot is a seqlock: `version` is odd while the owner writes the path, so a handler that reads
// a slot uses the path only when the version was even and unchanged around its copy.
struct Slot {
  std::atomic<bool> taken{false};
  std::atomic<unsigned> version{0};
  std::atomic<bool> folder{false};
  std::atomic<bool> live{false};
  char path[slot_path_bytes];
};
static_assert(std::atomic<bool>::is_always_lock_free && std::atomic<unsigned>::is_always_lock_free);

Slot slots[slot_count];

constexpr std::string_view prefix = ".tmp-";

// The pid of a `.tmp-<pid>-<target name>` entry, or 0 when `name` is not one for `target_name`.
pid_t temporary_owner(const std::string& name, const std::string& target_name) {
  if (name.size() <= prefix.size() + target_name.size() + 1 || !name.starts_with(prefix) ||
      !name.ends_with("-" + target_name))
    return 0;
  const char* first = name.data() + prefix.size();
  const char* last = name.data() + name.size() - target_name.size() - 1;
  pid_t pid = 0;
  const auto [end, error] = std::from_chars(first, last, pid);
  return error == std::errc() && end == last && pid > 0 ? pid : 0;
}

bool process_runs(pid_t pid) { return ::kill(pid, 0) == 0 || errno != ESRCH; }

}  // namespace

fs::path temporary_path_for(const fs::path& target) {
  const fs::path parent = target.has_parent_path() ? target.parent_path() : fs::path(".");
  // Keep the target's name last: image writers choose the format from the extension.
  return parent /
         (std::string(prefix) + std::to_string(::getpid()) + "-" + target.filename().string());
}

TemporaryPathRegistration::TemporaryPathRegistration(const fs::path& path, Kind kind) {
  const std::string text = fs::absolute(path).string();
  if (text.size() >= slot_path_bytes) return;
  for (int s = 0; s < slot_count; ++s) {
    bool expected = false;
    if (!slots[s].taken.compare_exchange_strong(expected, true)) continue;
    Slot& slot = slots[s];
    slot.version.fetch_add(1);  // odd: being written
    std::memcpy(slot.path, text.c_str(), text.size() + 1);
    slot.folder.store(kind == Kind::folder);
    slot.live.store(true);
    slot.version.fetch_add(1);  // even: complete
    slot_ = s;
    return;
  }
}

TemporaryPathRegistration::~TemporaryPathRegistration() {
  if (slot_ < 0) return;
  Slot& slot = slots[slot_];
  slot.version.fetch_add(1);
  slot.live.store(false);
  slot.version.fetch_add(1);
  slot.taken.store(false);
}

void remove_registered_temporaries() noexcept {
  for (bool folders : {false, true})
    for (Slot& slot : slots) {
      char path[slot_path_bytes];
      const unsigned before = slot.version.load();
      if (before % 2 != 0 || !slot.live.load() || slot.folder.load() != folders) continue;
      std::memcpy(path, slot.path, slot_path_bytes);
      path[slot_path_bytes - 1] = '\0';
      if (slot.version.load() != before) continue;
      if (folders)
        ::rmdir(path);
      else
        ::unlink(path);
    }
}

void remove_stale_temporaries(const fs::path& target) noexcept {
  try {
    const fs::path parent = target.has_parent_path() ? target.parent_path() : fs::path(".");
    const std::string target_name = target.filename().string();
    std::error_code ec;
    for (fs::directory_iterator it(parent, ec), end; !ec && it != end; it.increment(ec)) {
      const pid_t owner = temporary_owner(it->path().filename().string(), target_name);
      if (owner == 0 || owner == ::getpid() || process_runs(owner)) continue;
      std::error_code ignored;
      fs::remove_all(it->path(), ignored);
    }
  } catch (...) {
    // Cleanup is best effort: a folder that cannot be listed keeps its stale files.
  }
}

}  // namespace relume
