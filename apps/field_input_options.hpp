// The options that say how an uncompressed field is read, shared by `compress` and `relight`:
// the object mask (`--mask FILE` for any input, replacing a folder's mask.png; `--no-mask` keeps
// every pixel).
#pragma once

#include <CLI/CLI.hpp>
#include <relume/field.hpp>
#include <string>

namespace relume {

struct FieldInputOptions {
  std::string mask_file;
  bool no_mask = false;
};

void add_field_input_options(CLI::App& command, FieldInputOptions& options);

// The options as one line ("mask the folder's"), for checkpoint fingerprints.
std::string describe_field_input(const FieldInputOptions& options);

// The load options these options ask for, with `threads` workers.
FieldLoadOptions field_load_options(const FieldInputOptions& options, unsigned threads);

}  // namespace relume
