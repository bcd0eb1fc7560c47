// SIGINT and SIGTERM for the `relume` command. The handler only sets flags and unlinks registered
// temporary files, as a signal handler may:
//  - the first signal requests an interruption (core/interruption.hpp): long work stops at its
//    next check by throwing relume::Interrupted, atomic writes in progress discard their
//    temporary files as the exception unwinds, and checkpoints already written stay valid;
//  - a second signal (work that does not reach a check soon enough) unlinks the registered
//    temporary files (core/temporary_files.hpp) and exits at once.
// Either way the exit status is 128 + the signal number: 130 for SIGINT, 143 for SIGTERM.
#pragma once

namespace relume {

// Installs the handler for SIGINT and SIGTERM (with SA_RESTART, so system calls in progress go
// on).
void install_interruption_handlers();

// The signal that requested the interruption, or 0 when none came.
int interrupting_signal() noexcept;

}  // namespace relume
