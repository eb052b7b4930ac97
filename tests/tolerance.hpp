#pragma once

#include <type_traits>

// Tolerances stated per scalar: double tests hold to near round-off, float
// tests to what 24-bit mantissas allow over the same number of steps.
namespace spook::test {

template <class S>
constexpr S pick(double forDouble, double forFloat) {
  return static_cast<S>(std::is_same_v<S, double> ? forDouble : forFloat);
}

}  // namespace spook::test
