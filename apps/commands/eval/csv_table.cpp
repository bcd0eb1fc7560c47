// Implementation of the CSV table (see csv_table.hpp).
#include "commands/eval/csv_table.hpp"

#include <cmath>
#include <cstdio>
#include <relume/error.hpp>

#include "core/atomic_file.hpp"

namespace relume {

CsvTable::CsvTable(std::vector<std::string> columns) : columns_(std::move(columns)) {}

CsvTable& CsvTable::row() {
  cells_.emplace_back();
  return *this;
}

CsvTable& CsvTable::cell(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) {
    cells_.back().push_back(text);
    return *this;
  }
  std::string quoted = "\"";
  for (const char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  cells_.back().push_back(quoted + "\"");
  return *this;
}

CsvTable& CsvTable::cell(double value) {
  if (!std::isfinite(value)) return cell(std::string());
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", value);
  return cell(std::string(text));
}

CsvTable& CsvTable::cell(long long value) { return cell(std::to_string(value)); }

void CsvTable::write(const std::filesystem::path& path) const {
  std::string text;
  for (std::size_t c = 0; c < columns_.size(); ++c) text += (c ? "," : "") + columns_[c];
  text += "\n";
  for (std::size_t r = 0; r < cells_.size(); ++r) {
    if (cells_[r].size() != columns_.size())
      throw Error(path.string() + ": row " + std::to_string(r + 1) + " has " +
                  std::to_string(cells_[r].size()) + " cells, expected " +
                  std::to_string(columns_.size()));
    for (std::size_t c = 0; c < cells_[r].size(); ++c) text += (c ? "," : "") + cells_[r][c];
    text += "\n";
  }
  write_file_atomically(path, text);
}

}  // namespace relume
