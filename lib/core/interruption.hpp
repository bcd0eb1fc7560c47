// A process-wide request to stop long work, so that a Ctrl-C handler or a progress callback can
// end a compress (or any loop that reports progress) cleanly. request_interruption() only sets a
// lock-free atomic flag, so a signal handler may call it. Long loops call throw_if_interrupted()
// at points where stopping leaves nothing half done (ProgressReporter::advance does, and the
// clustering iterations between steps); it throws relume::Interrupted, which unwinds the work like
// any other Error. The flag stays set until clear_interruption(): whoever requested the
// interruption clears it once the interrupted work has returned.
#pragma once

namespace relume {

// Async-signal-safe.
void request_interruption() noexcept;
void clear_interruption() noexcept;
bool interruption_requested() noexcept;

// Throws relume::Interrupted (relume/error.hpp) when an interruption was requested.
void throw_if_interrupted();

}  // namespace relume
