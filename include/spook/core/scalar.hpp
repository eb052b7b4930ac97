#pragma once

#include <concepts>
#include <limits>

namespace spook {

/// The floating-point types every physics class is instantiated with.
template <class S>
concept Scalar = std::same_as<S, float> || std::same_as<S, double>;

/// Per-scalar numerical constants, so physics code carries no magic numbers.
template <Scalar S>
struct ScalarTraits {
  /// Machine epsilon of S.
  static constexpr S epsilon() { return std::numeric_limits<S>::epsilon(); }
  /// Relative tolerance for iterative solves inside one step (a few ulps).
  static constexpr S solveTolerance() { return S(8) * std::numeric_limits<S>::epsilon(); }
  /// Tolerance on ‖RᵀR − I‖ when checking that a matrix is a rotation.
  static constexpr S rotationTolerance() { return std::is_same_v<S, float> ? S(1e-4) : S(1e-9); }
  /// Relative tolerance when checking that a matrix is symmetric.
  static constexpr S symmetryTolerance() { return std::is_same_v<S, float> ? S(1e-5) : S(1e-10); }
};

}  // namespace spook
