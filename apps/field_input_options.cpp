// Implementation of the shared field input options.
#include "field_input_options.hpp"

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
}

std::string describe_field_input(const FieldInputOptions& options) {
  return "mask " + (options.no_mask             ? std::string("none")
                    : options.mask_file.empty() ? std::string("the folder's")
                                                : options.mask_file);
}

FieldLoadOptions field_load_options(const FieldInputOptions& options, unsigned threads) {
  FieldLoadOptions load;
  load.threads = threads;
  load.mask_file = options.mask_file;
  load.use_mask = !options.no_mask;
  return load;
}

}  // namespace relume
