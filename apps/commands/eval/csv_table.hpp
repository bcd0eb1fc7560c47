// A small CSV table for `relume eval`: a header of column names and rows of cells, numbers written
// with enough digits to read back exactly, written atomically.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace relume {

class CsvTable {
 public:
  explicit CsvTable(std::vector<std::string> columns);

  // Starts a new row; cells are appended to it in column order.
  CsvTable& row();
  CsvTable& cell(const std::string& text);
  CsvTable& cell(double value);  // NaN and infinities are written as empty cells
  CsvTable& cell(long long value);
  CsvTable& cell(int value) { return cell(static_cast<long long>(value)); }

  std::size_t rows() const { return cells_.size(); }
  // Throws Error when a row does not have one cell per column.
  void write(const std::filesystem::path& path) const;

 private:
  std::vector<std::string> columns_;
  std::vector<std::vector<std::string>> cells_;
};

}  // namespace relume
