// relume.Compressed (a compressed field: its parts as NumPy views, relighting on an OpenCL device
// or with the CPU reference, reconstruction, saving, NumPy export), relume.open and
// relume.relative_error.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <optional>
#include <relume/compressed_field.hpp>
#include <relume/container.hpp>
#include <relume/relight.hpp>

#include "arrays.hpp"
#include "bindings.hpp"
#include "compressed_object.hpp"
#include "container/container.hpp"
#include "errors.hpp"
#include "export/npz_export.hpp"
#include "lighting/light_interpolation.hpp"
#include "moved_light.hpp"

namespace relume::python {

using namespace pybind11::literals;

namespace {

const CompressedField& field_of(const py::object& self) {
  return self.cast<const CompressedObject&>().field;
}

int residual_cap(const std::optional<int>& residual) {
  if (!residual) return all_residual_entries;
  if (*residual < 0)
    throw Error("residual must be a count of entries >= 0 (or None: all), got " +
                std::to_string(*residual));
  return *residual;
}

// The caller holds self.relighting.
Relighter& relighter_for(CompressedObject& self, const std::optional<std::string>& device,
                         bool reference) {
  if (reference && device)
    throw Error("give device= (OpenCL) or reference=True (the CPU reference), not both");
  if (reference) {
    if (!self.reference) {
      RelighterOptions options;
      options.cpu_reference = true;
      self.reference = std::make_unique<Relighter>(self.field, options);
    }
    return *self.reference;
  }
  std::unique_ptr<Relighter>& relighter = self.opencl[device.value_or("")];
  if (!relighter) {
    RelighterOptions options;
    options.device = device.value_or("");
    relighter = std::make_unique<Relighter>(self.field, options);
  }
  return *relighter;
}

ContainerOptions storage_with(const CompressedObject& self,
                              const std::optional<std::string>& weights_precision,
                              const std::optional<std::string>& residual_precision,
                              const std::string& light_index) {
  ContainerOptions options = self.storage;
  if (weights_precision) options.weights = parse_value_precision(*weights_precision);
  if (residual_precision) options.residual = parse_value_precision(*residual_precision);
  options.light_index = parse_index_width(light_index);
  return options;
}

constexpr const char* relight_options_doc = R"(
residual: use at most this many residual entries per function, its largest ones (faster,
less accurate; None: all). device: the OpenCL device, a substring of "platform / device"
(None: RELUME_DEVICE, else the first GPU, else PoCL's CPU device). reference=True relights
with the CPU reference (C++, accumulated in double) instead. The field is uploaded to a device
once and kept for later calls.)";

}  // namespace

void bind_compressed(py::module_& module) {
  py::class_<CompressedObject> compressed(module, "Compressed", R"(A compressed reflectance field:
    R[p, :] ~ weights[s, :] @ bases[cluster[s]] + residual row s
for every stored function p = stored_function[s]; the channels of each dark pixel are the rows
of the dark model, and the other functions (outside the mask or all zero) relight to 0. Made
by relume.compress or relume.open. Its array attributes are read-only views of its own
memory; a view keeps it alive.)");
  compressed.def_property_readonly("width", [](const CompressedObject& c) { return c.field.width; })
      .def_property_readonly("height", [](const CompressedObject& c) { return c.field.height; })
      .def_property_readonly("channels", [](const CompressedObject& c) { return c.field.channels; })
      .def_property_readonly("lights", [](const CompressedObject& c) { return c.field.lights; })
      .def_property_readonly("terms", [](const CompressedObject& c) { return c.field.terms; })
      .def_property_readonly("clusters", [](const CompressedObject& c) { return c.field.clusters; })
      .def_property_readonly("stored_rows",
                             [](const CompressedObject& c) { return c.field.stored_rows(); })
      .def_property_readonly("non_negative",
                             [](const CompressedObject& c) { return c.field.non_negative; })
      .def_property_readonly(
          "transform",
          [](const CompressedObject& c) {
            return c.field.transform == BasisTransform::haar ? "haar" : "identity";
          },
          "The basis of bases and the residual: 'identity' (lights) or 'haar'.")
      .def_property_readonly(
          "mask",
          [](const py::object& self) {
            const CompressedField& f = field_of(self);
            return readonly_view(f.mask.data(), {f.height, f.width}, self);
          },
          "uint8 (height, width), 1 = inside.")
      .def_property_readonly(
          "directions",
          [](const py::object& self) {
            const CompressedField& f = field_of(self);
            return readonly_view(f.directions.data(), {f.lights, 3}, self);
          },
          "float32 (lights, 3), unit vectors towards the lights.")
      .def_property_readonly(
          "intensities",
          [](const py::object& self) {
            const CompressedField& f = field_of(self);
            return readonly_view(f.intensities.data(), {f.lights, 3}, self);
          },
          "float32 (lights, 3), the RGB the original images were divided by.")
      .def_property_readonly(
          "stored_function",
          [](const py::object& self) {
            const CompressedField& f = field_of(self);
            return readonly_view(f.stored_function.data(), {py::ssize_t(f.stored_rows())}, self);
          },
          "uint32 (stored_rows,): the function p = (y * width + x) * channels + c of each row.")
      .def_property_readonly(
          "cluster",
          [](const py::object& self) {
            const CompressedField& f = field_of(self);
            return readonly_view(f.cluster.data(), {py::ssize_t(f.stored_rows())}, self);
          },
          "uint32 (stored_rows,): the cluster of each stored row.")
      .def_property_readonly(
          "weights",
          [](const py::object& self) {
            const CompressedField& f = field_of(self);
            return readonly_view(f.weights.data(), {py::ssize_t(f.stored_rows()), f.terms}, self);
          },
          "float32 (stored_rows, terms): W.")
      .def_property_readonly(
          "bases",
          [](const py::object& self) {
            const CompressedField& f = field_of(self);
            return readonly_view(f.bases.data(), {f.clusters, f.terms, f.lights}, self);
          },
          "float32 (clusters, terms, lights): F of every cluster.")
      .def_property_readonly(
          "residual_offsets",
          [](const py::object& self) {
            const ResidualRows& r = field_of(self).residual;
            return readonly_view(r.row_offsets.data(), {py::ssize_t(r.row_offsets.size())}, self);
          },
          "uint32 (stored_rows + 1,): row s of the residual is [offsets[s], offsets[s + 1]).")
      .def_property_readonly(
          "residual_indices",
          [](const py::object& self) {
            const ResidualRows& r = field_of(self).residual;
            return readonly_view(r.light_index.data(), {py::ssize_t(r.nonzeros())}, self);
          },
          "uint32 (nonzeros,): the light of each residual entry.")
      .def_property_readonly(
          "residual_values",
          [](const py::object& self) {
            const ResidualRows& r = field_of(self).residual;
            return readonly_view(r.values.data(), {py::ssize_t(r.nonzeros())}, self);
          },
          "float32 (nonzeros,): residual values, each row sorted by |value| descending.")
      .def_property_readonly(
          "dark_pixels",
          [](const py::object& self) {
            const CompressedField& f = field_of(self);
            return readonly_view(f.dark_pixels.data(), {py::ssize_t(f.dark_pixels.size())}, self);
          },
          "uint32 (n,): pixels y * width + x at the noise level, relit by the dark model.")
      .def_property_readonly(
          "dark",
          [](const py::object& self) {
            const CompressedField& f = field_of(self);
            return readonly_view(f.dark.data(), {py::ssize_t(f.dark.size()) / f.lights, f.lights},
                                 self);
          },
          "float32 (channels, lights), in the basis of bases: the dark model, (0, lights) when no "
          "pixel is dark.")
      .def_property_readonly(
          "dark_gains",
          [](const CompressedObject& c) {
            const CompressedField& f = c.field;
            py::array_t<float> gains({py::ssize_t(f.dark_pixels.size()), py::ssize_t(f.channels)});
            float* out = gains.mutable_data();
            for (std::size_t v = 0; v < f.dark_pixels.size() * std::size_t(f.channels); ++v)
              out[v] = dark_gain(f, v / std::size_t(f.channels), int(v % f.channels));
            return gains;
          },
          "float32 (n, channels): channel c of dark pixel d relights as dark_gains[d, c] * "
          "dark[c] (ones for containers before version 4).")
      .def_property_readonly(
          "weights_precision",
          [](const CompressedObject& c) { return to_string(c.storage.weights); },
          "How save() stores W by default: 'float32' or 'float16'.")
      .def_property_readonly(
          "residual_precision",
          [](const CompressedObject& c) { return to_string(c.storage.residual); },
          "How save() stores residual values by default: 'float32' or 'float16'.")
      .def_property_readonly(
          "parameters",
          [](const CompressedObject& c) {
            return py::module_::import("json").attr("loads")(c.storage.parameters_json);
          },
          "The compression parameters recorded in the container header, a dict.")
      .def(
          "relight",
          [](CompressedObject& self, py::handle light, py::handle light_dir, py::handle color,
             double spread, std::optional<int> residual, std::optional<std::string> device,
             bool reference) {
            const LightRgb rgb =
                relight_light(light, light_dir, color, spread, self.field.directions);
            const int cap = residual_cap(residual);
            Image image;
            {
              py::gil_scoped_release released;
              const std::lock_guard lock(self.relighting);
              image = relighter_for(self, device, reference).relight(rgb, cap);
            }
            return adopt_image(std::move(image));
          },
          "light"_a = py::none(), py::kw_only(), "light_dir"_a = py::none(),
          "color"_a = default_light_color(), "spread"_a = DirectionalLight{}.spread_degrees,
          "residual"_a = py::none(), "device"_a = py::none(), "reference"_a = false,
          (std::string("Relight under a light vector (lights, 3): float32 (height, width, "
                       "channels), owning its pixels. Or, instead of light, under a light moved "
                       "to light_dir=(x, y, z) with color= and spread=, as relume.light_vector "
                       "makes it (and `relume relight --light-dir`).\n") +
           relight_options_doc)
              .c_str())
      .def(
          "relight_batch",
          [](CompressedObject& self, py::handle lights, std::optional<int> residual,
             std::optional<std::string> device, bool reference) {
            const CompressedField& f = self.field;
            const std::vector<LightRgb> batch = rgb_batch_from(lights, "lights", f.lights);
            const int cap = residual_cap(residual);
            std::vector<float> frames;
            {
              py::gil_scoped_release released;
              const std::lock_guard lock(self.relighting);
              const std::vector<Image> images =
                  relighter_for(self, device, reference).relight_batch(batch, cap);
              frames.reserve(images.size() * std::size_t(f.width) * f.height * f.channels);
              for (const Image& image : images)
                frames.insert(frames.end(), image.pixels.begin(), image.pixels.end());
            }
            return adopt_vector(std::move(frames),
                                {py::ssize_t(batch.size()), f.height, f.width, f.channels});
          },
          "lights"_a, py::kw_only(), "residual"_a = py::none(), "device"_a = py::none(),
          "reference"_a = false,
          (std::string("Relight under a batch of light vectors (count, lights, 3), in one pass "
                       "over W and the residual on OpenCL: float32 (count, height, width, "
                       "channels).\n") +
           relight_options_doc)
              .c_str())
      .def(
          "reconstruct",
          [](const CompressedObject& self, std::optional<int> residual) {
            const int cap = residual_cap(residual);
            py::gil_scoped_release released;
            return reconstruct_field(self.field, cap);
          },
          py::kw_only(), "residual"_a = py::none(),
          R"(The whole field back in the light basis, a relume.Field: W F plus the residual (at
most `residual` entries per function when given); functions not stored are zero.)")
      .def(
          "save",
          [](const CompressedObject& self, const std::filesystem::path& path,
             std::optional<std::string> weights_precision,
             std::optional<std::string> residual_precision, const std::string& light_index) {
            const ContainerOptions options =
                storage_with(self, weights_precision, residual_precision, light_index);
            with_file_errors([&] {
              py::gil_scoped_release released;
              write_container(path, self.field, options);
            });
          },
          "path"_a, py::kw_only(), "weights_precision"_a = py::none(),
          "residual_precision"_a = py::none(), "light_index"_a = "auto",
          R"(Write a .relume container (atomically: a failure leaves no file). Precisions:
'float32' or 'float16' (None: as given to compress, or as the opened file had);
light_index: 'auto', '8', '16' or '32' bits.)")
      .def(
          "export_npz",
          [](const CompressedObject& self, const std::filesystem::path& path) {
            with_file_errors([&] {
              py::gil_scoped_release released;
              write_compressed_field_npz(path, self.field);
            });
          },
          "path"_a,
          R"(Write the field's arrays as a NumPy .npz, as `relume export --to npz` does
(atomically; numpy.load reads it without pickle): W, F, the clusters, the residual as CSR,
the dark model, the mask, lights and intensities, the basis transform and the quantization,
with a 'description' entry that says how they rebuild the field and its images exactly.)")
      .def(
          "file_size",
          [](const CompressedObject& self, std::optional<std::string> weights_precision,
             std::optional<std::string> residual_precision, const std::string& light_index) {
            const ContainerOptions options =
                storage_with(self, weights_precision, residual_precision, light_index);
            py::gil_scoped_release released;
            return plan_container(self.field, options).file_bytes;
          },
          py::kw_only(), "weights_precision"_a = py::none(), "residual_precision"_a = py::none(),
          "light_index"_a = "auto",
          "The bytes of the .relume file save() would write with these options, without writing.")
      .def("__repr__", [](const CompressedObject& c) {
        const CompressedField& f = c.field;
        return "relume.Compressed(" + std::to_string(f.width) + "x" + std::to_string(f.height) +
               ", " + std::to_string(f.channels) + " channels, " + std::to_string(f.lights) +
               " lights, " + std::to_string(f.clusters) + " clusters of " +
               std::to_string(f.terms) + " terms, " + std::to_string(f.residual.nonzeros()) +
               " residual entries)";
      });

  module.def(
      "open",
      [](const std::filesystem::path& path) {
        auto opened = std::make_unique<CompressedObject>();
        with_file_errors([&] {
          py::gil_scoped_release released;
          opened->field = read_container(path, &opened->storage);
        });
        return opened;
      },
      "path"_a,
      R"(Read a .relume container (written by Compressed.save or `relume compress`). Raises
relume.FileError for a missing, truncated or altered file, naming the section.)");

  module.def(
      "relative_error",
      [](const ReflectanceField& original, const CompressedObject& compressed, bool masked,
         std::optional<int> residual, unsigned threads) {
        const int cap = residual_cap(residual);
        py::gil_scoped_release released;
        return relative_error(original, compressed.field, masked, cap, threads).mean;
      },
      "original"_a, "compressed"_a, py::kw_only(), "masked"_a = true, "residual"_a = py::none(),
      "threads"_a = 0,
      R"(The paper's error (Eq. 16) of a compressed field against its original: the mean over
functions of sum_i (R - R~)^2 / sum_i R^2, functions with zero energy left out. masked: only
functions inside the compressed field's mask. residual: at most this many residual entries
per function (None: all).)");
}

}  // namespace relume::python
