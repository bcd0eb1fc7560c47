// Implementation of the eval's JSON summary (see eval_summary.hpp).
#include "commands/eval/eval_summary.hpp"

namespace relume {
namespace {

nlohmann::ordered_json method_errors(const MethodErrors& at) {
  nlohmann::ordered_json errors = nlohmann::ordered_json::object();
  for (const auto& [method, error] : at.errors) errors[method] = error;
  return errors;
}

nlohmann::ordered_json settings_json(const EvaluationResult& result) {
  const EvaluationOptions& settings = result.settings;
  return {{"clusters", settings.clusters},
          {"terms", settings.terms},
          {"entries", settings.entries},
          {"refit_entries", settings.refit_entries},
          {"refit_rounds", settings.refit_rounds},
          {"rate_entries", settings.rate_entries},
          {"methods", settings.methods},
          {"primary", std::to_string(settings.primary_clusters) + "x" +
                          std::to_string(settings.primary_terms)},
          {"pca_iterations", settings.pca_iterations},
          {"quantization_budget", settings.quantization_budget},
          {"psnr_white", settings.psnr_white},
          {"seed", settings.seed},
          {"assignment", result.assignment}};
}

}  // namespace

nlohmann::ordered_json eval_summary(const std::string& input, const ReflectanceField& field,
                                    const std::string& environment, const EvaluationResult& result,
                                    const EvalFiles& files, const std::vector<std::string>& plots,
                                    double seconds) {
  const EvaluationOptions& settings = result.settings;
  nlohmann::ordered_json configurations = nlohmann::ordered_json::array();
  for (const ConfigurationErrors& configuration : result.configurations) {
    nlohmann::ordered_json entry = {{"clusters", configuration.clusters},
                                    {"terms", configuration.terms}};
    for (const MethodErrors* at :
         {&configuration.without_residual, &configuration.at_compare_entries})
      entry["error_at_" + std::to_string(at->entries) + "_entries"] = method_errors(*at);
    configurations.push_back(entry);
  }
  const ErrorDifference& difference = result.difference;
  return {{"input", input},
          {"field",
           {{"width", field.width},
            {"height", field.height},
            {"channels", field.channels},
            {"lights", field.lights()},
            {"stored_functions", result.stored_functions},
            {"noise_sigma", result.noise.sigma},
            {"dark_threshold", result.noise.threshold},
            {"dark_pixels", result.dark_pixels}}},
          {"settings", settings_json(result)},
          {"classes",
           {{"rule",
             "diffuse when max(0, a + b.l) over the light directions l, a and b fitted in least "
             "squares over the lights above 5% of the function's largest value, leaves at most "
             "`threshold` of the function's energy"},
            {"threshold", result.classes.threshold},
            {"diffuse", result.classes.diffuse_count},
            {"specular_or_shadowed", result.stored_functions - result.classes.diffuse_count}}},
          {"error_measure",
           "paper Eq. 16 over the stored functions (masked, non-zero, not of a dark pixel at or "
           "below the field's noise floor), float values (rate_distortion.csv: as the containers "
           "store them, dark pixels included)"},
          {"configurations", configurations},
          {"error_difference",
           {{"entries", settings.compare_entries},
            {"pixels", difference.pixels},
            {"fraction_where_relume_is_better",
             difference.pixels ? double(difference.l1_better) / double(difference.pixels) : 0.0}}},
          {"relighting",
           {{"device", result.relighting.device},
            {"frames", settings.frames},
            {"timed_calls", settings.timed_calls}}},
          {"images",
           {{"environment", environment},
            {"rotate", settings.rotate_degrees},
            {"entries", settings.compare_entries},
            {"reference", files.reference},
            {"relit", files.relit},
            {"difference10", files.difference10}}},
          {"files", {{"csv", files.csv}, {"npy", files.npy}, {"plots", plots}}},
          {"seconds", seconds}};
}

}  // namespace relume
