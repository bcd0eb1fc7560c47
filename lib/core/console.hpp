// What relume says on the terminal besides its results: one process-wide verbosity that the
// command's global -q/--quiet and -v/--verbose set, honoured by progress bars, notes and details
// (RELUME_QUIET=1 in the environment silences only the progress bars: lib/core/progress.hpp).
// Results a command was asked for (info's description, a JSON file, images) are not messages and
// are written whatever the verbosity.
#pragma once

namespace relume {

enum class Verbosity { quiet, normal, verbose };

// Starts as normal.
Verbosity verbosity();
void set_verbosity(Verbosity level);

// printf-style lines, each with a newline added: a summary of what a command did on stdout unless
// quiet; a note on stderr unless quiet (what was loaded, written, chosen); a detail on stderr
// only when verbose (settings as resolved, timings per phase).
[[gnu::format(printf, 1, 2)]] void say(const char* format, ...);
[[gnu::format(printf, 1, 2)]] void note(const char* format, ...);
[[gnu::format(printf, 1, 2)]] void detail(const char* format, ...);

}  // namespace relume
