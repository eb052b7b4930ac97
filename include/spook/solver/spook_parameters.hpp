#pragma once

#include <algorithm>

namespace spook::detail {

/// SPOOK's discretization of one row for a step h (PHYSICS.md §1.2), the
/// single place where a row's compliance and damping become the numbers
/// the solver uses. A holonomic row g with compliance ε and damping τ
/// (d = τ/h) takes, in impulse form,
///   (G M⁻¹ Gᵀ + Σ) Λ = −a g + b Gv − G v*,
/// with a = 4/(h(1+4d)), b = 1/(1+4d), Σ = 4ε/(h²(1+4d)).
/// A velocity row (a speed target, friction, motors) of compliance γ has
/// Σ = γ/h.
struct SpookParameters {
  /// Smallest d = τ/h used: at d = 0 a rigid row's violation obeys
  /// g⁺ = −2g − g⁻ (a double root at −1) and grows step by step; d ≥ 0.1
  /// keeps the roots at |z| = 1/√(1+4d) ≤ 0.85. A smaller τ (0 included)
  /// is raised to it.
  static constexpr double kMinimumDamping = 0.1;

  double a = 0.0;      ///< weight of the violation (1/s)
  double b = 0.0;      ///< weight of the rate Gv
  double sigma = 0.0;  ///< Σ, the regularization of the row's diagonal

  [[nodiscard]] static SpookParameters holonomic(double compliance, double damping, double h) {
    const double d = std::max(damping / h, kMinimumDamping);
    return {4.0 / (h * (1.0 + 4.0 * d)), 1.0 / (1.0 + 4.0 * d), 4.0 * compliance / (h * h * (1.0 + 4.0 * d))};
  }
  [[nodiscard]] static double velocitySigma(double compliance, double h) { return compliance / h; }

  /// The violation whose correction a·g is `speed` (m): what SPOOK turns
  /// into that restoring speed, e.g. the deepest overlap a contact may
  /// report for a capped depenetration speed.
  [[nodiscard]] double violationForSpeed(double speed) const { return speed / a; }
};

}  // namespace spook::detail
