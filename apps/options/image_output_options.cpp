// Implementation of the shared image output options.
#include "options/image_output_options.hpp"

#include "core/console.hpp"
#include "image/auto_exposure.hpp"
#include "options/number_or_auto.hpp"

namespace relume {

void add_image_output_options(CLI::App& command, ImageOutputOptions& options) {
  command
      .add_option("--exposure", options.exposure,
                  "Exposure in stops for integer outputs (PNG, JPEG, TIFF with --bits), or auto: "
                  "the 99th percentile of the lit object's luminance maps to 0.9")
      ->capture_default_str()
      ->check(number_or_auto("--exposure", "stops", max_exposure_stops));
  command
      .add_option("--bits", options.bits,
                  "Bits per channel of integer outputs: 8 or 16 for PNG and TIFF (a TIFF without "
                  "--bits is linear float), 8 for JPEG")
      ->check(CLI::IsMember({8, 16}));
  command.add_flag("--half", options.half,
                   "Write EXR outputs as half floats (half the bytes) instead of float");
}

void check_image_output(const std::filesystem::path& path, const ImageOutputOptions& options) {
  check_image_write_options(path, {0, options.bits, options.half});
  // An exposure given for a float output was ignored without a word.
  const bool floats = is_float_image_format(path) && options.bits == 0;
  if (floats && (options.exposure == "auto" ||
                 parse_finite_number(options.exposure, "--exposure", "stops") != 0))
    note("--exposure %s leaves %s unexposed: it is written as linear floats (the exposure applies "
         "to integer outputs: PNG, JPEG, TIFF with --bits)",
         options.exposure.c_str(), path.string().c_str());
}

double display_exposure(const ImageOutputOptions& options, const Image& image,
                        const std::vector<std::uint8_t>& mask) {
  if (options.exposure != "auto")
    return parse_finite_number(options.exposure, "--exposure", "stops", max_exposure_stops);
  const AutoExposure automatic = auto_exposure(image, mask);
  if (automatic.lit_pixels == 0)
    note("--exposure auto: nothing is lit, exposure 0");
  else
    note(
        "--exposure auto: %+.2f stops (the 99th percentile of %zu lit pixels, %.4g, maps to "
        "0.9)",
        automatic.stops, automatic.lit_pixels, automatic.percentile);
  return automatic.stops;
}

ImageWriteOptions resolve_image_output(const std::filesystem::path& path,
                                       const ImageOutputOptions& options, const Image& image,
                                       const std::vector<std::uint8_t>& mask) {
  ImageWriteOptions write{0, options.bits, options.half};
  // Floats are written unexposed: only an integer output needs (and measures) an exposure.
  if (!is_float_image_format(path) || options.bits != 0)
    write.exposure = display_exposure(options, image, mask);
  return write;
}

}  // namespace relume
