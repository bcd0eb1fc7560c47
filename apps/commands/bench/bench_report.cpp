// Implementation of the bench report's field, sweep and device parts.
#include "commands/bench/bench_report.hpp"

namespace relume {

nlohmann::ordered_json field_json(const BenchOptions& options, const CompressedField& field) {
  const auto& shape = options.shape;
  if (options.container.empty())
    return {{"source", "random"},
            {"width", shape.width},
            {"height", shape.height},
            {"channels", shape.channels},
            {"lights", shape.lights},
            {"clusters", shape.clusters},
            {"terms", shape.terms},
            {"residual_per_function", shape.residual_per_function},
            {"stored_fraction", shape.stored_fraction},
            {"precision", options.precision},
            {"stored_rows", field.stored_rows()},
            {"seed", shape.seed}};
  return {{"source", "container"},
          {"path", options.container},
          {"width", field.width},
          {"height", field.height},
          {"channels", field.channels},
          {"lights", field.lights},
          {"clusters", field.clusters},
          {"terms", field.terms},
          {"stored_rows", field.stored_rows()},
          {"residual_entries", field.residual.nonzeros()}};
}

nlohmann::ordered_json sweep_json(const BenchOptions& options, const RelightSubject& subject) {
  nlohmann::ordered_json points = nlohmann::ordered_json::array();
  for (const ResidualPoint& point : subject.points)
    points.push_back({{"residual_percent", point.percent ? nlohmann::ordered_json(*point.percent)
                                                         : nlohmann::ordered_json("all")},
                      {"residual_cap", residual_cap_json(point.cap)},
                      {"error", *point.error}});
  return {{"error_against", options.original_field.empty() ? "container" : "field"},
          {"original_field", options.original_field.empty()
                                 ? nlohmann::ordered_json()
                                 : nlohmann::ordered_json(options.original_field)},
          {"points", points}};
}

nlohmann::ordered_json device_json(const OpenClDevice& device) {
  return {{"platform", device.platform_name},
          {"device", device.device_name},
          {"type", device.type},
          {"version", device.version},
          {"driver_version", device.driver_version},
          {"compute_units", device.compute_units},
          {"global_memory_bytes", device.global_memory_bytes}};
}

}  // namespace relume
