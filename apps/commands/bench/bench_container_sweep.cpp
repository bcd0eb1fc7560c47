// Implementation of the residual points of `relume bench --container`.
#include "commands/bench/bench_container_sweep.hpp"

#include <relume/error.hpp>
#include <relume/field.hpp>

#include "compress/residual_selection.hpp"
#include "container/container.hpp"
#include "model/reconstruct_field.hpp"

namespace relume {

namespace {

std::vector<ResidualPoint> container_sweep_points(const CompressedField& container,
                                                  const std::filesystem::path& container_path,
                                                  const std::string& original_field,
                                                  unsigned threads) {
  std::vector<ResidualPoint> points;
  for (const double percent : {0.0, 3.0, 5.0, 10.0, 20.0, 30.0})
    points.push_back({ResidualBudget{0, percent}.entries_for(container.lights), percent, {}});
  points.push_back({all_residual_entries, {}, {}});

  if (original_field.empty()) {
    for (ResidualPoint& point : points)
      point.error = relative_error(container, container, point.cap, threads).mean;
    return points;
  }
  FieldLoadOptions load;
  load.threads = threads;
  const ReflectanceField original = load_field(original_field, load);
  for (ResidualPoint& point : points) {
    try {
      point.error = relative_error(original, container, true, point.cap, threads).mean;
    } catch (const Error& error) {
      throw Error("--field " + original_field + " does not match the container " +
                  container_path.string() + ": " + error.what());
    }
  }
  return points;
}

}  // namespace

ContainerSweep container_sweep(const std::filesystem::path& container_path,
                               const std::string& original_field, unsigned threads) {
  ContainerSweep sweep;
  sweep.field = read_container(container_path);
  sweep.points = container_sweep_points(sweep.field, container_path, original_field, threads);
  return sweep;
}

}  // namespace relume
