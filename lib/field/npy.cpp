// Reading and writing .npy matrices: the header is a Python dict literal
// {'descr': '<f8', 'fortran_order': False, 'shape': (rows, cols), } after a magic string, a version
// and a header length; the data follows it, padded so that it starts at a multiple of 64 bytes.
#include "field/npy.hpp"

#include <bit>
#include <cctype>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <optional>
#include <relume/error.hpp>
#include <vector>

#include "core/atomic_file.hpp"

namespace relume {
namespace {

static_assert(std::endian::native == std::endian::little, "npy.cpp assumes a little-endian host");

const char kMagic[] = "\x93NUMPY";
constexpr std::size_t kMagicSize = 6;

// A parsed dict value: a string, a bool, or a tuple of integers.
struct HeaderValue {
  std::optional<std::string> text;
  std::optional<bool> flag;
  std::optional<std::vector<std::uint64_t>> tuple;
};

// A small parser for the subset of Python literals that .npy headers use.
class HeaderParser {
 public:
  HeaderParser(const std::string& header, const std::string& name) : text_(header), name_(name) {}

  std::map<std::string, HeaderValue> parse_dict() {
    std::map<std::string, HeaderValue> dict;
    expect('{');
    skip_space();
    while (peek() != '}') {
      const std::string key = parse_string();
      expect(':');
      dict[key] = parse_value();
      skip_space();
      if (peek() == ',') {
        ++position_;
        skip_space();
      } else if (peek() != '}') {
        fail("expected ',' or '}' after the value of '" + key + "'");
      }
    }
    ++position_;
    skip_space();
    if (position_ != text_.size()) fail("unexpected text after the closing '}'");
    return dict;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw Error(name_ + ": malformed .npy header at character " + std::to_string(position_) + ": " +
                what + " (header: " + text_ + ")");
  }
  void skip_space() {
    while (position_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[position_])))
      ++position_;
  }
  char peek() {
    skip_space();
    if (position_ >= text_.size()) fail("unexpected end of header");
    return text_[position_];
  }
  void expect(char c) {
    if (peek() != c) fail(std::string("expected '") + c + "'");
    ++position_;
  }
  std::string parse_string() {
    const char quote = peek();
    if (quote != '\'' && quote != '"') fail("expected a quoted string");
    const std::size_t end = text_.find(quote, position_ + 1);
    if (end == std::string::npos) fail("unterminated string");
    std::string value = text_.substr(position_ + 1, end - position_ - 1);
    position_ = end + 1;
    return value;
  }
  std::uint64_t parse_integer() {
    skip_space();
    const std::size_t start = position_;
    std::uint64_t value = 0;
    while (position_ < text_.size() && std::isdigit(static_cast<unsigned char>(text_[position_]))) {
      const unsigned digit = static_cast<unsigned>(text_[position_] - '0');
      if (value > (std::numeric_limits<std::uint64_t>::max() - digit) / 10)
        fail("dimension too large");
      value = value * 10 + digit;
      ++position_;
    }
    if (position_ == start) fail("expected a non-negative integer");
    if (position_ < text_.size() && text_[position_] == 'L') ++position_;  // Python 2 long
    return value;
  }
  HeaderValue parse_value() {
    HeaderValue value;
    const char c = peek();
    if (c == '\'' || c == '"') {
      value.text = parse_string();
    } else if (text_.compare(position_, 4, "True") == 0) {
      value.flag = true;
      position_ += 4;
    } else if (text_.compare(position_, 5, "False") == 0) {
      value.flag = false;
      position_ += 5;
    } else if (c == '(') {
      ++position_;
      std::vector<std::uint64_t> items;
      while (peek() != ')') {
        items.push_back(parse_integer());
        if (peek() == ',')
          ++position_;
        else if (peek() != ')')
          fail("expected ',' or ')' in the shape");
      }
      ++position_;
      value.tuple = items;
    } else {
      fail("unsupported value (expected a string, True/False or a tuple of integers)");
    }
    return value;
  }

  const std::string& text_;
  const std::string& name_;
  std::size_t position_ = 0;
};

template <typename Word>
Word read_little_endian(const char* bytes) {
  Word value = 0;
  for (std::size_t k = 0; k < sizeof(Word); ++k)
    value |= Word(static_cast<unsigned char>(bytes[k])) << (8 * k);
  return value;
}

