// Writing the commands' JSON reports (compress --report, relight-sequence --report, compare
// --json, bench --json, bench-factor --json): every report starts with "software", the version
// and commit of the relume that made it, and is written atomically.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace relume {

// {"software": version_line()} followed by the keys of `document` (an object).
nlohmann::ordered_json stamped_report(const nlohmann::ordered_json& document);

// Writes stamped_report(document), indented, to `path` atomically.
void write_json_report(const std::string& path, const nlohmann::ordered_json& document);

}  // namespace relume
