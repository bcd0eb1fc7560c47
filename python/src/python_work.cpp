// Implementation of PythonProgress (see python_work.hpp).
#include "python_work.hpp"

#include <relume/error.hpp>

namespace relume::python {

PythonProgress::PythonProgress(py::object callback) : callback_(std::move(callback)) {
  if (!callback_.is_none() && !PyCallable_Check(callback_.ptr()))
    throw Error("progress must be a callable progress(phase: str, fraction: float) or None, got " +
                std::string(py::str(py::type::handle_of(callback_).attr("__name__"))));
}

ProgressListener PythonProgress::listener() {
  return [this](const std::string& phase, double fraction) { tell(phase, fraction); };
}

void PythonProgress::tell(const std::string& phase, double fraction) {
  py::gil_scoped_acquire held;
  if (raised_) return;  // already stopping
  try {
    if (!callback_.is_none()) callback_(phase, fraction);
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
  } catch (py::error_already_set& raised) {
    raised_.emplace(std::move(raised));
    request_interruption();
  }
}

}  // namespace relume::python
