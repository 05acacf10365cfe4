#pragma once
// Shared by the property tests: how many generated cases to run.

#include <algorithm>
#include <cstdlib>

namespace floornav::test {

/// `default_count` in a Release build; a fifth of it in a build without NDEBUG (CI's sanitizer
/// suite, 10-20x slower), so that the test stays within its time limit there. The environment
/// variable `env`, when set, gives the count instead (more cases than CI's time allows).
inline int property_count(const char* env, int default_count) {
  if (const char* n = std::getenv(env)) return std::max(1, std::atoi(n));
#ifdef NDEBUG
  return default_count;
#else
  return std::max(1, default_count / 5);
#endif
}

}  // namespace floornav::test
