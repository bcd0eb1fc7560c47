// Implementation of the container's little-endian ByteWriter / ByteReader and half conversions.
#include "container/container_bytes.hpp"

#include <Imath/half.h>

#include <bit>
#include <relume/error.hpp>

namespace relume {

std::uint16_t float_to_half_bits(float value) { return imath_float_to_half(value); }

float half_bits_to_float(std::uint16_t bits) { return imath_half_to_float(bits); }

void ByteWriter::little_endian(std::uint64_t value, int bytes) {
  for (int b = 0; b < bytes; ++b) data_.push_back(static_cast<char>((value >> (8 * b)) & 0xFFu));
}

void ByteWriter::f32(float value) { u32(std::bit_cast<std::uint32_t>(value)); }

void ByteWriter::varint(std::uint64_t value) {
  while (value >= 0x80) {
    u8(static_cast<std::uint8_t>((value & 0x7Fu) | 0x80u));
    value >>= 7;
  }
  u8(static_cast<std::uint8_t>(value));
}

void ByteReader::fail(const std::string& what) const { throw Error(where_ + ": " + what); }

std::uint64_t ByteReader::little_endian(int bytes) {
  if (remaining() < std::size_t(bytes))
    fail("ends early: " + std::to_string(bytes) + " more bytes needed at byte " +
         std::to_string(position_) + " of " + std::to_string(data_.size()));
  std::uint64_t value = 0;
  for (int b = 0; b < bytes; ++b)
    value |= std::uint64_t(static_cast<unsigned char>(data_[position_ + b])) << (8 * b);
  position_ += bytes;
  return value;
}

float ByteReader::f32() { return std::bit_cast<float>(u32()); }

std::uint64_t ByteReader::varint() {
  const std::size_t start = position_;
  std::uint64_t value = 0;
  for (int shift = 0; shift < 64; shift += 7) {
    const std::uint8_t byte = u8();
    if (shift == 63 && byte > 1) break;
    value |= std::uint64_t(byte & 0x7Fu) << shift;
    if (!(byte & 0x80u)) return value;
  }
  fail("the number at byte " + std::to_string(start) + " does not fit 64 bits");
}

std::string_view ByteReader::bytes(std::size_t count) {
  if (remaining() < count)
    fail("ends early: " + std::to_string(count) + " more bytes needed at byte " +
         std::to_string(position_) + " of " + std::to_string(data_.size()));
  const std::string_view result = data_.substr(position_, count);
  position_ += count;
  return result;
}

}  // namespace relume
