#pragma once

#include <algorithm>
#include <cmath>

namespace spook::detail {

// Bounds on the second-order terms κ = ½vᵀ∇²g v (SecondOrder::curvature) of
// rows whose bodies or ends turn by radians in a step of h, where the Taylor
// terms grow as the square of the turn and pull the step's nodes or bodies
// out by more than the row's own size.

/// (1 − cos φ)/(φ²/2) for the turn φ = ω h: the share of a centripetal term
/// ω×(ω×r) that the turn's exact motion keeps, 1 for small turns and at most
/// 4/φ² beyond a radian; 1 for h = 0.
inline double turnShare(double angularSpeed, double h) {
  const double half = 0.5 * angularSpeed * h;
  const double sinc = half > 1e-4 ? std::sin(half) / half : 1.0;
  return sinc * sinc;
}

/// κ of a length L whose ends part across it at `across` (m/s): the exact
/// lengthening over the step, √(L² + s²) − L = s²/(√(L² + s²) + L) with
/// s = across·h, over h²; the Taylor term across²/(2L) for turns well below a
/// radian (and for h = 0).
inline double partingCurvature(double across, double length, double h) {
  return across * across / (std::hypot(length, across * h) + length);
}

/// κ with the step's second-order change h²κ within half of `length`:
/// beyond, no motion along the step's start direction keeps the length and
/// the term only shoots the ends. Unbounded for h = 0.
inline double halfLengthBound(double curvature, double length, double h) {
  if (!(h > 0.0)) return curvature;
  const double most = 0.5 * length / (h * h);
  return std::clamp(curvature, -most, most);
}

}  // namespace spook::detail
