// Parsers and writer for light-direction and RGB-row files (see light_file.hpp).
#include "field/light_file.hpp"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>
#include <optional>
#include <relume/error.hpp>
#include <sstream>
#include <string_view>

#include "core/atomic_file.hpp"
#include "core/text_numbers.hpp"

namespace relume {
namespace fs = std::filesystem;

namespace {

std::string where(const fs::path& path, int line) {
  return path.string() + ":" + std::to_string(line);
}

// Parses one number, accepting a decimal comma ("0,25"). Throws naming the file, line and token.
double parse_number(std::string_view token, const fs::path& path, int line,
                    const std::string& what) {
  const ParsedNumber parsed = parse_number_token(token, /*decimal_comma=*/true);
  std::string quoted = "'";
  quoted.append(token).append("'");
  if (parsed.status == ParsedNumber::Status::not_a_number)
    throw Error(where(path, line) + ": " + what + " " + quoted + " is not a number");
  if (parsed.status == ParsedNumber::Status::not_finite)
    throw Error(where(path, line) + ": " + what + " " + quoted + " is not finite");
  return parsed.value;
}

std::ifstream open_text(const fs::path& path) {
  if (!fs::exists(path)) throw Error("light file not found: " + path.string());
  if (fs::is_directory(path)) throw Error("light file " + path.string() + " is a folder");
  std::ifstream in(path);
  if (!in) throw Error("cannot open light file " + path.string());
  return in;
}

// The unit vector of (x, y, z); hypot does not overflow for components near 1e308.
Eigen::RowVector3f unit_direction(const std::vector<double>& xyz, const fs::path& path, int line) {
  const double length = std::hypot(xyz[0], xyz[1], xyz[2]);
  if (!(length > 0)) throw Error(where(path, line) + ": light direction has zero length");
  return Eigen::RowVector3f(float(xyz[0] / length), float(xyz[1] / length), float(xyz[2] / length));
}

struct Triple {
  std::vector<double> values;
  int line;
};

// The lines of a text file with their numbers, blank lines and # comments skipped.
class TextLines {
 public:
  explicit TextLines(const fs::path& path) : path_(path), in_(open_text(path)) {}
  // The next line that is not blank or a comment; false at the end.
  bool next(std::string& line) {
    while (std::getline(in_, line)) {
      ++number_;
      if (!is_blank_or_comment(line)) return true;
    }
    if (in_.bad()) throw Error("cannot read light file " + path_.string());
    return false;
  }
  int number() const { return number_; }

 private:
  const fs::path& path_;
  std::ifstream in_;
  int number_ = 0;
};

// Rows of exactly three numbers with their line numbers; `what` names the quantity in messages.
std::vector<Triple> read_triples(const fs::path& path, const std::string& what) {
  TextLines lines(path);
  std::vector<Triple> rows;
  for (std::string line; lines.next(line);) {
    const auto fields = split_blank_fields(line);
    if (fields.size() != 3)
      throw Error(where(path, lines.number()) + ": expected 3 numbers (" + what + "), found " +
                  std::to_string(fields.size()) + " fields");
    std::vector<double> row;
    for (const auto& f : fields) row.push_back(parse_number(f, path, lines.number(), what));
    rows.push_back({row, lines.number()});
  }
  if (rows.empty()) throw Error(path.string() + ": no " + what + " rows");
  return rows;
}

// The most lights a light file may declare: light indices are 32-bit and counts are ints.
constexpr std::uint64_t max_light_count = std::numeric_limits<int>::max();

}  // namespace

LightDirections read_direction_rows(const fs::path& path) {
  const auto rows = read_triples(path, "light direction");
  LightDirections directions(rows.size(), 3);
  for (std::size_t i = 0; i < rows.size(); ++i)
    directions.row(i) = unit_direction(rows[i].values, path, rows[i].line);
  return directions;
}

LpFile read_lp_file(const fs::path& path) {
  TextLines lines(path);
  std::string line;
  if (!lines.next(line)) throw Error(path.string() + ": empty .lp file");
  const auto header = split_blank_fields(line);
  const std::optional<std::uint64_t> count =
      header.size() == 1 ? parse_unsigned(header[0]) : std::nullopt;
  if (!count || *count < 1 || *count > max_light_count)
    throw Error(where(path, lines.number()) + ": expected the light count (an integer from 1 to " +
                std::to_string(max_light_count) + "), found '" + std::string(trim_blanks(line)) +
                "'");
  LpFile lp;
  std::vector<Eigen::RowVector3f> directions;
  while (lines.next(line)) {
    const auto fields = split_blank_fields(line);
    if (fields.size() < 4)
      throw Error(where(path, lines.number()) + ": expected 'filename x y z', found " +
                  std::to_string(fields.size()) + " fields");
    std::vector<double> xyz;
    for (std::size_t k = fields.size() - 3; k < fields.size(); ++k)
      xyz.push_back(parse_number(fields[k], path, lines.number(), "light direction"));
    // The name is everything before the last three fields, so names may contain spaces.
    const std::size_t name_end = std::size_t(fields[fields.size() - 3].data() - line.data());
    lp.images.emplace_back(std::string(trim_blanks(std::string_view(line).substr(0, name_end))));
    directions.push_back(unit_direction(xyz, path, lines.number()));
    if (directions.size() > *count)
      throw Error(where(path, lines.number()) + ": the header says " + std::to_string(*count) +
                  " lights, but more light lines follow");
  }
  if (directions.size() != *count)
    throw Error(path.string() + ": header says " + std::to_string(*count) + " lights but " +
                std::to_string(directions.size()) + " light lines follow");
  lp.directions.resize(Eigen::Index(directions.size()), 3);
  for (std::size_t i = 0; i < directions.size(); ++i)
    lp.directions.row(Eigen::Index(i)) = directions[i];
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
    for (int c = 0; c < 3; ++c) {
      const double value = rows[i].values[c];
      if (std::abs(value) > std::numeric_limits<float>::max())
        throw Error(where(path, rows[i].line) + ": " + what + " " + std::to_string(value) +
                    " is beyond float32 (at most 3.4e38 in magnitude)");
      rgb(i, c) = static_cast<float>(value);
    }
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
