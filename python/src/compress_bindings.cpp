// relume.CompressOptions, relume.compress and relume.compress_file: the library's one compression
// run (relume/compress.hpp) with its options as keyword arguments. The options and their defaults
// are relume::CompressOptions' own, bound attribute by attribute under the names the command's
// options have (--target-bytes-per-pixel is target_bytes_per_pixel); python/relume.pyi lists
// them and a test keeps the two equal. The GIL is released and Ctrl-C honoured (python_work.hpp).
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <memory>
#include <nlohmann/json.hpp>
#include <relume/compress.hpp>
#include <relume/error.hpp>

#include "arrays.hpp"
#include "bindings.hpp"
#include "compressed_object.hpp"
#include "core/json_report.hpp"
#include "core/memory_budget.hpp"
#include "errors.hpp"
#include "python_work.hpp"

namespace relume::python {

using namespace pybind11::literals;

namespace {

// residual=: a count (int) or the text `relume compress --residual` takes ("12", "5%").
ResidualBudget residual_budget(py::handle residual) {
  if (py::isinstance<py::str>(residual)) return ResidualBudget::parse(residual.cast<std::string>());
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

// The residual budget as Python gives it: a count as an int, a percentage as its text.
py::object residual_value(const ResidualBudget& budget) {
  if (budget.percent < 0) return py::int_(budget.entries);
  return py::str(budget.describe());
}

// memory_limit=: bytes (an int) or a size text ("8G", "512M"); 0 for the process's budget.
std::uint64_t memory_limit(py::handle limit) {
  if (py::isinstance<py::str>(limit)) return parse_byte_size(limit.cast<std::string>());
  const long long bytes = limit.cast<long long>();
  if (bytes < 0) throw Error("memory_limit must be >= 0 bytes, got " + std::to_string(bytes));
  return std::uint64_t(bytes);
}

// The options named in `given` set on the defaults; Error naming an unknown option.
CompressOptions options_from(const py::kwargs& given) {
  py::object options = py::cast(CompressOptions{});
  for (const auto& [name, value] : given) {
    const std::string key = py::str(name);
    if (key == "progress" || !py::hasattr(options, key.c_str()))
      throw Error("unknown compress option '" + key + "' (relume.CompressOptions lists them)");
    py::setattr(options, name, value);
  }
  return options.cast<CompressOptions>();
}

// Writes `report` (its JSON) to `path` as `relume compress --report` does; None: nothing.
void write_report(py::object path, const CompressionReport& report) {
  if (path.is_none()) return;
  const std::string target = py::str(path);
  with_file_errors([&] { write_json_report(target, nlohmann::ordered_json::parse(report.json)); });
}

py::object report_dict(const CompressionReport& report) {
  return py::module_::import("json").attr("loads")(report.json);
}

void bind_options(py::module_& module) {
  py::class_<CompressOptions> options(module, "CompressOptions", R"(Every option of
relume.compress, relume.compress_file and `relume compress`, with its default (the command's
--help explains each; the names are its options' with _ for -). Give them to compress as keyword
arguments; relume.CompressOptions() shows the defaults.)");
  options.def(py::init([](const py::kwargs& given) { return options_from(given); }));
#define RELUME_OPTION(name) options.def_readwrite(#name, &CompressOptions::name)
  RELUME_OPTION(method);
  RELUME_OPTION(pca_center);
  RELUME_OPTION(pca_iterations);
  RELUME_OPTION(trimmed_refit);
  RELUME_OPTION(refit_chooses_clusters);
  RELUME_OPTION(clusters);
  RELUME_OPTION(terms);
  RELUME_OPTION(residual_allocation);
  RELUME_OPTION(noise_floor);
  RELUME_OPTION(threshold);
  RELUME_OPTION(solver);
  RELUME_OPTION(transform);
  RELUME_OPTION(light_weighting);
  RELUME_OPTION(channel_clusters);
  RELUME_OPTION(multires);
  RELUME_OPTION(refine);
  RELUME_OPTION(iterations);
  RELUME_OPTION(candidates);
  RELUME_OPTION(irls_iterations);
  RELUME_OPTION(min_cluster_size);
  RELUME_OPTION(max_cluster_size);
  RELUME_OPTION(seed);
  RELUME_OPTION(threads);
  RELUME_OPTION(assign);
  RELUME_OPTION(device);
  RELUME_OPTION(weights_precision);
  RELUME_OPTION(residual_precision);
  RELUME_OPTION(bases_precision);
  RELUME_OPTION(quantization_budget);
  RELUME_OPTION(term_budget);
  RELUME_OPTION(target_error);
  RELUME_OPTION(target_bytes);
  RELUME_OPTION(target_bytes_per_pixel);
  RELUME_OPTION(target_psnr);
  RELUME_OPTION(target_region);
  RELUME_OPTION(target_models);
  RELUME_OPTION(psnr_white);
  RELUME_OPTION(use_mask);
  RELUME_OPTION(input_encoding);
  RELUME_OPTION(resume);
  RELUME_OPTION(quiet);
#undef RELUME_OPTION
  // Paths as text: "" is none (a pathlib.Path would show it as ".").
  const auto path_option = [&](const char* name, std::filesystem::path CompressOptions::*member) {
    options.def_property(
        name, [member](const CompressOptions& o) { return (o.*member).string(); },
        [member](CompressOptions& o, const std::filesystem::path& value) { o.*member = value; });
  };
  path_option("psnr_mask", &CompressOptions::psnr_mask);
  path_option("mask_file", &CompressOptions::mask_file);
  path_option("scratch", &CompressOptions::scratch);
  options.def_property(
      "residual", [](const CompressOptions& o) { return residual_value(o.residual); },
      [](CompressOptions& o, py::handle value) { o.residual = residual_budget(value); });
  options.def_property(
      "memory_limit", [](const CompressOptions& o) { return o.memory_limit; },
      [](CompressOptions& o, py::handle value) { o.memory_limit = memory_limit(value); });
}

}  // namespace

void bind_compress(py::module_& module) {
  bind_options(module);
  module.def(
      "compress",
      [](py::object field, py::object dirs, py::object mask, py::object intensities,
         py::object report, py::object progress, const py::kwargs& given) {
        std::optional<ReflectanceField> from_arrays;
        if (!py::isinstance<ReflectanceField>(field))
          from_arrays = field_from(field, dirs, mask, intensities);
        else if (!dirs.is_none() || !mask.is_none() || !intensities.is_none())
          throw Error(
              "dirs, mask and intensities are for a field given as an array; a "
              "relume.Field has its own");
        const ReflectanceField& input =
            from_arrays ? *from_arrays : field.cast<const ReflectanceField&>();
        CompressOptions options = options_from(given);
        PythonProgress watcher(std::move(progress));
        options.progress = watcher.listener();
        CompressionResult result =
            watcher.run([&] { return relume::compress_with_report(input, options); });
        write_report(report, result.report);
        auto compressed = std::make_unique<CompressedObject>();
        compressed->field = std::move(result.field);
        compressed->storage = result.container;
        return compressed;
      },
      "field"_a, "dirs"_a = py::none(), py::kw_only(), "mask"_a = py::none(),
      "intensities"_a = py::none(), "report"_a = py::none(), "progress"_a = py::none(),
      R"(Compress a reflectance field in memory by clustered sparse residual factorization, by
the run `relume compress` makes (same options, same defaults, same result for the same seed):
rate targets (target_bytes_per_pixel=0.5, target_psnr=40), the quantized storage and the error
measures included. save() writes the container the command would.

field: a relume.Field, or values float32 (height, width, channels, lights) with dirs
(lights, 3) and optionally mask (height, width) and intensities (lights, 3); the array is
copied once into a field.
report: a path that receives the JSON report, as `relume compress --report` writes it.
progress: called as progress(phase, fraction) on this thread about every 0.1 s, e.g.
("compress: iteration 2, assigning", 0.4).
Every other keyword is an option of relume.CompressOptions, e.g. clusters=64, terms=4,
residual="5%" (or a count), assign="cpu", target_psnr=40, memory_limit="8G".

The GIL is released while compressing. Ctrl-C (or an exception from progress) stops it:
the exception is raised and nothing is returned. Raises relume.Error for bad options or
arrays.)");

  module.def(
      "compress_file",
      [](const std::filesystem::path& input, const std::filesystem::path& output, py::object report,
         py::object progress, const py::kwargs& given) {
        CompressOptions options = options_from(given);
        PythonProgress watcher(std::move(progress));
        options.progress = watcher.listener();
        const CompressionReport result = watcher.run([&] {
          return with_file_errors([&] { return compress_file(input.string(), output, options); });
        });
        write_report(report, result);
        return report_dict(result);
      },
      "input"_a, "output"_a, py::kw_only(), "report"_a = py::none(), "progress"_a = py::none(),
      R"(Compress a field folder or .lp file into the container `output`, exactly as
`relume compress INPUT -o OUTPUT` does (the same bytes for the same options): planned within the
memory budget (memory_limit=, else the available memory; a field that does not fit is read in
strips), checkpointed (resume=True continues from OUTPUT.checkpoint), 8-bit images decoded as the
command decodes them (input_encoding="auto"). Returns the report as a dict; report= also writes
it as JSON. Options as relume.compress takes them.)");
}

}  // namespace relume::python
