// The options of `relume compress`, bound to relume::CompressOptions (relume/compress.hpp), which
// holds every default once: the --help shows them as the library has them.
#pragma once

#include <CLI/CLI.hpp>
#include <relume/compress.hpp>
#include <string>
#include <vector>

#include "options/field_input_options.hpp"

namespace relume {

struct CompressArguments {
  std::vector<std::string> inputs;
  std::string output;
  std::string report;
  std::string residual = compress_defaults().residual.describe();  // parsed into options
  FieldInputOptions field_input;  // the mask and the encoding, as relight reads them
  CompressOptions options;
};

// Adds every option of the command to `command`, bound to `arguments`.
void add_compress_options(CLI::App& command, CompressArguments& arguments);

// `arguments.options` completed from the options given as text (residual, mask, encoding).
// Throws Error naming a bad value.
CompressOptions compress_options(const CompressArguments& arguments);

}  // namespace relume
