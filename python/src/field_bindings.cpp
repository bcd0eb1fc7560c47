// relume.Field (a reflectance field: values, mask, light directions and intensities as NumPy
// views) and relume.load.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <optional>
#include <relume/compress.hpp>
#include <relume/field.hpp>
#include <relume/relight.hpp>

#include "arrays.hpp"
#include "bindings.hpp"
#include "errors.hpp"
#include "field/input_encoding.hpp"
#include "lighting/light_interpolation.hpp"
#include "moved_light.hpp"

namespace relume::python {

using namespace pybind11::literals;

namespace {

const ReflectanceField& field_of(const py::object& self) {
  return self.cast<const ReflectanceField&>();
}

}  // namespace

void bind_field(py::module_& module) {
  py::class_<ReflectanceField>(module, "Field", R"(A fixed-viewpoint reflectance field.

values[y, x, c, i] is pixel (x, y), channel c under light i (divided by that light's
intensity): float32 (height, width, channels, lights). directions[i] is the unit vector from
the object towards light i in the camera frame (x right, y up, z towards the camera).
Every array attribute is a read-only view of the field's own memory (no copy); a view keeps
the field alive. Make one with relume.load(path) or Field(values, dirs, ...).)")
      .def(py::init(&field_from), "values"_a, "dirs"_a, py::kw_only(), "mask"_a = py::none(),
           "intensities"_a = py::none(),
           R"(A field from arrays, copied once into the field's memory.

values: float32 (height, width, channels, lights), every value finite (other dtypes are
refused: convert with .astype(numpy.float32)). dirs: (lights, 3), normalised to unit length.
mask: (height, width) bool or integers, non-zero = inside (None: all inside).
intensities: (lights, 3), what the values were divided by (None: ones).)")
      .def_property_readonly("width", [](const ReflectanceField& f) { return f.width; })
      .def_property_readonly("height", [](const ReflectanceField& f) { return f.height; })
      .def_property_readonly("channels", [](const ReflectanceField& f) { return f.channels; })
      .def_property_readonly("lights", &ReflectanceField::lights)
      .def_property_readonly(
          "values",
          [](const py::object& self) {
            const ReflectanceField& f = field_of(self);
            return readonly_view(f.values.data(), {f.height, f.width, f.channels, f.lights()},
                                 self);
          },
          "float32 (height, width, channels, lights), a read-only view.")
      .def_property_readonly(
          "mask",
          [](const py::object& self) {
            const ReflectanceField& f = field_of(self);
            return readonly_view(f.mask.data(), {f.height, f.width}, self);
          },
          "uint8 (height, width), 1 = inside the object; a read-only view.")
      .def_property_readonly(
          "directions",
          [](const py::object& self) {
            const ReflectanceField& f = field_of(self);
            return readonly_view(f.directions.data(), {f.lights(), 3}, self);
          },
          "float32 (lights, 3), unit vectors towards the lights; a read-only view.")
      .def_property_readonly(
          "intensities",
          [](const py::object& self) {
            const ReflectanceField& f = field_of(self);
            return readonly_view(f.intensities.data(), {f.lights(), 3}, self);
          },
          "float32 (lights, 3), the RGB each image was divided by; a read-only view.")
      .def_readonly("image_names", &ReflectanceField::image_names,
                    "The image file of each light (empty for a field made from arrays).")
      .def(
          "relight",
          [](const ReflectanceField& f, py::handle light, py::handle light_dir, py::handle color,
             double spread, unsigned threads) {
            const LightRgb rgb = relight_light(light, light_dir, color, spread, f.directions);
            Image image;
            {
              py::gil_scoped_release released;
              image = relight_field(f, rgb, threads);
            }
            return adopt_image(std::move(image));
          },
          "light"_a = py::none(), py::kw_only(), "light_dir"_a = py::none(),
          "color"_a = default_light_color(), "spread"_a = DirectionalLight{}.spread_degrees,
          "threads"_a = 0,
          R"(The field relit without compression (the reference): float32 (height, width,
channels), out[p] = sum_i values[p, i] * light[i, c], accumulated in double. light:
(lights, 3) RGB per light; a grey field uses each row's mean. Or, instead of light, a light
moved to light_dir=(x, y, z) with color= and spread=, as relume.light_vector makes it (and
`relume relight --light-dir`). Pixels outside the mask are not set to 0 (the command does).)")
      .def(
          "save",
          [](const ReflectanceField& f, const std::filesystem::path& folder) {
            with_file_errors([&] {
              py::gil_scoped_release released;
              write_field_folder(folder, f);
            });
          },
          "folder"_a,
          R"(Write a field folder that relume.load and the relume command read: one EXR per
light, filenames.txt, light_directions.txt, light_intensities.txt and mask.png.)")
      .def("__repr__", [](const ReflectanceField& f) {
        return "relume.Field(" + std::to_string(f.width) + "x" + std::to_string(f.height) + ", " +
               std::to_string(f.channels) + " channels, " + std::to_string(f.lights()) + " lights)";
      });

  module.def(
      "load",
      [](const std::filesystem::path& path, const std::string& input_encoding,
         std::optional<std::filesystem::path> mask_file, bool use_mask, unsigned threads) {
        FieldLoadOptions options;
        options.image.eight_bit = parse_input_encoding(input_encoding);
        options.mask_file = mask_file.value_or(std::filesystem::path());
        options.use_mask = use_mask;
        options.threads = threads;
        return with_file_errors([&] {
          py::gil_scoped_release released;
          return load_field(path, options);
        });
      },
      "path"_a, py::kw_only(), "input_encoding"_a = compress_defaults().input_encoding,
      "mask_file"_a = py::none(), "use_mask"_a = compress_defaults().use_mask, "threads"_a = 0,
      R"(Load a reflectance field: a field folder (DiLiGenT layout: the images, filenames.txt,
light_directions.txt, optional light_intensities.txt and mask.png) or an RTI .lp file.

input_encoding: how 8-bit images are decoded, as `relume compress --input-encoding` decodes
them: "auto" (float and 16-bit images and DiLiGenT folders linear, other 8-bit JPEG/PNG sRGB
unless they declare linear), "linear" or "srgb". mask_file replaces a folder's mask.png (for
an .lp capture too); use_mask=False keeps every pixel. Raises relume.FileError naming the
file, line or pixel at fault (missing files, unequal image sizes, NaN/Inf pixels).)");
}

}  // namespace relume::python
