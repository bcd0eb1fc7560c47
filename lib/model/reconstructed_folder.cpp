// Implementation of the strip-by-strip reconstruction into a field folder.
#include "model/reconstructed_folder.hpp"

#include <algorithm>
#include <vector>

#include "core/parallel.hpp"
#include "model/compressed_field_checks.hpp"
#include "model/reconstruct_field.hpp"

namespace relume {

std::size_t reconstructed_folder_memory(const CompressedField& field) {
  // One strip of values (field_folder_writer.hpp), at least one whole row of pixels.
  const std::size_t row = std::size_t(field.width) * field.channels * field.lights * sizeof(float);
  return std::max<std::size_t>(StripLimits{}.strip_bytes, row) +
         std::size_t(field.functions()) * sizeof(std::int64_t);
}

void write_reconstructed_folder(const std::filesystem::path& folder, const CompressedField& field,
                                int residual_cap, const StripLimits& limits) {
  check_residual_cap(residual_cap);
  validate_compressed_field(field, "cannot reconstruct the compressed field");
  const std::vector<std::int64_t> row_of = stored_row_of_function(field);
  const int lights = field.lights, channels = field.channels;
  const FieldFolderLayout layout{field.width,      field.height,      channels,
                                 field.directions, field.intensities, field.mask};
  const std::size_t row_functions = std::size_t(field.width) * channels;
  write_field_folder_in_strips(
      folder, layout,
      [&](int first_row, int rows, int first_light, int count, float* values) {
        const std::size_t functions = std::size_t(rows) * row_functions;
        const unsigned workers = resolve_thread_count(0);
        std::vector<std::vector<double>> sums(workers, std::vector<double>(lights));
        std::vector<std::vector<float>> rebuilt(workers, std::vector<float>(lights));
        parallel_for(functions, 0, [&](std::size_t f, unsigned worker) {
          const std::int64_t p = std::int64_t(first_row * row_functions + f);
          reconstruct_function(field, row_of[std::size_t(p)], residual_cap, sums[worker].data(),
                               rebuilt[worker].data());
          for (int l = 0; l < count; ++l)
            values[std::size_t(l) * functions + f] = rebuilt[worker][first_light + l];
        });
      },
      limits);
}

}  // namespace relume
