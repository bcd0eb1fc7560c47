// Implementation of the relume module's exceptions (see errors.hpp).
#include "errors.hpp"

namespace relume::python {

void bind_errors(py::module_& module) {
  // Raw and never released: the classes live as long as the interpreter, and a C++ static that
  // released them would run after it has finalized.
  static PyObject* const error = PyErr_NewExceptionWithDoc(
      "relume.Error",
      "A relume error: bad input (an option, an array, a value) or failed work. The message "
      "names the argument, file, line or value at fault and what was expected.",
      PyExc_ValueError, nullptr);
  if (!error) throw py::error_already_set();
  const py::tuple bases = py::make_tuple(py::handle(error), py::handle(PyExc_OSError));
  static PyObject* const file_error = PyErr_NewExceptionWithDoc(
      "relume.FileError",
      "A relume error about a file (missing, unreadable, not what it should be, or not "
      "writable): both a relume.Error and an OSError.",
      bases.ptr(), nullptr);
  if (!file_error) throw py::error_already_set();
  module.attr("Error") = py::handle(error);
  module.attr("FileError") = py::handle(file_error);
  py::register_exception_translator([](std::exception_ptr thrown) {
    try {
      if (thrown) std::rethrow_exception(thrown);
    } catch (const Interrupted& interrupted) {
      PyErr_SetString(PyExc_KeyboardInterrupt, interrupted.what());
    } catch (const FileError& failure) {
      PyErr_SetString(file_error, failure.what());
    } catch (const Error& failure) {
      PyErr_SetString(error, failure.what());
    }
  });
}

}  // namespace relume::python
