// relume.compress: `relume compress` on a relume.Field or arrays, its options as keyword
// arguments, with a progress callback, the GIL released and Ctrl-C honoured (python_work.hpp).
#include <pybind11/stl.h>

#include <nlohmann/json.hpp>
#include <optional>
#include <relume/compress.hpp>
#include <relume/error.hpp>

#include "arrays.hpp"
#include "bindings.hpp"
#include "compress/residual_selection.hpp"
#include "compressed_object.hpp"
#include "container/container.hpp"
#include "python_work.hpp"

namespace relume::python {

using namespace pybind11::literals;

namespace {

// residual=: a count (int) or the text `relume compress --residual` takes ("12", "5%").
ResidualBudget residual_budget(py::handle residual) {
  if (py::isinstance<py::str>(residual)) return parse_residual_budget(residual.cast<std::string>());
  if (py::isinstance<py::int_>(residual) && !py::isinstance<py::bool_>(residual)) {
    const long long count = residual.cast<long long>();
    if (count < 0 || count > (1 << 24))
      throw Error("residual must be a count of entries per function >= 0, got " +
                  std::to_string(count));
    return ResidualBudget{static_cast<int>(count)};
  }
  throw Error(
      "residual must be a count of entries per function (an int) or a text such as "
      "'5%' (a percentage of the lights), got " +
      std::string(py::str(py::repr(residual))));
}

std::string one_of(const std::string& what, const std::string& value, const char* first,
                   const char* second) {
  if (value != first && value != second)
    throw Error(what + " must be '" + first + "' or '" + second + "', got '" + value + "'");
  return value;
}

}  // namespace

void bind_compress(py::module_& module) {
  module.def(
      "compress",
      [](py::object field, py::object dirs, py::object mask, py::object intensities, int clusters,
         int terms, py::object residual, float threshold, float noise_floor,
         const std::string& solver, const std::string& transform, double light_weighting,
         int multires, int refine, int iterations, int candidates, int irls_iterations,
         std::optional<int> min_cluster_size, int max_cluster_size, std::uint64_t seed,
         unsigned threads, const std::string& assign, const std::string& device,
         const std::string& weights_precision, const std::string& residual_precision,
         const std::string& bases_precision, double quantization_budget, double term_budget,
         std::optional<double> target_error, bool quiet, py::object progress) {
        std::optional<ReflectanceField> from_arrays;
        if (!py::isinstance<ReflectanceField>(field))
          from_arrays = field_from(field, dirs, mask, intensities);
        else if (!dirs.is_none() || !mask.is_none() || !intensities.is_none())
          throw Error(
              "dirs, mask and intensities are for a field given as an array; a "
              "relume.Field has its own");
        const ReflectanceField& input =
            from_arrays ? *from_arrays : field.cast<const ReflectanceField&>();

        CompressOptions options;
        options.clusters = clusters;
        options.terms = terms;
        const ResidualBudget budget = residual_budget(residual);
        options.residual_entries = budget.percent < 0 ? budget.entries : -1;
        options.residual_percent = budget.percent < 0 ? 0.0 : budget.percent;
        options.residual_threshold = threshold;
        options.noise_floor = noise_floor;
        options.solver = solver;
        options.transform = one_of("transform", transform, "identity", "haar") == "haar"
                                ? BasisTransform::haar
                                : BasisTransform::identity;
        options.light_weighting = light_weighting;
        options.multires_levels = multires;
        options.refine_iterations = refine;
        options.iterations = iterations;
        options.candidates = candidates;
        options.irls_iterations = irls_iterations;
        options.min_cluster_size = min_cluster_size.value_or(-1);
        options.max_cluster_size = max_cluster_size;
        options.seed = seed;
        options.threads = threads;
        options.opencl_assignment = one_of("assign", assign, "opencl", "cpu") == "opencl";
        options.device = device;
        options.weights_precision = parse_value_precision(weights_precision);
        options.residual_precision = parse_value_precision(residual_precision);
        options.quantize_bases =
            one_of("bases_precision", bases_precision, "quantized", "float32") == "quantized";
        options.quantization_budget = quantization_budget;
        options.term_budget = term_budget;
        if (target_error && !(*target_error > 0))
          throw Error("target_error must be a relative error > 0 (or None), got " +
                      std::to_string(*target_error));
        options.target_error = target_error.value_or(0.0);
        options.quiet = quiet;

        PythonProgress watcher(std::move(progress));
        options.progress = watcher.listener();
        auto result = std::make_unique<CompressedObject>();
        result->field = watcher.run([&] { return relume::compress(input, options); });
        result->storage.weights = options.weights_precision;
        result->storage.residual = options.residual_precision;
        nlohmann::ordered_json parameters = {{"written_from", "python"},
                                             {"clusters_asked", clusters},
                                             {"clusters", result->field.clusters},
                                             {"terms", result->field.terms},
                                             {"residual", budget.describe()},
                                             {"residual_threshold", threshold},
                                             {"transform", transform},
                                             {"light_weighting", light_weighting},
                                             {"solver", solver},
                                             {"multires_levels", multires},
                                             {"refine_iterations", refine},
                                             {"max_iterations", iterations},
                                             {"candidates", candidates},
                                             {"seed", seed}};
        if (target_error) parameters["target_error"] = *target_error;
        result->storage.parameters_json = parameters.dump();
        return result;
      },
      "field"_a, "dirs"_a = py::none(), py::kw_only(), "mask"_a = py::none(),
      "intensities"_a = py::none(), "clusters"_a = 64, "terms"_a = 4, "residual"_a = "5%",
      "threshold"_a = -1.0f, "noise_floor"_a = -1.0f, "solver"_a = "irls",
      "transform"_a = "identity", "light_weighting"_a = 0.0, "multires"_a = 0, "refine"_a = 2,
      "iterations"_a = 4, "candidates"_a = 3, "irls_iterations"_a = 5,
      "min_cluster_size"_a = py::none(), "max_cluster_size"_a = 0, "seed"_a = 1, "threads"_a = 0,
      "assign"_a = "opencl", "device"_a = "", "weights_precision"_a = "quantized",
      "residual_precision"_a = "quantized", "bases_precision"_a = "quantized",
      "quantization_budget"_a = 0.01, "term_budget"_a = 0.0, "target_error"_a = py::none(),
      "quiet"_a = true, "progress"_a = py::none(),
      R"(Compress a reflectance field by clustered sparse residual factorization, as
`relume compress` does (same options, same defaults, same result for the same seed; the
command's -o, --report and --resume have no counterpart: save() writes the container).

field: a relume.Field, or values float32 (height, width, channels, lights) with dirs
(lights, 3) and optionally mask (height, width) and intensities (lights, 3); the array is
copied once into a field.
clusters, terms: K clusters of t basis functions each (t in 1..16, fewer than the lights).
residual: entries kept per function, a count (12) or a percentage of the lights ("5%").
threshold: drop residual entries with |value| <= threshold (field units; negative: the
noise floor). noise_floor: pixels whose every channel has an RMS at or below it share one dark
model (field units; negative: the field's own, its images' quantization step).
solver: "irls" (the fast IRLS fits only) or "lp-dual", "lp", "huber": refit every cluster
exactly with that solver after the iterations.
transform: "identity" or "haar" (the factorization in an orthonormal Haar basis).
light_weighting: exponent in [0, 1]; > 0 fits each light's image relative to its own energy
(0.5 halfway, 1 fully), so that dim lights (a sun behind the object) keep their accuracy, at a
higher Eq. 16 error (identity transform only).
multires: cluster a field downsampled 2x per level first, then refine full-resolution
iterations. iterations: cap on L1 iterations (they stop earlier once fewer than 0.2% of the
functions change cluster). candidates: clusters given the exact L1 fit per function.
irls_iterations: reweighted solves per IRLS fit. min_cluster_size (None: max(8, 2 terms)),
max_cluster_size (0: no limit): clusters merge or split to stay within them.
seed: of the cluster seeding. threads: 0 = all cores.
assign: where the reassignment fits run, "opencl" (device, a substring of "platform /
device"; "" = RELUME_DEVICE, else the first GPU, else PoCL) or "cpu" (the C++ path).
weights_precision, residual_precision: "quantized" (integers times the coarsest steps that
add at most quantization_budget, relative, to the Eq. 16 error), "float32" or "float16";
bases_precision: "quantized" (8 to 16 bits) or "float32". The result is what save() stores.
term_budget: with quantized storage, what dropping the basis terms that clusters of dim or
simple functions do not need may add to the Eq. 16 error, relative (0: all terms kept).
target_error: choose terms, clusters and per-function residual lengths that reach this
relative error (paper Eq. 16, masked functions) in the fewest bytes (clusters, terms and
residual are then not used).
quiet: no progress bars on stderr. progress: called as progress(phase, fraction) on this
thread about every 0.1 s, e.g. ("compress: iteration 2, assigning", 0.4).

The GIL is released while compressing. Ctrl-C (or an exception from progress) stops it:
the exception is raised and nothing is returned. Raises relume.Error for bad options or
arrays.)");
}

}  // namespace relume::python
