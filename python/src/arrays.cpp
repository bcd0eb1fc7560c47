// Implementation of the array checks and conversions declared in arrays.hpp.
#include "arrays.hpp"

#include <cmath>
#include <relume/error.hpp>

namespace relume::python {
namespace {

std::string shape_text(const py::array& array) {
  std::string text = "(";
  for (py::ssize_t d = 0; d < array.ndim(); ++d)
    text += (d ? ", " : "") + std::to_string(array.shape(d));
  return text + (array.ndim() == 1 ? ",)" : ")");
}

// "[3, 4, 0]" for the element at C-order offset `offset` of `array`.
std::string index_text(const py::array& array, py::ssize_t offset) {
  std::vector<py::ssize_t> index(static_cast<std::size_t>(array.ndim()));
  for (py::ssize_t d = array.ndim() - 1; d >= 0; --d) {
    index[static_cast<std::size_t>(d)] = offset % array.shape(d);
    offset /= array.shape(d);
  }
  std::string text = "[";
  for (std::size_t d = 0; d < index.size(); ++d) text += (d ? ", " : "") + std::to_string(index[d]);
  return text + "]";
}

bool dtype_accepted(const py::dtype& dtype, Accepted accepted) {
  const char kind = dtype.kind();
  switch (accepted) {
    case Accepted::float32:
      return kind == 'f' && dtype.itemsize() == 4;
    case Accepted::float32or64:
      return kind == 'f' && (dtype.itemsize() == 4 || dtype.itemsize() == 8);
    case Accepted::real_numbers:
      return kind == 'f' || kind == 'i' || kind == 'u';
    case Accepted::integers:
      return kind == 'b' || kind == 'i' || kind == 'u';
  }
  return false;
}

std::string accepted_text(Accepted accepted) {
  switch (accepted) {
    case Accepted::float32:
      return "float32 (convert with .astype(numpy.float32))";
    case Accepted::float32or64:
      return "float32 or float64";
    case Accepted::real_numbers:
      return "real numbers (an integer or floating dtype)";
    case Accepted::integers:
      return "bool or integers";
  }
  return "";
}

template <class Values>
Values finite(const py::array& array, const std::string& what) {
  Values values = Values::ensure(array);
  if (!values) throw Error(what + ": the values cannot be converted to floating point");
  const auto* data = values.data();
  for (py::ssize_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(data[i]))
      throw Error(what + index_text(array, i) + " is " + std::to_string(data[i]) +
                  ": every value must be finite");
  }
  return values;
}

}  // namespace

py::array adopt_image(Image&& image) {
  const Shape shape{image.height, image.width, image.channels};
  return adopt_vector(std::move(image.pixels), shape);
}

py::array checked_array(py::handle object, const std::string& what, Accepted accepted,
                        const Shape& shape, const std::string& layout) {
  py::array array = py::array::ensure(object);
  if (!array)
    throw Error(what + " must be an array (or a sequence NumPy turns into one), got " +
                std::string(py::str(py::type::handle_of(object).attr("__name__"))));
  if (!dtype_accepted(array.dtype(), accepted))
    throw Error(what + " must hold " + accepted_text(accepted) + ", got dtype " +
                std::string(py::str(array.dtype())));
  bool fits = array.ndim() == static_cast<py::ssize_t>(shape.size());
  for (std::size_t d = 0; fits && d < shape.size(); ++d)
    fits = shape[d] < 0 || array.shape(static_cast<py::ssize_t>(d)) == shape[d];
  if (!fits) throw Error(what + " must have shape " + layout + ", got " + shape_text(array));
  return array;
}

FloatArray finite_float32(const py::array& array, const std::string& what) {
  return finite<FloatArray>(array, what);
}

DoubleArray finite_float64(const py::array& array, const std::string& what) {
  return finite<DoubleArray>(array, what);
}

LightDirections directions_from(py::handle object, const std::string& what) {
  const DoubleArray rows = finite_float64(
      checked_array(object, what, Accepted::real_numbers, {-1, 3}, "(lights, 3)"), what);
  if (rows.shape(0) == 0) throw Error(what + " must hold at least one light");
  LightDirections directions(rows.shape(0), 3);
  for (py::ssize_t i = 0; i < rows.shape(0); ++i) {
    const Eigen::Vector3d row(rows.at(i, 0), rows.at(i, 1), rows.at(i, 2));
    if (!(row.norm() > 1e-12))
      throw Error(what + "[" + std::to_string(i) + "] has zero length: a direction is expected");
    directions.row(i) = row.normalized().cast<float>().transpose();
  }
  return directions;
}

