#pragma once

#include <type_traits>

// Tolerances stated per scalar: double tests hold to near round-off, float
// tests to what 24-bit mantissas allow over the same number of steps.
namespace spook::test {

template <class S>
constexpr S pick(double forDouble, double forFloat) {
  return static_cast<S>(std::is_same_v<S, double> ? forDouble : forFloat);
}

/// Sweep sizes (poses, cells, steps): `full` in optimized builds, `reduced`
/// without NDEBUG (CI's sanitizer stage, Debug at -O1 under ASan and UBSan,
/// some 20 times slower), where the sweeps look for memory and undefined
/// behaviour faults rather than measure accuracy.
constexpr int sweep(int full, int reduced) {
#ifdef NDEBUG
  (void)reduced;
  return full;
#else
  (void)full;
  return reduced;
#endif
}

}  // namespace spook::test
