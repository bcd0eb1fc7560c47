// `relume compare IMAGE REFERENCE`: how far a relit image is from a reference (for example a
// compressed field relit against the uncompressed one): relative squared error, relative L2
// error, RMS and PSNR, the largest absolute and relative differences and where they are, and the
// count of negative values; with --mask, inside the mask only. --fail T exits 1 above a threshold;
// --json - prints the JSON on stdout.
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <optional>
#include <relume/error.hpp>
#include <relume/image.hpp>

#include "command_registry.hpp"
#include "field/mask_file.hpp"
#include "image/image_difference.hpp"
#include "core/json_report.hpp"
#include "options/output_paths.hpp"

namespace relume {
namespace {

struct CompareOptions {
  std::string image, reference, json, mask;
  std::optional<double> fail;
};

void run_compare(const CompareOptions& options) {
  const bool json_to_stdout = options.json == "-";
  if (!json_to_stdout) check_new_output(options.json);
  const Image image = read_image(options.image);
  const std::vector<std::uint8_t> mask = options.mask.empty()
                                             ? std::vector<std::uint8_t>{}
                                             : read_mask(options.mask, image.width, image.height);
  const ImageDifference d = image_difference(image, read_image(options.reference), options.image,
                                             options.reference, mask);
  const double psnr = peak_signal_to_noise_db(d);
  const bool failed = options.fail && d.relative_squared_error > *options.fail;
  char psnr_text[32];
  std::snprintf(psnr_text, sizeof psnr_text, std::isinf(psnr) ? "infinite" : "%.2f dB", psnr);
  // The figures are the result asked for: on stdout, unless the JSON goes there.
  std::fprintf(json_to_stdout ? stderr : stdout,
               "%s against %s: relative squared error %.6g (relative L2 %.6g), RMS %.6g, PSNR %s "
               "(peak 1), largest |difference| %.6g at pixel (%d, %d) channel %d, largest "
               "relative difference %.4g at pixel (%d, %d) channel %d, %zu of %zu values "
               "negative\n",
               options.image.c_str(), options.reference.c_str(), d.relative_squared_error,
               std::sqrt(d.relative_squared_error), std::sqrt(d.mean_squared_difference), psnr_text,
               d.max_abs_difference, d.max_x, d.max_y, d.max_channel, d.max_relative_difference,
               d.relative_x, d.relative_y, d.relative_channel, d.negative_values, d.values);
  if (!options.json.empty()) {
    nlohmann::ordered_json report = {
        {"image", options.image},
        {"reference", options.reference},
        {"relative_squared_error", d.relative_squared_error},
        {"relative_l2_error", std::sqrt(d.relative_squared_error)},
        {"rms", std::sqrt(d.mean_squared_difference)},
        {"psnr_db", std::isinf(psnr) ? nlohmann::ordered_json() : nlohmann::ordered_json(psnr)},
        {"max_abs_difference", d.max_abs_difference},
        {"max_at", {{"x", d.max_x}, {"y", d.max_y}, {"channel", d.max_channel}}},
        {"max_relative_difference", d.max_relative_difference},
        {"max_relative_at",
         {{"x", d.relative_x}, {"y", d.relative_y}, {"channel", d.relative_channel}}},
        {"relative_difference_floor", relative_difference_floor},
        {"negative_values", d.negative_values},
        {"values", d.values},
        {"mask",
         options.mask.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(options.mask)}};
    if (options.fail) {
      report["fail_threshold"] = *options.fail;
      report["failed"] = failed;
    }
    if (json_to_stdout)
      std::printf("%s\n", stamped_report(report).dump(2).c_str());
    else
      write_json_report(options.json, report);
  }
  if (failed) {
    char text[160];
    std::snprintf(text, sizeof text, "relative squared error %.6g is above --fail %g",
                  d.relative_squared_error, *options.fail);
    throw Error(text);
  }
}

const CommandRegistration registration{
    38, [](CLI::App& app) {
      auto options = std::make_shared<CompareOptions>();
      auto* command = app.add_subcommand(
          "compare",
          "Compare an image with a reference of the same size (any format OpenImageIO reads; use "
          "linear EXRs for relit images): relative squared error sum (a - r)^2 / sum r^2, relative "
          "L2 error, RMS and PSNR (peak 1), largest absolute difference, largest relative "
          "difference |a - r| / max(|r|, 1% of the reference's peak), negative values.\n"
          "Example: relume compare relit.exr reference.exr --fail 0.001 --json -");
      command->add_option("image", options->image, "The image to judge")->required();
      command->add_option("reference", options->reference, "The reference image")->required();
      command->add_option("--json", options->json,
                          "Also write the figures to this JSON file ('-': to stdout, the text "
                          "line then goes to stderr)");
      command
          ->add_option("--fail", options->fail,
                       "Exit with status 1 when the relative squared error is above this "
                       "threshold (after printing and writing the figures), as idiff -fail does")
          ->check(CLI::NonNegativeNumber);
      command->add_option("--mask", options->mask,
                          "Compare only the pixels inside this mask (an image of the same size, "
                          "non-zero = inside; a field's mask.png)");
      command->callback([options] { run_compare(*options); });
    }};

}  // namespace
}  // namespace relume
