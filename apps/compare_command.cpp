// `relume compare IMAGE REFERENCE`: how far a relit image is from a reference (for example a
// compressed field relit against the uncompressed one): relative squared error, relative L2
// error, the largest absolute difference and where it is, and the count of negative values;
// with --mask, inside the mask only.
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <relume/image.hpp>

#include "command_registry.hpp"
#include "field/mask_file.hpp"
#include "image/image_difference.hpp"
#include "json_report.hpp"
#include "output_paths.hpp"

namespace relume {
namespace {

struct CompareOptions {
  std::string image, reference, json, mask;
};

void run_compare(const CompareOptions& options) {
  check_new_output(options.json);
  const Image image = read_image(options.image);
  const std::vector<std::uint8_t> mask = options.mask.empty()
                                             ? std::vector<std::uint8_t>{}
                                             : read_mask(options.mask, image.width, image.height);
  const ImageDifference d = image_difference(image, read_image(options.reference), options.image,
                                             options.reference, mask);
  std::printf(
      "%s against %s: relative squared error %.6g (relative L2 %.6g), largest |difference| "
      "%.6g at pixel (%d, %d) channel %d, %zu of %zu values negative\n",
      options.image.c_str(), options.reference.c_str(), d.relative_squared_error,
      std::sqrt(d.relative_squared_error), d.max_abs_difference, d.max_x, d.max_y, d.max_channel,
      d.negative_values, d.values);
  if (options.json.empty()) return;
  const nlohmann::ordered_json report = {
      {"image", options.image},
      {"reference", options.reference},
      {"relative_squared_error", d.relative_squared_error},
      {"relative_l2_error", std::sqrt(d.relative_squared_error)},
      {"max_abs_difference", d.max_abs_difference},
      {"max_at", {{"x", d.max_x}, {"y", d.max_y}, {"channel", d.max_channel}}},
      {"negative_values", d.negative_values},
      {"values", d.values},
      {"mask",
       options.mask.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(options.mask)}};
  write_json_report(options.json, report);
}

const CommandRegistration registration{
    38, [](CLI::App& app) {
      auto options = std::make_shared<CompareOptions>();
      auto* command = app.add_subcommand(
          "compare",
          "Compare an image with a reference of the same size (any format OpenImageIO reads; use "
          "linear EXRs for relit images): relative squared error sum (a - r)^2 / sum r^2, relative "
          "L2 error, largest absolute difference, negative values");
      command->add_option("image", options->image, "The image to judge")->required();
      command->add_option("reference", options->reference, "The reference image")->required();
      command->add_option("--json", options->json, "Also write the figures to this JSON file");
      command->add_option("--mask", options->mask,
                          "Compare only the pixels inside this mask (an image of the same size, "
                          "non-zero = inside; a field's mask.png)");
      command->callback([options] { run_compare(*options); });
    }};

}  // namespace
}  // namespace relume
