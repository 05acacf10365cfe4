#pragma once
/// @file
/// The one random source of a run: seeded from the scenario, carried in the run's state.

#include <cmath>
#include <cstdint>
#include <random>

namespace floornav {

/// Deterministic random numbers. std::mt19937_64's sequence is fixed by the C++ standard; the
/// distributions are written here because the standard library's are not (they differ between
/// library implementations), and the same seed must give the same trajectory everywhere.
class Rng {
 public:
  explicit Rng(std::uint64_t seed = 1) : engine_(seed) {}

  /// Uniform in [0, 1), 53 random bits.
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }

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
  std::mt19937_64 engine_;
  double spare_{0.0};
  bool has_spare_{false};
};

}  // namespace floornav
