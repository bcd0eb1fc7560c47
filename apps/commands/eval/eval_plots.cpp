// Implementation of running the eval's plotting script (see eval_plots.hpp).
#include "commands/eval/eval_plots.hpp"

#include <spawn.h>
#include <sys/wait.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <relume/error.hpp>
#include <vector>

#include "core/atomic_file.hpp"

extern char** environ;

namespace relume {

#ifndef RELUME_PLOT_PYTHON
#define RELUME_PLOT_PYTHON "python3"
#endif

const std::vector<std::string>& eval_plot_files() {
  static const std::vector<std::string> files = {"error_vs_entries.png", "sparseness.png",
                                                 "error_ratio.png",      "error_difference.png",
                                                 "relighting.png",       "rate_distortion.png",
                                                 "compression_time.png", "relit_side_by_side.png"};
  return files;
}

void draw_eval_plots(const std::filesystem::path& directory) {
  const std::filesystem::path script = directory / "plot_eval.py";
  write_file_atomically(script, eval_plot_script());
  const char* from_environment = std::getenv("RELUME_PYTHON");
  const std::string python =
      from_environment && *from_environment ? from_environment : RELUME_PLOT_PYTHON;
  std::string script_text = script.string(), directory_text = directory.string();
  std::string python_text = python;
  std::vector<char*> argv = {python_text.data(), script_text.data(), directory_text.data(),
                             nullptr};
  pid_t child = 0;
  const int spawned = posix_spawnp(&child, python.c_str(), nullptr, nullptr, argv.data(), environ);
  if (spawned != 0)
    throw Error("cannot run " + python + " to draw the plots: " + std::strerror(spawned) +
                " (set RELUME_PYTHON, or give --no-plots; the CSV files are in " +
                directory.string() + ")");
  int status = 0;
  while (waitpid(child, &status, 0) < 0)
    if (errno != EINTR)
      throw Error("waiting for the plotting script failed: " + std::string(std::strerror(errno)));
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw Error(python + " " + script_text +
                " failed (it needs matplotlib and NumPy: Debian "
                "python3-matplotlib python3-numpy, see scripts/install_deps.sh); the CSV files "
                "are in " +
                directory.string() + " and the script can be rerun on them");
}

}  // namespace relume
