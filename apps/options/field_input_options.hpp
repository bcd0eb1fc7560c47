// The options that say how an uncompressed field is read, shared by `compress` and `relight`:
// the object mask (`--mask FILE` for any input, replacing a folder's mask.png; `--no-mask` keeps
// every pixel) and the encoding of 8-bit images (`--input-encoding auto|linear|srgb`, with
// `--linear` and `--srgb` as short forms).
#pragma once

#include <CLI/CLI.hpp>
#include <relume/field.hpp>
#include <string>

namespace relume {

struct FieldInputOptions {
  std::string mask_file;
  bool no_mask = false;
  std::string input_encoding = "auto";
  bool linear = false;
  bool srgb = false;
};

void add_field_input_options(CLI::App& command, FieldInputOptions& options);

// "auto", "linear" or "srgb", as --input-encoding, --linear or --srgb asked.
std::string requested_encoding(const FieldInputOptions& options);

// How `input` is read as the options say, with `threads` workers: decides the input encoding
// (once) and notes the decision with its reason. No progress callback
// (field/load_with_progress.hpp loads with one).
FieldLoadOptions input_load_options(const std::string& input, const FieldInputOptions& options,
                                    unsigned threads);

}  // namespace relume
