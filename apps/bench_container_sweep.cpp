// Implementation of the residual points of `relume bench --container`.
#include "bench_container_sweep.hpp"

#include <algorithm>

#include "error.hpp"
#include "field_io.hpp"
#include "reconstruct_field.hpp"
#include "residual_selection.hpp"

namespace relume {
namespace {

// `field` with each residual row cut to its first `cap` entries (its largest ones).
CompressedField with_residual_cap(const CompressedField& field, int cap) {
  CompressedField capped = field;
  const ResidualRows& full = field.residual;
  ResidualRows& rows = capped.residual;
  rows.light_index.clear();
  rows.values.clear();
  for (std::size_t s = 0; s < full.rows(); ++s) {
    const std::uint32_t begin = full.row_offsets[s];
    const std::uint32_t end = std::min<std::uint32_t>(full.row_offsets[s + 1], begin + cap);
    rows.row_offsets[s] = std::uint32_t(rows.values.size());
    rows.light_index.insert(rows.light_index.end(), full.light_index.begin() + begin,
                            full.light_index.begin() + end);
    rows.values.insert(rows.values.end(), full.values.begin() + begin, full.values.begin() + end);
  }
  rows.row_offsets[full.rows()] = std::uint32_t(rows.values.size());
  return capped;
}

}  // namespace

std::vector<ResidualPoint> container_sweep_points(const CompressedField& container,
                                                  const std::filesystem::path& container_path,
                                                  const std::string& original_field,
                                                  unsigned threads) {
  std::vector<ResidualPoint> points;
  for (const double percent : {0.0, 3.0, 5.0, 10.0, 20.0, 30.0})
    points.push_back({ResidualBudget{0, percent}.entries_for(container.lights), percent, {}});
  points.push_back({full_residual, {}, {}});

  if (original_field.empty()) {
    for (ResidualPoint& point : points)
      point.error =
          point.cap == full_residual
              ? relative_error(container, container, threads).mean
              : relative_error(container, with_residual_cap(container, point.cap), threads).mean;
    return points;
  }
  FieldLoadOptions load;
  load.threads = threads;
  const ReflectanceField original = load_field(original_field, load);
  for (ResidualPoint& point : points) {
    try {
      point.error =
          relative_error(original, container, true,
                         point.cap == full_residual ? all_residual_entries : point.cap, threads)
              .mean;
    } catch (const Error& error) {
      throw Error("--field " + original_field + " does not match the container " +
                  container_path.string() + ": " + error.what());
    }
  }
  return points;
}

}  // namespace relume
