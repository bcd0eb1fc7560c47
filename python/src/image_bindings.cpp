// relume.read_image and relume.write_image: images through OpenImageIO as float32 arrays
// (height, width, channels), as the library reads and writes them (relume/image.hpp).
#include <pybind11/stl/filesystem.h>

#include <relume/image.hpp>

#include "arrays.hpp"
#include "bindings.hpp"
#include "errors.hpp"

namespace relume::python {

using namespace pybind11::literals;

void bind_images(py::module_& module) {
  module.def(
      "read_image",
      [](const std::filesystem::path& path, bool srgb) {
        ImageReadOptions options;
        options.eight_bit = srgb ? EightBitEncoding::srgb : EightBitEncoding::linear;
        Image image = with_file_errors([&] {
          py::gil_scoped_release released;
          return read_image(path, options);
        });
        return adopt_image(std::move(image));
      },
      "path"_a, py::kw_only(), "srgb"_a = false,
      R"(Read an image (any format OpenImageIO reads) as float32 (height, width, channels).

Integer formats are normalised to [0, 1] at their full depth (16-bit PNG as 16 bits); 8-bit
images are linear unless srgb=True decodes them. The array owns the pixels (no copy).
Raises relume.FileError for a missing or unreadable file.)");

  module.def(
      "write_image",
      [](const std::filesystem::path& path, py::handle pixels, double exposure) {
        const Image image = image_from(pixels, "image");
        ImageWriteOptions options;
        options.exposure = exposure;
        with_file_errors([&] {
          py::gil_scoped_release released;
          write_image(path, image, options);
        });
      },
      "path"_a, "image"_a, py::kw_only(), "exposure"_a = 0.0,
      R"(Write an image (height, width) or (height, width, channels); the format follows the
extension. EXR, HDR and TIFF are written linear; 8-bit formats (PNG, JPEG) are exposed by
2**exposure and sRGB-encoded. Atomic: a failed write leaves no file. NaN/Inf values are
refused (relume.Error), write failures raise relume.FileError.)");
}

}  // namespace relume::python
