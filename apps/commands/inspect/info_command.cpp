// `relume info`: describes a .relume container (after verifying all of it): dimensions, model
// size, storage precisions, the compression parameters it records, the bytes of every section
// and the ratio of the file to the float32 field it stands for (functions x lights x 4 bytes).
#include <algorithm>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>

#include "command_registry.hpp"
#include "container/container.hpp"
#include "core/json_report.hpp"

namespace relume {
namespace {

struct InfoOptions {
  std::string input;
  bool json = false;
};

nlohmann::ordered_json describe(const std::string& input) {
  ContainerOptions stored;
  const CompressedField field = read_container(input, &stored);
  const ContainerLayout layout = describe_container(input);
  const std::uint64_t input_bytes = std::uint64_t(field.functions()) * field.lights * 4;
  nlohmann::ordered_json info = {
      {"file", input},
      {"format_version", layout.version},
      {"width", field.width},
      {"height", field.height},
      {"channels", field.channels},
      {"lights", field.lights},
      {"functions", field.functions()},
      {"stored_rows", field.stored_rows()},
      {"clusters", field.clusters},
      {"terms", field.terms},
      {"transform", field.transform == BasisTransform::haar ? "haar" : "identity"},
      {"residual_nonzeros", field.residual.nonzeros()},
      {"residual_longest_row", field.residual.longest_row()},
      {"weights_precision", to_string(stored.weights)},
      {"residual_precision", to_string(stored.residual)},
      {"light_index_bits", index_width_bits(stored.light_index)},
      {"parameters", nlohmann::ordered_json::parse(stored.parameters_json)},
      {"written_by", stored.written_by},
      {"preamble_bytes", layout.preamble_bytes},
      {"sections", nlohmann::ordered_json::array()},
      {"file_bytes", layout.file_bytes},
      {"float32_input_bytes", input_bytes},
      {"ratio_to_float32_input", double(layout.file_bytes) / double(input_bytes)}};
  for (const ContainerSection& section : layout.sections)
    info["sections"].push_back(
        {{"name", section.name},
         {"offset", section.offset},
         {"bytes", section.bytes},
         {"raw_bytes", section.raw_bytes},
         {"coding", section.coding},
         {"bits_per_stored_row",
          field.stored_rows() ? 8.0 * double(section.bytes) / double(field.stored_rows()) : 0.0},
         {"crc32", section.crc32}});
  info["bits_per_stored_row"] =
      field.stored_rows() ? 8.0 * double(layout.file_bytes) / double(field.stored_rows()) : 0.0;
  info["bytes_per_pixel"] =
      double(layout.file_bytes) / double(field.width * std::int64_t(field.height));
  return info;
}

void print_text(const nlohmann::ordered_json& info) {
  const auto file_bytes = info["file_bytes"].get<std::uint64_t>();
  const auto stored_rows = info["stored_rows"].get<std::uint64_t>();
  const auto nonzeros = info["residual_nonzeros"].get<std::uint64_t>();
  std::printf("%s: relume container, format version %u, %llu bytes\n",
              info["file"].get<std::string>().c_str(), info["format_version"].get<unsigned>(),
              static_cast<unsigned long long>(file_bytes));
  std::printf("field:      %d x %d pixels, %d channels, %d lights (%lld functions, %llu stored)\n",
              info["width"].get<int>(), info["height"].get<int>(), info["channels"].get<int>(),
              info["lights"].get<int>(), info["functions"].get<long long>(),
              static_cast<unsigned long long>(stored_rows));
  std::printf("model:      %d clusters x %d terms, %s basis\n", info["clusters"].get<int>(),
              info["terms"].get<int>(), info["transform"].get<std::string>().c_str());
  std::printf("residual:   %llu entries (%.2f per stored row, at most %u)\n",
              static_cast<unsigned long long>(nonzeros),
              stored_rows ? double(nonzeros) / double(stored_rows) : 0.0,
              info["residual_longest_row"].get<unsigned>());
  std::printf("precision:  weights %s, residual values %s, light indices %d bits\n",
              info["weights_precision"].get<std::string>().c_str(),
              info["residual_precision"].get<std::string>().c_str(),
              info["light_index_bits"].get<int>());
  std::printf("parameters: %s\n", info["parameters"].dump().c_str());
  if (!info["written_by"].get<std::string>().empty())
    std::printf("written by: %s\n", info["written_by"].get<std::string>().c_str());
  std::printf("sections:   %-18s %12s %12s %7s %9s  %s\n", "name", "raw bytes", "bytes", "share",
              "bits/row", "coding");
  auto row = [&](const std::string& name, std::uint64_t raw, std::uint64_t bytes,
                 const std::string& coding) {
    std::printf("            %-18s %12llu %12llu %6.2f%% %9.2f  %s\n", name.c_str(),
                static_cast<unsigned long long>(raw), static_cast<unsigned long long>(bytes),
                100.0 * double(bytes) / double(file_bytes),
                stored_rows ? 8.0 * double(bytes) / double(stored_rows) : 0.0, coding.c_str());
  };
  const auto preamble = info["preamble_bytes"].get<std::uint64_t>();
  row("(preamble+table)", preamble, preamble, "raw");
  for (const auto& section : info["sections"])
    row(section["name"].get<std::string>(), section["raw_bytes"].get<std::uint64_t>(),
        section["bytes"].get<std::uint64_t>(), section["coding"].get<std::string>());
  std::printf("total:      %llu bytes, %.2f bits per stored row, %.4f bytes per pixel\n",
              static_cast<unsigned long long>(file_bytes),
              info["bits_per_stored_row"].get<double>(), info["bytes_per_pixel"].get<double>());
  const double ratio = info["ratio_to_float32_input"].get<double>();
  std::printf("float32 input: %lld functions x %d lights x 4 bytes = %llu bytes\n",
              info["functions"].get<long long>(), info["lights"].get<int>(),
              static_cast<unsigned long long>(info["float32_input_bytes"].get<std::uint64_t>()));
  std::printf("ratio:      %.4f of the float32 input (%.2f : 1)\n", ratio, 1.0 / ratio);
}

void run_info(const InfoOptions& options) {
  const nlohmann::ordered_json info = describe(options.input);
  if (options.json)
    std::printf("%s\n", info.dump(2).c_str());
  else
    print_text(info);
}

const CommandRegistration registration{
    50, [](CLI::App& app) {
      auto options = std::make_shared<InfoOptions>();
      auto* command = app.add_subcommand(
          "info",
          "Describe a .relume container: dimensions, parameters, bytes per section and the ratio "
          "to "
          "the float32 field (functions x lights x 4 bytes). The whole file is verified first");
      command->add_option("input", options->input, "The .relume container")->required();
      command->add_flag("--json", options->json,
                        "Print one JSON object instead of text (default: text)");
      command->callback([options] { run_info(*options); });
    }};

}  // namespace
}  // namespace relume
