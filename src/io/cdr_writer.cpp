#include "floornav/io/cdr_writer.hpp"

#include <bit>
#include <cstring>
#include <limits>
#include <stdexcept>

namespace floornav {

namespace {

// CDR_LE: the representation identifier 0x0001 (big-endian in the header), then two option bytes.
constexpr char kHeader[] = {0x00, 0x01, 0x00, 0x00};

std::uint32_t checked_count(std::size_t n) {
  if (n > std::numeric_limits<std::uint32_t>::max())
    throw std::length_error("CDR: a sequence or string longer than 2^32 - 1");
  return static_cast<std::uint32_t>(n);
}

}  // namespace

void CdrWriter::begin() {
  static_assert(sizeof(kHeader) == kHeaderSize);
  size_ = 0;
  std::memcpy(extend(kHeaderSize), kHeader, kHeaderSize);
}

void CdrWriter::string(std::string_view s) {
  u32(checked_count(s.size() + 1));
  char* at = extend(s.size() + 1);
  if (!s.empty()) std::memcpy(at, s.data(), s.size());
  at[s.size()] = '\0';
}

void CdrWriter::sequence_size(std::size_t n) {
  u32(checked_count(n));
}

void CdrWriter::f32_sequence(std::span<const float> values) {
  sequence_size(values.size());
  if (values.empty()) return;
  align(4);
  if constexpr (std::endian::native == std::endian::little) {
    std::memcpy(extend(values.size_bytes()), values.data(), values.size_bytes());
  } else {
    for (float v : values) f32(v);
  }
}

void CdrWriter::i8_sequence(std::span<const std::int8_t> values) {
  sequence_size(values.size());
  if (!values.empty()) std::memcpy(extend(values.size()), values.data(), values.size());
}

void CdrWriter::f64_array(std::span<const double> values) {
  if (values.empty()) return;
  align(8);
  if constexpr (std::endian::native == std::endian::little) {
    std::memcpy(extend(values.size_bytes()), values.data(), values.size_bytes());
  } else {
    for (double v : values) f64(v);
  }
}

}  // namespace floornav
