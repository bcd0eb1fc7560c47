// Implementation of the evaluation's settings checks (see evaluation_options.hpp).
#include "eval/evaluation_options.hpp"

#include <algorithm>
#include <relume/error.hpp>

namespace relume {
namespace {

// Ascending, without repeats; throws Error naming `option` for a value below `minimum`.
std::vector<int> sorted_list(std::vector<int> values, const std::string& option, int minimum) {
  if (values.empty()) throw Error(option + " needs at least one value");
  for (const int value : values)
    if (value < minimum)
      throw Error(option + " value " + std::to_string(value) +
                  " (expected >= " + std::to_string(minimum) + ")");
  std::sort(values.begin(), values.end());
  values.erase(std::unique(values.begin(), values.end()), values.end());
  return values;
}

bool contains(const std::vector<int>& values, int value) {
  return std::find(values.begin(), values.end(), value) != values.end();
}

}  // namespace

EvaluationOptions resolve_evaluation_options(EvaluationOptions options) {
  options.clusters = sorted_list(options.clusters, "--clusters", 1);
  options.terms = sorted_list(options.terms, "--terms", 1);
  options.entries = sorted_list(options.entries, "--entries", 0);
  options.refit_entries = has_method(options.methods, "l1-refit")
                              ? sorted_list(options.refit_entries, "--refit-entries", 0)
                              : std::vector<int>{};
  options.rate_entries = options.rate_entries.empty()
                             ? options.entries
                             : sorted_list(options.rate_entries, "--rate-entries", 0);
  for (const std::string& method : options.methods)
    if (!has_method(evaluation_methods, method))
      throw Error("--methods: unknown method '" + method + "' (expected l1, cpca, cpca-mean, " +
                  "l1-refit)");
  if (!has_method(options.methods, "l1") || !has_method(options.methods, "cpca"))
    throw Error("--methods must include l1 and cpca, the two methods every table compares");
  if (options.compare_entries < 0)
    throw Error("--compare-entries " + std::to_string(options.compare_entries) +
                " (expected >= 0)");
  if (options.refit_rounds < 0)
    throw Error("--refit-rounds " + std::to_string(options.refit_rounds) + " (expected >= 0)");
  if (options.frames < 1 || options.timed_calls < 1)
    throw Error("--frames and --timed-calls must be >= 1, got " + std::to_string(options.frames) +
                " and " + std::to_string(options.timed_calls));
  if (options.assign != "opencl" && options.assign != "cpu")
    throw Error("--assign must be 'opencl' or 'cpu', got '" + options.assign + "'");
  if (!options.primary_clusters) options.primary_clusters = options.clusters.back();
  if (!options.primary_terms) options.primary_terms = options.terms.back();
  if (!contains(options.clusters, options.primary_clusters) ||
      !contains(options.terms, options.primary_terms))
    throw Error("--primary '" + std::to_string(options.primary_clusters) + "x" +
                std::to_string(options.primary_terms) +
                "' is not a configuration of the grid (--clusters and --terms)");
  return options;
}

}  // namespace relume
