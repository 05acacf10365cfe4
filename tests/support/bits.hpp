#pragma once
// Shared by the tests that assert "the same, bit for bit".

#include <bit>
#include <cstdint>

namespace floornav::test {

/// `v` as its bits: compared this way, two doubles are equal only when they are the same value
/// (a NaN equals itself, 0.0 and -0.0 differ), which == does not promise.
inline std::uint64_t bits(double v) {
  return std::bit_cast<std::uint64_t>(v);
}

}  // namespace floornav::test