template <typename Float>
double decode_value(const char* bytes, bool big_endian) {
  char ordered[sizeof(Float)];
  for (std::size_t k = 0; k < sizeof(Float); ++k)
    ordered[k] = bytes[big_endian ? sizeof(Float) - 1 - k : k];
  Float value;
  std::memcpy(&value, ordered, sizeof value);
  return static_cast<double>(value);
}

std::string shape_text(const std::vector<std::uint64_t>& shape) {
  std::string text = "(";
  for (std::size_t k = 0; k < shape.size(); ++k) text += (k ? ", " : "") + std::to_string(shape[k]);
  return text + (shape.size() == 1 ? ",)" : ")");
}

}  // namespace

NpyMatrix parse_npy_matrix(const std::string& bytes, const std::string& name) {
  if (bytes.size() < kMagicSize + 2 || bytes.compare(0, kMagicSize, kMagic, kMagicSize) != 0)
    throw Error(name + ": not a .npy file (it does not start with the magic string \\x93NUMPY)");
  const int major = static_cast<unsigned char>(bytes[6]);
  std::size_t header_start = 0, header_size = 0;
  if (major == 1) {
    if (bytes.size() < 10) throw Error(name + ": truncated .npy file (no header length)");
    header_size = read_little_endian<std::uint16_t>(bytes.data() + 8);
    header_start = 10;
  } else if (major == 2 || major == 3) {
    if (bytes.size() < 12) throw Error(name + ": truncated .npy file (no header length)");
    header_size = read_little_endian<std::uint32_t>(bytes.data() + 8);
    header_start = 12;
  } else {
    throw Error(name + ": unsupported .npy format version " + std::to_string(major) + "." +
                std::to_string(static_cast<unsigned char>(bytes[7])) +
                " (expected 1.0, 2.0 or 3.0)");
  }
  if (bytes.size() < header_start + header_size)
    throw Error(name + ": truncated .npy file: the header says it is " +
                std::to_string(header_size) + " bytes long but the file ends before that");
  const std::string header = bytes.substr(header_start, header_size);
  const auto dict = HeaderParser(header, name).parse_dict();
  for (const char* key : {"descr", "fortran_order", "shape"})
    if (!dict.count(key)) throw Error(name + ": .npy header has no '" + key + "' entry: " + header);
  const HeaderValue& descr = dict.at("descr");
  const HeaderValue& fortran = dict.at("fortran_order");
  const HeaderValue& shape_value = dict.at("shape");
  if (!descr.text)
    throw Error(name +
                ": structured dtypes are not supported (expected float32 '<f4' or float64 "
                "'<f8'; convert with a.astype(numpy.float64))");
  if (!fortran.flag) throw Error(name + ": .npy header 'fortran_order' is not True or False");
  if (!shape_value.tuple) throw Error(name + ": .npy header 'shape' is not a tuple");
  const std::string& type = *descr.text;
  const bool known_order = type.size() == 3 && (type[0] == '<' || type[0] == '>' || type[0] == '=');
  if (!known_order || (type.substr(1) != "f4" && type.substr(1) != "f8"))
    throw Error(name + ": dtype '" + type +
                "' is not supported: expected float32 ('<f4') or float64 ('<f8'); convert with "
                "a.astype(numpy.float64)");
  const bool big_endian = type[0] == '>';
  NpyMatrix result;
  result.dtype = type.substr(1) == "f4" ? NpyDtype::float32 : NpyDtype::float64;
  const std::size_t item_size = result.dtype == NpyDtype::float32 ? 4 : 8;
  const auto& shape = *shape_value.tuple;
  if (shape.size() != 2)
    throw Error(
        name + ": expected a 2-D array (rows x columns), got shape " + shape_text(shape) +
        (shape.size() == 1 ? "; reshape it with a.reshape(1, -1) or a.reshape(-1, 1)" : ""));
  const std::uint64_t limit = std::numeric_limits<Eigen::Index>::max() / 8;
  if (shape[0] > limit || (shape[0] && shape[1] > limit / shape[0]))
    throw Error(name + ": shape " + shape_text(shape) + " is too large");
  const std::size_t count = shape[0] * shape[1];
  const std::size_t data_start = header_start + header_size;
  const std::size_t data_size = bytes.size() - data_start;
  if (data_size != count * item_size)
    throw Error(name + ": " + (data_size < count * item_size ? "truncated" : "oversized") +
                " .npy data: shape " + shape_text(shape) + " of " + type + " needs " +
                std::to_string(count * item_size) + " bytes after the header, the file has " +
                std::to_string(data_size));
  const auto rows = static_cast<Eigen::Index>(shape[0]);
  const auto cols = static_cast<Eigen::Index>(shape[1]);
  result.values.resize(rows, cols);
  const char* data = bytes.data() + data_start;
  for (Eigen::Index i = 0; i < rows; ++i)
    for (Eigen::Index j = 0; j < cols; ++j) {
      const std::size_t index =
          *fortran.flag ? std::size_t(j * rows + i) : std::size_t(i * cols + j);
      const char* item = data + index * item_size;
      result.values(i, j) = item_size == 4 ? decode_value<float>(item, big_endian)
                                           : decode_value<double>(item, big_endian);
    }
  return result;
}

