// Implementation of the temp-file + fsync + rename writers.
#include "core/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <relume/error.hpp>
#include <sstream>

#include "core/interruption.hpp"
#include "core/temporary_files.hpp"

namespace relume {
namespace fs = std::filesystem;

namespace {

std::string system_reason() { return std::strerror(errno); }

void fsync_path(const fs::path& path, const fs::path& target) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) throw Error("cannot open " + path.string() + " to flush " + target.string());
  const int rc = ::fsync(fd);
  const std::string reason = system_reason();
  ::close(fd);
  if (rc != 0) throw Error("cannot write " + target.string() + ": " + reason);
}

fs::path folder_of(const fs::path& target) {
  return target.has_parent_path() ? target.parent_path() : fs::path(".");
}

void rename_or_throw(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  fs::rename(from, to, ec);
  if (ec)
    throw Error("cannot rename " + from.string() + " to " + to.string() + ": " + ec.message());
}

// Why this process cannot create a file in `folder`, or "" when it can. access() answers yes for
// root in folders that take no new files (/proc), so a probe file is made and removed; it is
// registered meanwhile, so that a signal handler removes it too.
std::string why_folder_takes_no_files(const fs::path& folder) {
  const fs::path probe = temporary_path_for(folder / "write-probe");
  const TemporaryPathRegistration registration(probe, TemporaryPathRegistration::Kind::file);
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0) return errno == EEXIST ? "" : system_reason();
  ::close(fd);
  ::unlink(probe.c_str());
  return "";
}

}  // namespace

void check_output_file_location(const fs::path& target) {
  const fs::path parent = folder_of(target);
  if (!fs::is_directory(parent))
    throw Error("cannot write " + target.string() + ": " +
                (fs::exists(parent) ? parent.string() + " is a file, not a folder"
                                    : "folder " + parent.string() + " does not exist"));
  if (fs::is_directory(target)) throw Error("cannot write " + target.string() + ": it is a folder");
  if (const std::string why = why_folder_takes_no_files(parent); !why.empty())
    throw Error("cannot write " + target.string() + ": folder " + parent.string() +
                " is not writable (" + why + ")");
}

void check_output_folder_location(const fs::path& folder) {
  if (fs::exists(folder) && !fs::is_directory(folder))
    throw Error("cannot write the folder " + folder.string() + ": a file of that name exists");
  fs::path existing = fs::absolute(folder).lexically_normal();
  while (!fs::exists(existing) && existing.has_parent_path() && existing != existing.parent_path())
    existing = existing.parent_path();
  if (!fs::is_directory(existing))
    throw Error("cannot write the folder " + folder.string() + ": " + existing.string() +
                " is not a folder");
  if (const std::string why = why_folder_takes_no_files(existing); !why.empty())
    throw Error("cannot write the folder " + folder.string() + ": folder " + existing.string() +
                " is not writable (" + why + ")");
}

void write_atomically(const fs::path& target, const std::function<void(const fs::path&)>& write) {
  check_output_file_location(target);
  remove_stale_temporaries(target);
  const fs::path temp = temporary_path_for(target);
  const TemporaryPathRegistration registration(temp, TemporaryPathRegistration::Kind::file);
  try {
    write(temp);
    fsync_path(temp, target);
    throw_if_interrupted();
    rename_or_throw(temp, target);
  } catch (...) {
    std::error_code ignored;
    fs::remove(temp, ignored);
    throw;
  }
}

void write_file_atomically(const fs::path& target, const std::string& bytes) {
  write_atomically(target, [&](const fs::path& temp) {
    const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) throw Error("cannot write " + target.string() + ": " + system_reason());
    for (std::size_t done = 0; done < bytes.size();) {
      const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        const std::string reason = n < 0 ? system_reason() : "nothing written";
        ::close(fd);
        throw Error("cannot write " + target.string() + ": " + reason);
      }
      done += std::size_t(n);
    }
    if (::close(fd) != 0) throw Error("cannot write " + target.string() + ": " + system_reason());
  });
}

void write_folder_atomically(const fs::path& target_path,
                             const std::function<void(const fs::path&)>& write) {
  fs::path target = target_path.lexically_normal();
  if (target.filename().empty()) target = target.parent_path();  // "out/" is the folder "out"
  check_output_folder_location(target);
  const fs::path parent = folder_of(target);
  std::error_code ec;
  fs::create_directories(parent, ec);
  if (ec) throw Error("cannot create the folder " + parent.string() + ": " + ec.message());
  remove_stale_temporaries(target);
  const fs::path temp = temporary_path_for(target);
  const TemporaryPathRegistration registration(temp, TemporaryPathRegistration::Kind::folder);
  try {
    fs::create_directory(temp, ec);
    if (ec) throw Error("cannot create a folder in " + parent.string() + ": " + ec.message());
    write(temp);
    throw_if_interrupted();
    if (!fs::exists(target)) {
      rename_or_throw(temp, target);
      return;
    }
    for (const fs::directory_entry& entry : fs::directory_iterator(temp)) {
      // A folder replaces the folder of its name whole (a rename cannot replace a non-empty one).
      const fs::path replaced = target / entry.path().filename();
      if (entry.is_directory() && fs::is_directory(replaced)) {
        fs::remove_all(replaced, ec);
        if (ec) throw Error("cannot replace the folder " + replaced.string() + ": " + ec.message());
      }
      rename_or_throw(entry.path(), replaced);
    }
    fs::remove(temp);
  } catch (...) {
    std::error_code ignored;
    fs::remove_all(temp, ignored);
    throw;
  }
}

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot open " + path.string());
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw Error("cannot read " + path.string());
  return buffer.str();
}

}  // namespace relume
