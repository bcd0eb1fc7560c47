// The parts of the relume Python module, each defined in its own *_bindings.cpp and added to the
// module by module.cpp.
#pragma once

#include <pybind11/pybind11.h>

namespace relume::python {

namespace py = pybind11;

void bind_images(py::module_& module);      // read_image, write_image
void bind_field(py::module_& module);       // Field, load
void bind_lighting(py::module_& module);    // light_vector, sky
void bind_compressed(py::module_& module);  // Compressed, open, relative_error
void bind_compress(py::module_& module);    // compress
void bind_factor(py::module_& module);      // factor

}  // namespace relume::python
