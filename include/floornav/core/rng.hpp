#pragma once
/// @file
/// The one random source of a run: seeded from the scenario, carried in the run's state.

#include <cmath>
#include <cstdint>

namespace floornav {

/// Deterministic random numbers: xoshiro256** (Blackman and Vigna, 2018) seeded through
/// splitmix64, as its authors recommend. Written here rather than std::mt19937_64 because every
/// robot of a fleet carries one: 32 bytes of state instead of 2.5 KB (100,000 robots: 3 MB, not
/// 250 MB), with the same statistical quality for this use. The distributions are written here
/// too, because the standard library's differ between implementations and the same seed must
/// give the same trajectory everywhere.
class Rng {
 public:
  explicit Rng(std::uint64_t seed = 1) {
    for (std::uint64_t& word : s_) word = splitmix64(seed);
  }

  /// The next 64 random bits.
  std::uint64_t next() {
    const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }

  /// Uniform in [0, 1), 53 random bits.
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  /// Uniform in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

  /// Standard normal, by the Box-Muller transform.
  double normal() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    double u1 = uniform();
    while (u1 <= 0.0) u1 = uniform();
    const double u2 = uniform();
    const double r = std::sqrt(-2.0 * std::log(u1));
    spare_ = r * std::sin(2.0 * 3.141592653589793 * u2);
    has_spare_ = true;
    return r * std::cos(2.0 * 3.141592653589793 * u2);
  }

 private:
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  static std::uint64_t splitmix64(std::uint64_t& state) {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }

  std::uint64_t s_[4];
  double spare_{0.0};
  bool has_spare_{false};
};

}  // namespace floornav
