#pragma once
/// @file
/// The CDR encoding of a ROS 2 message: XCDR1 (PLAIN_CDR), little-endian, as ROS 2's middleware
/// writes it and as a ROS 2 bag (MCAP profile `ros2`, message encoding `cdr`) stores it: the
/// 4-byte encapsulation header 00 01 00 00, then each field in order, every primitive aligned to
/// its own size (at most 8) counted from the end of the header; a string is a uint32 length that
/// counts its terminating NUL, the bytes, the NUL; a sequence is a uint32 element count, then
/// the elements; a fixed-size array is its elements alone. Written here (a few dozen lines)
/// rather than taken from a library: Debian 12 packages no CDR encoder outside a DDS stack.

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <string_view>
#include <utility>

namespace floornav {

class CdrWriter {
 public:
  /// Starts a message: the buffer is emptied (its memory kept) and gets the header.
  void begin();

  void u8(std::uint8_t v) { *extend(1) = static_cast<char>(v); }
  void i8(std::int8_t v) { u8(static_cast<std::uint8_t>(v)); }
  void boolean(bool v) { u8(v ? 1 : 0); }
  void i32(std::int32_t v) { put(v); }
  void u32(std::uint32_t v) { put(v); }
  void f32(float v) { put(v); }
  void f64(double v) { put(v); }
  void string(std::string_view s);
  /// A sequence's element count (the elements follow, each written by the caller).
  void sequence_size(std::size_t n);
  /// A sequence of float32 (count, then the values): LaserScan's ranges.
  void f32_sequence(std::span<const float> values);
  /// A sequence of int8 (count, then the bytes): OccupancyGrid's data.
  void i8_sequence(std::span<const std::int8_t> values);
  /// A fixed-size array of float64 (no count): a covariance.
  void f64_array(std::span<const double> values);

  /// The message so far, header included.
  std::string_view data() const { return {buffer_.data(), size_}; }
  /// Pads to a multiple of `alignment` (1, 2, 4 or 8) and returns where the next field starts:
  /// where a primitive of that size written next lands (a message template patches it there).
  std::size_t next_at(std::size_t alignment) {
    align(alignment);
    return size_;
  }

 private:
  static constexpr std::size_t kHeaderSize = 4;

  /// `n` more bytes at the end of the message, to be written by the caller. The buffer grows by
  /// doubling and is kept from message to message: a message of a run allocates nothing.
  char* extend(std::size_t n) {
    if (size_ + n > buffer_.size()) buffer_.resize(std::max(2 * buffer_.size(), size_ + n));
    char* at = buffer_.data() + size_;
    size_ += n;
    return at;
  }
  /// Pads with zero bytes to a multiple of `n` counted from the end of the header.
  void align(std::size_t n) {  // n: 1, 2, 4 or 8
    const std::size_t pad = (kHeaderSize - size_) & (n - 1);
    if (pad != 0) std::memset(extend(pad), 0, pad);
  }
  template <class T>
  void put(T v) {
    static_assert(std::endian::native == std::endian::little ||
                  std::endian::native == std::endian::big);
    align(sizeof(T));
    char bytes[sizeof(T)];
    std::memcpy(bytes, &v, sizeof(T));
    if constexpr (std::endian::native == std::endian::big)
      for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
    std::memcpy(extend(sizeof(T)), bytes, sizeof(T));
  }

  std::string buffer_;  ///< its first size_ bytes are the message
  std::size_t size_{0};
};

}  // namespace floornav