LightRgb rgb_rows_from(py::handle object, const std::string& what, py::ssize_t lights) {
  const std::string layout =
      "(" + (lights < 0 ? std::string("lights") : std::to_string(lights)) + ", 3)";
  const DoubleArray rows = finite_float64(
      checked_array(object, what, Accepted::real_numbers, {lights, 3}, layout), what);
  LightRgb rgb(rows.shape(0), 3);
  for (py::ssize_t i = 0; i < rows.shape(0); ++i)
    for (int c = 0; c < 3; ++c) rgb(i, c) = static_cast<float>(rows.at(i, c));
  return rgb;
}

std::vector<LightRgb> rgb_batch_from(py::handle object, const std::string& what,
                                     py::ssize_t lights) {
  const DoubleArray rows =
      finite_float64(checked_array(object, what, Accepted::real_numbers, {-1, lights, 3},
                                   "(count, " + std::to_string(lights) + ", 3)"),
                     what);
  std::vector<LightRgb> batch(static_cast<std::size_t>(rows.shape(0)), LightRgb(lights, 3));
  for (py::ssize_t n = 0; n < rows.shape(0); ++n)
    for (py::ssize_t i = 0; i < lights; ++i)
      for (int c = 0; c < 3; ++c) batch[n](i, c) = static_cast<float>(rows.at(n, i, c));
  return batch;
}

ReflectanceField field_from(py::handle values, py::handle dirs, py::handle mask,
                            py::handle intensities) {
  const std::string what = "field values";
  const py::array array = checked_array(values, what, Accepted::float32, {-1, -1, -1, -1},
                                        "(height, width, channels, lights)");
  for (py::ssize_t d = 0; d < 4; ++d)
    if (array.shape(d) == 0) throw Error(what + " must not be empty (a dimension is 0)");
  const FloatArray checked = finite_float32(array, what);
  ReflectanceField field;
  field.height = static_cast<int>(array.shape(0));
  field.width = static_cast<int>(array.shape(1));
  field.channels = static_cast<int>(array.shape(2));
  const auto lights = array.shape(3);
  field.values.resize(field.pixels() * field.channels, lights);
  std::copy(checked.data(), checked.data() + checked.size(), field.values.data());
  if (dirs.is_none())
    throw Error(
        "dirs= is needed when the field is given as an array: the (lights, 3) light "
        "directions");
  field.directions = directions_from(dirs, "dirs");
  if (field.directions.rows() != lights)
    throw Error("dirs has " + std::to_string(field.directions.rows()) + " rows but the field has " +
                std::to_string(lights) + " lights");
  field.mask = mask.is_none() ? std::vector<std::uint8_t>(field.pixels(), 1)
                              : mask_from(mask, "mask", field.width, field.height);
  if (intensities.is_none())
    field.intensities.setOnes(lights, 3);
  else
    field.intensities = rgb_rows_from(intensities, "intensities", lights);
  return field;
}

Image image_from(py::handle object, const std::string& what) {
  const py::array any = py::array::ensure(object);
  const bool grey = any && any.ndim() == 2;
  const py::array array =
      grey ? checked_array(object, what, Accepted::real_numbers, {-1, -1}, "(height, width)")
           : checked_array(object, what, Accepted::real_numbers, {-1, -1, -1},
                           "(height, width) or (height, width, channels)");
  const FloatArray values = finite_float32(array, what);
  const int channels = grey ? 1 : static_cast<int>(array.shape(2));
  if (array.shape(0) == 0 || array.shape(1) == 0 || channels == 0)
    throw Error(what + " is empty: " + std::to_string(array.shape(0)) + " x " +
                std::to_string(array.shape(1)) + " x " + std::to_string(channels));
  Image image(static_cast<int>(array.shape(1)), static_cast<int>(array.shape(0)), channels);
  std::copy(values.data(), values.data() + values.size(), image.pixels.begin());
  return image;
}

std::vector<std::uint8_t> mask_from(py::handle object, const std::string& what, int width,
                                    int height) {
  const py::array array =
      checked_array(object, what, Accepted::integers, {height, width},
                    "(" + std::to_string(height) + ", " + std::to_string(width) + ")");
  const auto values =
      py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(array);
  std::vector<std::uint8_t> mask(static_cast<std::size_t>(values.size()));
  for (py::ssize_t i = 0; i < values.size(); ++i) mask[i] = values.data()[i] != 0;
  return mask;
}

}  // namespace relume::python