NpyMatrix read_npy_matrix(const std::filesystem::path& path) {
  return parse_npy_matrix(read_file(path), path.string());
}

namespace {

// Magic, version 1.0 and the header dict, padded with spaces and ended with a newline so that
// the data starts at a multiple of 64 bytes.
std::string npy_header(const std::string& descr, const std::vector<std::size_t>& shape) {
  // Python tuples: (), (4,), (2, 3).
  std::string dimensions;
  for (std::size_t i = 0; i < shape.size(); ++i)
    dimensions += (i ? ", " : "") + std::to_string(shape[i]);
  if (shape.size() == 1) dimensions += ",";
  std::string header =
      "{'descr': '" + descr + "', 'fortran_order': False, 'shape': (" + dimensions + "), }";
  const std::size_t unpadded = 10 + header.size() + 1;
  header.append((64 - unpadded % 64) % 64, ' ');
  header += '\n';
  if (header.size() > 0xffff)
    throw Error("a .npy header of " + std::to_string(header.size()) +
                " bytes does not fit version 1.0");
  std::string bytes(kMagic, kMagicSize);
  bytes += '\x01';
  bytes += '\x00';
  bytes += static_cast<char>(header.size() & 0xff);
  bytes += static_cast<char>(header.size() >> 8);
  return bytes + header;
}

}  // namespace

std::string encode_npy_array(const std::string& descr, const std::vector<std::size_t>& shape,
                             const void* data, std::size_t bytes) {
  std::size_t count = 1;
  for (std::size_t d : shape) count *= d;
  if (count == 0 ? bytes != 0 : bytes % count != 0)
    throw Error("a .npy array of " + std::to_string(count) + " " + descr + " values cannot hold " +
                std::to_string(bytes) + " bytes");
  std::string file = npy_header(descr, shape);
  file.append(static_cast<const char*>(data), bytes);
  return file;
}

std::string encode_npy_matrix(const Eigen::MatrixXd& values, NpyDtype dtype) {
  const bool single = dtype == NpyDtype::float32;
  std::string bytes =
      npy_header(single ? "<f4" : "<f8", {std::size_t(values.rows()), std::size_t(values.cols())});
  const std::size_t item_size = single ? 4 : 8;
  const std::size_t data_start = bytes.size();
  bytes.resize(data_start + std::size_t(values.size()) * item_size);
  char* out = bytes.data() + data_start;
  for (Eigen::Index i = 0; i < values.rows(); ++i)
    for (Eigen::Index j = 0; j < values.cols(); ++j, out += item_size) {
      const double value = values(i, j);
      if (single) {
        if (std::isfinite(value) && std::abs(value) > FLT_MAX)
          throw Error("value " + std::to_string(value) + " at (" + std::to_string(i) + ", " +
                      std::to_string(j) + ") does not fit float32; write float64 instead");
        const float narrow = static_cast<float>(value);
        std::memcpy(out, &narrow, 4);
      } else {
        std::memcpy(out, &value, 8);
      }
    }
  return bytes;
}

void write_npy_matrix(const std::filesystem::path& path, const Eigen::MatrixXd& values,
                      NpyDtype dtype) {
  write_file_atomically(path, encode_npy_matrix(values, dtype));
}

}  // namespace relume
