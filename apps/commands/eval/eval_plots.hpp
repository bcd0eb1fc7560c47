// The plots of `relume eval`: scripts/plot_eval.py, embedded into the command at build time
// (cmake/embed_text.cmake, apps/CMakeLists.txt), copied into the output folder and run there
// with Python 3 and matplotlib.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace relume {

// The text of scripts/plot_eval.py.
const std::string& eval_plot_script();

// The PNG files the script draws, by name.
const std::vector<std::string>& eval_plot_files();

// Writes DIR/plot_eval.py and runs it on DIR with RELUME_PYTHON from the environment when set,
// else the Python 3 the build found. Throws Error when it cannot run or fails, saying what it
// needs (python3-matplotlib).
void draw_eval_plots(const std::filesystem::path& directory);

}  // namespace relume
