// The Python exceptions of the relume module and how C++ errors become them:
//   relume.Error (a ValueError)      every relume::Error, with relume's message;
//   relume.FileError (relume.Error and OSError)  an Error of a function that reads or writes a
//                                    file (load, open, save, read_image, ...): the file is
//                                    missing, unreadable or not what it should be;
//   KeyboardInterrupt                relume::Interrupted: long work stopped on request.
#pragma once

#include <pybind11/pybind11.h>

#include <relume/error.hpp>
#include <string>
#include <utility>

namespace relume::python {

namespace py = pybind11;

// A relume::Error that names a file: raised as relume.FileError.
class FileError : public Error {
 public:
  using Error::Error;
};

// Runs `work`, turning its relume::Error (not Interrupted) into FileError.
template <class Work>
auto with_file_errors(Work&& work) -> decltype(work()) {
  try {
    return std::forward<Work>(work)();
  } catch (const Interrupted&) {
    throw;
  } catch (const Error& error) {
    throw FileError(error.what());
  }
}

// Creates relume.Error and relume.FileError in `module` and registers the translations.
void bind_errors(py::module_& module);

}  // namespace relume::python
