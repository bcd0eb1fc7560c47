// NumPy arrays in and out of the relume module. In: every array a user hands in is checked (kind
// of dtype, shape, finite values) and refused with a relume::Error that names the argument, the
// index at fault and what was expected. Out: views of C++ memory that keep their owner alive
// (read-only, so a view cannot make a field inconsistent), or arrays that take over a C++ vector
// without copying it.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstdint>
#include <relume/field.hpp>
#include <relume/image.hpp>
#include <string>
#include <utility>
#include <vector>

namespace relume::python {

namespace py = pybind11;

using Shape = std::vector<py::ssize_t>;

// A read-only array over `data` (C order, `shape`) whose base is `owner`, which it keeps alive.
template <class T>
py::array readonly_view(const T* data, Shape shape, py::handle owner) {
  py::array view(py::dtype::of<T>(), std::move(shape), {}, data, owner);
  view.attr("setflags")(py::arg("write") = false);
  return view;
}

// An array (C order, `shape`) that owns `values` from now on: no copy is made.
template <class T>
py::array adopt_vector(std::vector<T>&& values, Shape shape) {
  auto* owned = new std::vector<T>(std::move(values));
  py::capsule free_when_done(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array(py::dtype::of<T>(), std::move(shape), {}, owned->data(), free_when_done);
}

// An image as an array (height, width, channels) that takes over its pixels.
py::array adopt_image(Image&& image);

// Which dtypes an argument accepts.
enum class Accepted {
  float32,       // big arrays, used as they are: any other dtype is refused
  float32or64,   // matrices relume computes on in double (factor)
  real_numbers,  // small arrays: any integer or floating dtype, converted
  integers,      // masks: bool or any integer dtype
};

// `object` as an array of `shape` (-1: any length) after checking its dtype and shape; `what`
// names the argument and `layout` its expected shape in messages ("(lights, 3)").
py::array checked_array(py::handle object, const std::string& what, Accepted accepted,
                        const Shape& shape, const std::string& layout);

using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;
using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

// The values of `array` (checked_array'd) as a C-contiguous float or double array (the array
// itself when it already is one), every value checked finite: the first that is not is named by
// its index.
FloatArray finite_float32(const py::array& array, const std::string& what);
DoubleArray finite_float64(const py::array& array, const std::string& what);

// (lights, 3) arrays: light directions (normalised to unit length like a light file's; a zero or
// non-finite row is refused), and RGB per light (light vectors, intensities).
LightDirections directions_from(py::handle object, const std::string& what);
LightRgb rgb_rows_from(py::handle object, const std::string& what, py::ssize_t lights = -1);
// A batch of light vectors: (count, lights, 3).
std::vector<LightRgb> rgb_batch_from(py::handle object, const std::string& what,
                                     py::ssize_t lights);

// A field from arrays: values (height, width, channels, lights) float32, copied once; dirs
// (lights, 3); mask (height, width) or None (all inside); intensities (lights, 3) or None (ones).
ReflectanceField field_from(py::handle values, py::handle dirs, py::handle mask,
                            py::handle intensities);

// A (height, width) or (height, width, channels) array of real numbers as an Image.
Image image_from(py::handle object, const std::string& what);

// A (height, width) mask: any integer or bool dtype, non-zero = inside.
std::vector<std::uint8_t> mask_from(py::handle object, const std::string& what, int width,
                                    int height);

}  // namespace relume::python
