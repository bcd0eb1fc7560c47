// Implementation of the temp-file + fsync + rename writer.
#include "core/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <fstream>
#include <relume/error.hpp>
#include <sstream>

namespace relume {
namespace fs = std::filesystem;

namespace {
void fsync_path(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) throw Error("cannot open " + path.string() + " to flush it to disk");
  const int rc = ::fsync(fd);
  ::close(fd);
  if (rc != 0) throw Error("cannot flush " + path.string() + " to disk");
}
}  // namespace

void write_atomically(const fs::path& target, const std::function<void(const fs::path&)>& write) {
  const fs::path parent = target.has_parent_path() ? target.parent_path() : fs::path(".");
  if (!fs::is_directory(parent))
    throw Error("cannot write " + target.string() + ": folder " + parent.string() +
                " does not exist");
  // Keep the extension last: image writers choose the format from it.
  const fs::path temp =
      parent / (".tmp-" + std::to_string(::getpid()) + "-" + target.filename().string());
  try {
    write(temp);
    fsync_path(temp);
    std::error_code ec;
    fs::rename(temp, target, ec);
    if (ec)
      throw Error("cannot rename " + temp.string() + " to " + target.string() + ": " +
                  ec.message());
  } catch (...) {
    std::error_code ignored;
    fs::remove(temp, ignored);
    throw;
  }
}

void write_file_atomically(const fs::path& target, const std::string& bytes) {
  write_atomically(target, [&](const fs::path& temp) {
    std::ofstream out(temp, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.close();
    if (!out) throw Error("cannot write " + target.string());
  });
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
