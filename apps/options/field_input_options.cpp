// Implementation of the shared field input options.
#include "options/field_input_options.hpp"

#include "core/console.hpp"
#include "field/field_source.hpp"
#include "field/input_encoding.hpp"

namespace relume {

void add_field_input_options(CLI::App& command, FieldInputOptions& options) {
  auto* mask = command.add_option(
      "--mask", options.mask_file,
      "Object mask for the input (an image of its size, non-zero = inside), for any input "
      "(an .lp capture too); replaces a folder's mask.png. Pixels outside are not stored and "
      "relight to black");
  auto* no_mask = command.add_flag(
      "--no-mask", options.no_mask,
      "Ignore the folder's mask.png: every pixel is inside (the background is kept)");
  mask->excludes(no_mask);
  no_mask->excludes(mask);
  auto* encoding = command
                       .add_option("--input-encoding", options.input_encoding,
                                   "How 8-bit input images are decoded: auto (float and 16-bit "
                                   "images and DiLiGenT folders linear; other 8-bit JPEG/PNG "
                                   "sRGB unless they declare linear), linear or srgb")
                       ->capture_default_str()
                       ->check(CLI::IsMember({"auto", "linear", "srgb"}));
  auto* linear = command.add_flag("--linear", options.linear,
                                  "Short for --input-encoding linear (8-bit values are linear)");
  auto* srgb = command.add_flag("--srgb", options.srgb,
                                "Short for --input-encoding srgb (8-bit values are sRGB-encoded)");
  linear->excludes(srgb)->excludes(encoding);
  srgb->excludes(linear)->excludes(encoding);
  encoding->excludes(linear)->excludes(srgb);
}

std::string requested_encoding(const FieldInputOptions& options) {
  return options.linear ? "linear" : options.srgb ? "srgb" : options.input_encoding;
}

FieldLoadOptions input_load_options(const std::string& input, const FieldInputOptions& options,
                                    unsigned threads) {
  const FieldSource source = describe_field(input);
  const InputEncodingDecision decision =
      decide_input_encoding(source, parse_input_encoding(requested_encoding(options)));
  note("%s: input %s", input.c_str(), decision.reason.c_str());
  FieldLoadOptions load;
  load.image.eight_bit = decision.encoding;
  load.threads = threads;
  load.mask_file = options.mask_file;
  load.use_mask = !options.no_mask;
  return load;
}

}  // namespace relume
