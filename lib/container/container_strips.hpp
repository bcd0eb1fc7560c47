// Writing a container for a compressed field held in strips of pixel rows (a streamed
// compression's, whose stored rows do not fit in memory): the strips are encoded one at a time,
// the sections with an entry per stored row go to raw files in a scratch folder, and each is
// coded from its file into the container (container/section_file_coding.hpp). The file holds the
// same field write_container would write for the strips stacked, and is written atomically too.
#pragma once

#include <filesystem>
#include <functional>
#include <relume/container.hpp>
#include <vector>

namespace relume {

struct CompressedFieldStrips {
  // The field without its stored rows: size, lights, mask, dark pixels and model, bases and
  // quantization (no stored_function, cluster, weights or residual).
  CompressedField shell;
  // Strip s is pixel rows [first_rows[s], first_rows[s + 1]) (the last one ends at the field's
  // height); first_rows[0] is 0.
  std::vector<int> first_rows;
  // Strip s as compressed_rows (model/compressed_field_rows.hpp) would cut it out of the whole
  // field, as stored (quantized). Called twice for each strip.
  std::function<CompressedField(std::size_t s)> strip;
};

// Writes `strips` to `path`; raw sections are kept in `scratch_folder` while it writes, and coded
// on options.coding_threads threads. Returns the layout written. Throws Error as write_container
// does (naming the strip's pixel rows for an inconsistent or unstorable strip); nothing is left at
// `path` or in the scratch folder then.
ContainerLayout write_container_strips(const std::filesystem::path& path,
                                       const CompressedFieldStrips& strips,
                                       const ContainerOptions& options,
                                       const std::filesystem::path& scratch_folder);

}  // namespace relume
