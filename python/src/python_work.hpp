// Long library work called from Python (compress, factor): run with the GIL released, its
// progress told to a Python callback, and Ctrl-C honoured.
//
// The work runs on the calling thread. Its ProgressReporters tell listener() (given to the work as
// its progress callback or through a ProgressListenerScope) at most every 0.1 s, on that thread:
// the GIL is taken, the Python callback (if any) is called with (phase, fraction), and
// PyErr_CheckSignals runs Python's signal handlers (Ctrl-C raises KeyboardInterrupt there when the
// caller is the main thread). A Python exception from either is kept and an interruption is
// requested (lib/core/interruption.hpp): the library unwinds at its next check and returns
// nothing. run() then clears the request and raises the kept exception, with the GIL back. The
// request is process-wide: relume work running on other threads at that moment may stop too.
#pragma once

#include <pybind11/pybind11.h>

#include <exception>
#include <optional>
#include <string>

#include "core/interruption.hpp"
#include "core/progress.hpp"

namespace relume::python {

namespace py = pybind11;

class PythonProgress {
 public:
  // callback: a callable (phase: str, fraction: float), or None to only watch for signals.
  explicit PythonProgress(py::object callback);
  PythonProgress(const PythonProgress&) = delete;
  PythonProgress& operator=(const PythonProgress&) = delete;

  // To be called by the work only (it refers to this object).
  ProgressListener listener();

  // Runs work() with the GIL released; called with the GIL held.
  template <class Work>
  auto run(Work&& work) -> decltype(work());

 private:
  void tell(const std::string& phase, double fraction);

  py::object callback_;
  std::optional<py::error_already_set> raised_;
};

template <class Work>
auto PythonProgress::run(Work&& work) -> decltype(work()) {
  std::optional<decltype(work())> result;
  std::exception_ptr failure;
  {
    py::gil_scoped_release released;
    try {
      result.emplace(work());
    } catch (...) {
      failure = std::current_exception();
    }
  }
  if (raised_) {
    // Raised even when the work finished before it noticed: the caller asked to stop.
    clear_interruption();
    py::error_already_set raised = std::move(*raised_);
    raised_.reset();
    throw raised;
  }
  if (failure) std::rethrow_exception(failure);
  return std::move(*result);
}

}  // namespace relume::python
