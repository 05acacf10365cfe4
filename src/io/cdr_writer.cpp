#include "floornav/io/cdr_writer.hpp"

#include <bit>
#include <cstring>
#include <limits>
#include <stdexcept>

namespace floornav {

namespace {

constexpr std::size_t kHeaderSize = 4;
// CDR_LE: the representation identifier 0x0001 (big-endian in the header), then two option bytes.
constexpr char kHeader[kHeaderSize] = {0x00, 0x01, 0x00, 0x00};

std::uint32_t checked_count(std::size_t n) {
  if (n > std::numeric_limits<std::uint32_t>::max())
    throw std::length_error("CDR: a sequence or string longer than 2^32 - 1");
  return static_cast<std::uint32_t>(n);
}

}  // namespace

void CdrWriter::begin() {
  buffer_.assign(kHeader, kHeaderSize);
}

void CdrWriter::align(std::size_t n) {  // n: 1, 2, 4 or 8
  const std::size_t pad = (kHeaderSize - buffer_.size()) & (n - 1);
  if (pad != 0) buffer_.append(pad, '\0');
}

template <class T>
void CdrWriter::put(T v) {
  static_assert(std::endian::native == std::endian::little ||
                std::endian::native == std::endian::big);
  align(sizeof(T));
  char bytes[sizeof(T)];
  std::memcpy(bytes, &v, sizeof(T));
  if constexpr (std::endian::native == std::endian::big)
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
  buffer_.append(bytes, sizeof(T));
}

void CdrWriter::u8(std::uint8_t v) {
  buffer_.push_back(static_cast<char>(v));
}
void CdrWriter::i32(std::int32_t v) {
  put(v);
}
void CdrWriter::u32(std::uint32_t v) {
  put(v);
}
void CdrWriter::f32(float v) {
  put(v);
}
void CdrWriter::f64(double v) {
  put(v);
}

void CdrWriter::string(std::string_view s) {
  u32(checked_count(s.size() + 1));
  buffer_.append(s);
  buffer_.push_back('\0');
}

void CdrWriter::sequence_size(std::size_t n) {
  u32(checked_count(n));
}

void CdrWriter::f32_sequence(std::span<const float> values) {
  sequence_size(values.size());
  if (values.empty()) return;
  align(4);
  if constexpr (std::endian::native == std::endian::little) {
    buffer_.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(float));
  } else {
    for (float v : values) f32(v);
  }
}

void CdrWriter::i8_sequence(std::span<const std::int8_t> values) {
  sequence_size(values.size());
  buffer_.append(reinterpret_cast<const char*>(values.data()), values.size());
}

void CdrWriter::f64_array(std::span<const double> values) {
  if (values.empty()) return;
  align(8);
  if constexpr (std::endian::native == std::endian::little) {
    buffer_.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(double));
  } else {
    for (double v : values) f64(v);
  }
}

}  // namespace floornav
