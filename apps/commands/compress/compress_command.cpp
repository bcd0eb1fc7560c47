// `relume compress`: clustered sparse residual factorization of one or more reflectance fields
// into .relume containers by the library's compression run (relume/compress.hpp: compress_file),
// with a JSON report per run, checkpoints after every clustering iteration (--resume continues
// an interrupted run) and, with several inputs, one container per input in the output folder: a
// failing input is reported and the others still run. This file parses, checks outputs and prints.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <relume/error.hpp>

#include "command_registry.hpp"
#include "commands/compress/compress_options.hpp"
#include "compress/compress_settings.hpp"
#include "compress/compression_run.hpp"
#include "core/atomic_file.hpp"
#include "core/console.hpp"
#include "core/json_report.hpp"
#include "core/ranks.hpp"
#include "options/output_paths.hpp"

namespace relume {
namespace {

namespace fs = std::filesystem;

// OUT/<input name>.relume for one of several inputs.
fs::path output_for(const fs::path& folder, const std::string& input) {
  fs::path name = fs::path(input).lexically_normal();
  if (name.filename().empty()) name = name.parent_path();
  const std::string stem =
      name.extension() == ".lp" ? name.stem().string() : name.filename().string();
  return folder / (stem + ".relume");
}

// The container of each input, checked before any work: none may exist (without -y), and two
// inputs of one name (scans/a and other/a) would write the same OUT/a.relume: refused.
std::vector<fs::path> output_paths(const CompressArguments& arguments) {
  check_new_output(arguments.report);
  const bool several = arguments.inputs.size() > 1;
  if (several) {
    check_output_folder_location(arguments.output);
  } else {
    check_output_file_location(arguments.output);
    check_output_file_location(arguments.output + ".checkpoint");
  }
  if (!arguments.report.empty()) check_output_file_location(arguments.report);
  if (several && fs::exists(arguments.output) && !fs::is_directory(arguments.output))
    throw Error("with several inputs -o names a folder, but " + arguments.output + " is a file");
  std::vector<fs::path> outputs;
  for (const std::string& input : arguments.inputs) {
    const fs::path output =
        several ? output_for(arguments.output, input) : fs::path(arguments.output);
    for (std::size_t j = 0; j < outputs.size(); ++j)
      if (outputs[j] == output)
        throw Error("inputs " + arguments.inputs[j] + " and " + input + " would both write " +
                    output.string() + ": compress them into different folders");
    if (!(arguments.options.resume && fs::exists(output.string() + ".checkpoint")))
      check_new_output(output);
    outputs.push_back(output);
  }
  return outputs;
}

// One input's run; its report, printed, or null on the ranks that do not report.
nlohmann::ordered_json compress_one(const std::string& input, const fs::path& output,
                                    const CompressOptions& options, OpenClAssigner* assigner) {
  const CompressionReport report = compress_file_with(input, output, options, assigner);
  if (report.json.empty()) return nullptr;
  say("%s", report.summary.c_str());
  const auto json = nlohmann::ordered_json::parse(report.json);
  for (const auto& [phase, seconds] : json["phases_seconds"].items())
    detail("compress: %-22s %8.2f s", phase.c_str(), seconds.get<double>());
  return json;
}

void run_compress(const CompressArguments& arguments) {
  CompressOptions options = compress_options(arguments);
  options.quiet = verbosity() == Verbosity::quiet;
  // Options and outputs are checked before any field is loaded: a typo costs no clustering.
  compress_settings(options);
  const std::vector<fs::path> outputs = output_paths(arguments);
  const std::unique_ptr<OpenClAssigner> assigner = assigner_for(options);

  const bool several = arguments.inputs.size() > 1;
  if (several) fs::create_directories(arguments.output);
  nlohmann::ordered_json reports = nlohmann::ordered_json::array();
  nlohmann::ordered_json failures = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < arguments.inputs.size(); ++i) {
    const std::string& input = arguments.inputs[i];
    // Under mpirun a failure ends every rank (the others would wait for it): no catching.
    if (!several || process_ranks().size() > 1) {
      reports.push_back(compress_one(input, outputs[i], options, assigner.get()));
      continue;
    }
    try {
      reports.push_back(compress_one(input, outputs[i], options, assigner.get()));
    } catch (const Interrupted&) {
      throw;  // an interruption stops the whole batch
    } catch (const std::exception& e) {
      std::fprintf(stderr, "relume: compress: %s failed: %s\n", input.c_str(), e.what());
      failures.push_back({{"input", input}, {"error", e.what()}});
    }
  }
  if (!arguments.report.empty() && process_ranks().root()) {
    const nlohmann::ordered_json document =
        several ? nlohmann::ordered_json{{"runs", reports}, {"failed", failures}} : reports[0];
    write_json_report(arguments.report, document);
  }
  if (!failures.empty())
    throw Error(std::to_string(failures.size()) + " of " + std::to_string(arguments.inputs.size()) +
                " inputs failed (see the messages above)");
}

const CommandRegistration registration{
    20, [](CLI::App& app) {
      auto arguments = std::make_shared<CompressArguments>();
      auto* command = app.add_subcommand(
          "compress",
          "Compress reflectance fields (field folders or .lp files) by clustered sparse residual\n"
          "factorization into .relume containers, with an optional JSON report");
      command->footer(
          "Examples:\n"
          "  relume compress scans/ball -o ball.relume --report ball.json\n"
          "  relume compress capture/dirs.lp -o lion.relume --target-bytes-per-pixel 0.5\n"
          "  relume compress a b c -o out/ --clusters 32 --terms 3 --residual 4");
      add_compress_options(*command, *arguments);
      command->callback([arguments] { run_compress(*arguments); });
    }};

}  // namespace
}  // namespace relume
