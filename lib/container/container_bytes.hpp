// Little-endian byte encoding for the .relume container: a writer that appends fixed-width
// integers, floats (float32 or IEEE half via Imath), LEB128 varints and raw bytes, and a reader
// that takes them back and throws an Error naming its section when the bytes run out.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace relume {

// IEEE 754 binary16 conversions (Imath; float -> half rounds to nearest even, overflow gives Inf).
std::uint16_t float_to_half_bits(float value);
float half_bits_to_float(std::uint16_t bits);

class ByteWriter {
 public:
  void u8(std::uint8_t value) { data_.push_back(static_cast<char>(value)); }
  void u16(std::uint16_t value) { little_endian(value, 2); }
  void u32(std::uint32_t value) { little_endian(value, 4); }
  void u64(std::uint64_t value) { little_endian(value, 8); }
  // An unsigned integer in `bytes` bytes (1, 2, 4 or 8); the caller has checked that it fits.
  void unsigned_of_width(std::uint64_t value, int bytes) { little_endian(value, bytes); }
  void f32(float value);
  void varint(std::uint64_t value);  // LEB128: 7 bits a byte, low bits first
  void bytes(std::string_view bytes) { data_.append(bytes); }

  // Room for `count` more bytes: a large section written value by value is not copied as it grows.
  void reserve(std::size_t count) { data_.reserve(data_.size() + count); }

  const std::string& data() const { return data_; }
  std::string take() { return std::move(data_); }

 private:
  void little_endian(std::uint64_t value, int bytes);
  std::string data_;
};

class ByteReader {
 public:
  // `where` prefixes every error, e.g. "scene.relume: section 'mask'".
  ByteReader(std::string_view data, std::string where) : data_(data), where_(std::move(where)) {}

  std::uint8_t u8() { return static_cast<std::uint8_t>(little_endian(1)); }
  std::uint16_t u16() { return static_cast<std::uint16_t>(little_endian(2)); }
  std::uint32_t u32() { return static_cast<std::uint32_t>(little_endian(4)); }
  std::uint64_t u64() { return little_endian(8); }
  std::uint64_t unsigned_of_width(int bytes) { return little_endian(bytes); }
  float f32();
  std::uint64_t varint();
  std::string_view bytes(std::size_t count);

  std::string_view rest() const { return data_.substr(position_); }  // the unread bytes
  std::size_t position() const { return position_; }
  std::size_t remaining() const { return data_.size() - position_; }
  const std::string& where() const { return where_; }
  // Throws Error("<where>: <what>").
  [[noreturn]] void fail(const std::string& what) const;

 private:
  std::uint64_t little_endian(int bytes);
  std::string_view data_;
  std::size_t position_ = 0;
  std::string where_;
};

}  // namespace relume
