// `relume compare IMAGE REFERENCE`: how far a relit image is from a reference (for example a
// compressed field relit against the uncompressed one): relative squared error, relative L2
// error, RMS and PSNR, the largest absolute and relative differences and where they are, and the
// count of negative values; what a person sees that those average away: the luminance SSIM (mean
// and worst 1% of windows), black pixels where the reference is lit, chroma outliers and the
// channel sums; and with --model, the container the image was relit from, the seam contrast of its
// cluster borders. With --mask, inside the mask only (with --model and no --mask, inside the
// model's mask). --fail T exits 1 above a threshold; --json - prints the JSON on stdout.
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <optional>
#include <relume/container.hpp>
#include <relume/error.hpp>
#include <relume/image.hpp>

#include "command_registry.hpp"
#include "core/json_report.hpp"
#include "field/mask_file.hpp"
#include "image/image_difference.hpp"
#include "image/lit_pixel_faults.hpp"
#include "image/luminance_ssim.hpp"
#include "model/seam_contrast.hpp"
#include "options/output_paths.hpp"

namespace relume {
namespace {

struct CompareOptions {
  std::string image, reference, json, mask, model;
  std::optional<double> fail;
};

nlohmann::ordered_json optional_json(const std::optional<double>& value) {
  return value ? nlohmann::ordered_json(*value) : nlohmann::ordered_json();
}

nlohmann::ordered_json optional_json(const std::vector<std::optional<double>>& values) {
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const auto& value : values) list.push_back(optional_json(value));
  return list;
}

nlohmann::ordered_json ssim_json(const LuminanceSsim& ssim) {
  return {{"mean", ssim.mean},       {"worst_1_percent", ssim.worst_1_percent},
          {"minimum", ssim.minimum}, {"minimum_at", {{"x", ssim.minimum_x}, {"y", ssim.minimum_y}}},
          {"windows", ssim.windows}, {"window", "gaussian 11x11, sigma 1.5"},
          {"white", ssim.white}};
}

nlohmann::ordered_json faults_json(const LitPixelFaults& faults) {
  nlohmann::ordered_json black_at = nlohmann::ordered_json::array();
  for (const PixelPosition& at : faults.black_examples)
    black_at.push_back({{"x", at.x}, {"y", at.y}});
  return {
      {"white", faults.white},
      {"lit_pixels", faults.lit_pixels},
      {"black_pixels", faults.black_pixels},
      {"black_pixels_first_at", black_at},
      {"chroma_outliers", faults.chroma_outliers},
      {"chroma_outlier_share",
       faults.lit_pixels ? double(faults.chroma_outliers) / double(faults.lit_pixels) : 0.0},
      {"largest_chroma_difference", faults.largest_chroma_difference},
      {"largest_chroma_at", {{"x", faults.largest_chroma_at.x}, {"y", faults.largest_chroma_at.y}}},
      {"channel_sum_ratio", optional_json(faults.channel_sum_ratio)}};
}

nlohmann::ordered_json seam_json(const SeamContrast& seams) {
  return {{"contrast", optional_json(seams.contrast)},
          {"per_channel", optional_json(seams.per_channel)},
          {"same_pairs", seams.same_pairs},
          {"border_pairs", seams.border_pairs},
          {"compared_border_pairs", seams.compared_border_pairs},
          {"pixels_with_every_channel_stored", seams.pixels_with_every_channel_stored},
          {"pixels_with_split_channels", seams.pixels_with_split_channels}};
}

std::string optional_text(const std::optional<double>& value, const char* format) {
  if (!value) return "undefined";
  char text[32];
  std::snprintf(text, sizeof text, format, *value);
  return text;
}

void run_compare(const CompareOptions& options) {
  const bool json_to_stdout = options.json == "-";
  if (!json_to_stdout) check_new_output(options.json);
  const Image image = read_image(options.image);
  const Image reference = read_image(options.reference);
  const std::optional<CompressedField> model =
      options.model.empty() ? std::nullopt : std::optional(read_container(options.model));
  const std::vector<std::uint8_t> mask = !options.mask.empty()
                                             ? read_mask(options.mask, image.width, image.height)
                                         : model ? model->mask
                                                 : std::vector<std::uint8_t>{};
  // The seam contrast first: it names the model when the model does not fit the images.
  const std::optional<SeamContrast> seams =
      model ? std::optional(seam_contrast(image, reference, *model, mask, options.image,
                                          options.reference, options.model))
            : std::nullopt;
  const ImageDifference d =
      image_difference(image, reference, options.image, options.reference, mask);
  const LuminanceSsim ssim =
      luminance_ssim(image, reference, mask, options.image, options.reference);
  const LitPixelFaults faults =
      lit_pixel_faults(image, reference, mask, options.image, options.reference);
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
  std::string sums;
  for (const auto& ratio : faults.channel_sum_ratio) sums += " " + optional_text(ratio, "%.4f");
  std::fprintf(json_to_stdout ? stderr : stdout,
               "luminance SSIM mean %.4f, worst 1%% of windows %.4f; %zu of %zu lit pixels black, "
               "%zu chroma outliers; channel sums%s of the reference's%s\n",
               ssim.mean, ssim.worst_1_percent, faults.black_pixels, faults.lit_pixels,
               faults.chroma_outliers, sums.c_str(),
               seams ? ("; seam contrast " + optional_text(seams->contrast, "%.3f")).c_str() : "");
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
         options.mask.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(options.mask)},
        {"model",
         options.model.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(options.model)},
        {"luminance_ssim", ssim_json(ssim)},
        {"lit_pixels", faults_json(faults)},
        {"seam_contrast", seams ? seam_json(*seams) : nlohmann::ordered_json()}};
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
          "difference |a - r| / max(|r|, 1% of the reference's peak), negative values. What a "
          "person sees, relative to the reference's white W (the luminance --exposure auto shows "
          "as 1): luminance SSIM of both images shown that way (luminance / W clipped to [0, 1], "
          "sRGB-encoded; Gaussian 11x11 windows, sigma 1.5, Wang et al.'s constants; the mean and "
          "the worst 1% of windows); black pixels (lit in the reference, luminance at least 2/255 "
          "of W, and below 1/255 of W in the image); chroma outliers (lit pixels whose r,g,b / "
          "(r+g+b) is more than 0.05 from the reference's); each channel's sum over the "
          "reference's. With --model, the seam contrast: per channel, for 4-neighbour pixel pairs "
          "binned by their reference gradient, the mean |change of the error| between pixels "
          "whose functions are in different clusters over that between pixels in the same "
          "cluster (1.0: the borders do not show).\n"
          "Examples: relume compare relit.exr reference.exr --fail 0.001 --json -\n"
          "          relume compare relit.exr reference.exr --model scene.relume --json -");
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
      command->add_option("--model", options->model,
                          "The container IMAGE was relit from: adds the seam contrast of its "
                          "clusters, and compares inside its mask when --mask is not given");
      command->callback([options] { run_compare(*options); });
    }};

}  // namespace
}  // namespace relume
