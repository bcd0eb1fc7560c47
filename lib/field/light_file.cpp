// Parsers and writer for light-direction and RGB-row files (see light_file.hpp).
#include "field/light_file.hpp"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <relume/error.hpp>
#include <sstream>

#include "core/atomic_file.hpp"

namespace relume {
namespace fs = std::filesystem;

namespace {

std::string where(const fs::path& path, int line) {
  return path.string() + ":" + std::to_string(line);
}

// Parses one number, accepting a decimal comma ("0,25"). Throws naming the file, line and token.
double parse_number(std::string token, const fs::path& path, int line, const std::string& what) {
  for (char& ch : token)
    if (ch == ',') ch = '.';
  std::size_t used = 0;
  double value = 0;
  try {
    value = std::stod(token, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != token.size())
    throw Error(where(path, line) + ": " + what + " '" + token + "' is not a number");
  if (!std::isfinite(value))
    throw Error(where(path, line) + ": " + what + " '" + token + "' is not finite");
  return value;
}

std::vector<std::string> split_fields(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> fields;
  for (std::string field; in >> field;) fields.push_back(field);
  return fields;
}

bool is_blank_or_comment(const std::string& line) {
  const auto first = line.find_first_not_of(" \t\r");
  return first == std::string::npos || line[first] == '#';
}

std::ifstream open_text(const fs::path& path) {
  if (!fs::exists(path)) throw Error("light file not found: " + path.string());
  std::ifstream in(path);
  if (!in) throw Error("cannot open light file " + path.string());
  return in;
}

Eigen::RowVector3f unit_direction(const std::vector<double>& xyz, const fs::path& path, int line) {
  const double length = std::sqrt(xyz[0] * xyz[0] + xyz[1] * xyz[1] + xyz[2] * xyz[2]);
  if (!(length > 1e-12)) throw Error(where(path, line) + ": light direction has zero length");
  return Eigen::RowVector3f(float(xyz[0] / length), float(xyz[1] / length), float(xyz[2] / length));
}

struct Triple {
  std::vector<double> values;
  int line;
};

// Rows of exactly three numbers with their line numbers; `what` names the quantity in messages.
std::vector<Triple> read_triples(const fs::path& path, const std::string& what) {
  std::ifstream in = open_text(path);
  std::vector<Triple> rows;
  int line_number = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_number;
    if (is_blank_or_comment(line)) continue;
    const auto fields = split_fields(line);
    if (fields.size() != 3)
      throw Error(where(path, line_number) + ": expected 3 numbers (" + what + "), found " +
                  std::to_string(fields.size()) + " fields");
    std::vector<double> row;
    for (const auto& f : fields) row.push_back(parse_number(f, path, line_number, what));
    rows.push_back({row, line_number});
  }
  if (rows.empty()) throw Error(path.string() + ": no " + what + " rows");
  return rows;
}

}  // namespace

LightDirections read_direction_rows(const fs::path& path) {
  const auto rows = read_triples(path, "light direction");
  LightDirections directions(rows.size(), 3);
  for (std::size_t i = 0; i < rows.size(); ++i)
    directions.row(i) = unit_direction(rows[i].values, path, rows[i].line);
  return directions;
}

LpFile read_lp_file(const fs::path& path) {
  std::ifstream in = open_text(path);
  std::string line;
  int line_number = 0;
  long count = -1;
  while (std::getline(in, line)) {
    ++line_number;
    if (is_blank_or_comment(line)) continue;
    const auto fields = split_fields(line);
    const double n = parse_number(fields.at(0), path, line_number, "light count");
    if (fields.size() != 1 || n < 1 || n != std::floor(n))
      throw Error(where(path, line_number) + ": expected the light count (a positive integer)");
    count = static_cast<long>(n);
    break;
  }
  if (count < 0) throw Error(path.string() + ": empty .lp file");
  LpFile lp;
  std::vector<Eigen::RowVector3f> directions;
  while (std::getline(in, line)) {
    ++line_number;
    if (is_blank_or_comment(line)) continue;
    const auto fields = split_fields(line);
    if (fields.size() < 4)
      throw Error(where(path, line_number) + ": expected 'filename x y z', found " +
                  std::to_string(fields.size()) + " fields");
    std::vector<double> xyz;
    for (std::size_t k = fields.size() - 3; k < fields.size(); ++k)
      xyz.push_back(parse_number(fields[k], path, line_number, "light direction"));
    // The name is everything before the last three fields, so names may contain spaces.
    std::string name = line.substr(0, line.find_last_not_of(" \t\r") + 1);
    for (int k = 0; k < 3; ++k) name = name.substr(0, name.find_last_of(" \t"));
    name = name.substr(0, name.find_last_not_of(" \t") + 1);
    name = name.substr(name.find_first_not_of(" \t"));
    lp.images.emplace_back(name);
    directions.push_back(unit_direction(xyz, path, line_number));
  }
  if (static_cast<long>(directions.size()) != count)
    throw Error(path.string() + ": header says " + std::to_string(count) + " lights but " +
                std::to_string(directions.size()) + " light lines follow");
  lp.directions.resize(count, 3);
  for (long i = 0; i < count; ++i) lp.directions.row(i) = directions[i];
  return lp;
}

LightDirections read_light_directions(const fs::path& path) {
  if (fs::is_directory(path)) {
    if (fs::exists(path / "light_directions.txt"))
      return read_direction_rows(path / "light_directions.txt");
    std::vector<fs::path> lp_files;
    for (const auto& entry : fs::directory_iterator(path))
      if (entry.path().extension() == ".lp") lp_files.push_back(entry.path());
    if (lp_files.size() != 1)
      throw Error("folder " + path.string() + " has no light_directions.txt and " +
                  std::to_string(lp_files.size()) + " .lp files (expected exactly one)");
    return read_lp_file(lp_files.front()).directions;
  }
  if (path.extension() == ".lp") return read_lp_file(path).directions;
  return read_direction_rows(path);
}

LightRgb read_rgb_rows(const fs::path& path, const std::string& what) {
  const auto rows = read_triples(path, what);
  LightRgb rgb(rows.size(), 3);
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (int c = 0; c < 3; ++c) rgb(i, c) = static_cast<float>(rows[i].values[c]);
  return rgb;
}

void write_rgb_rows(const fs::path& path, const LightRgb& rows, const std::string& header_comment) {
  std::ostringstream out;
  if (!header_comment.empty()) out << "# " << header_comment << "\n";
  out << std::setprecision(9);
  for (Eigen::Index i = 0; i < rows.rows(); ++i)
    out << rows(i, 0) << " " << rows(i, 1) << " " << rows(i, 2) << "\n";
  write_file_atomically(path, out.str());
}

}  // namespace relume
