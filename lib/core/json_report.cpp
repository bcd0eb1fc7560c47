// Implementation of the version-stamped JSON reports.
#include "core/json_report.hpp"

#include <relume/version.hpp>

#include "core/atomic_file.hpp"

namespace relume {

nlohmann::ordered_json stamped_report(const nlohmann::ordered_json& document) {
  nlohmann::ordered_json report = {{"software", version_line()}};
  for (const auto& [key, value] : document.items()) report[key] = value;
  return report;
}

void write_json_report(const std::string& path, const nlohmann::ordered_json& document) {
  write_file_atomically(path, stamped_report(document).dump(2) + "\n");
}

}  // namespace relume
