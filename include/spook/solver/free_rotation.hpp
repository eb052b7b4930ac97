#pragma once

#include <cmath>
#include <utility>

#include <spook/core/math.hpp>
#include <spook/core/scalar.hpp>

namespace spook::detail {

/// Result of advancing a torque-free rotation over one step.
template <Scalar S>
struct FreeRotation {
  QuatT<S> increment;  ///< body-frame rotation over the step: R⁺ = R · increment
  Vec3T<S> momentum;   ///< body-frame angular momentum at the end, Π⁺ (kg·m²/s)
  bool converged;
};

/// A 3×3 matrix factorized by Gaussian elimination with partial pivoting
/// (what Eigen's PartialPivLU does, without instantiating its blocked
/// kernels in every simulation part): stable where the closed-form inverse
/// overflows, e.g. float entries beyond ~1e12 whose determinant exceeds
/// the type's range.
template <Scalar S>
class PivotedLu3 {
 public:
  explicit PivotedLu3(const Mat3T<S>& m) : lu_(m) {
    for (int k = 0; k < 3; ++k) {
      int pivot = k;
      for (int i = k + 1; i < 3; ++i)
        if (std::abs(lu_(i, k)) > std::abs(lu_(pivot, k))) pivot = i;
      if (pivot != k) {
        lu_.row(pivot).swap(lu_.row(k));
        std::swap(order_[pivot], order_[k]);
      }
      for (int i = k + 1; i < 3; ++i) {
        lu_(i, k) /= lu_(k, k);
        for (int j = k + 1; j < 3; ++j) lu_(i, j) -= lu_(i, k) * lu_(k, j);
      }
    }
  }
  [[nodiscard]] Vec3T<S> solve(const Vec3T<S>& b) const {
    Vec3T<S> x(b(order_[0]), b(order_[1]), b(order_[2]));
    for (int i = 1; i < 3; ++i)
      for (int j = 0; j < i; ++j) x(i) -= lu_(i, j) * x(j);
    for (int i = 2; i >= 0; --i) {
      for (int j = i + 1; j < 3; ++j) x(i) -= lu_(i, j) * x(j);
      x(i) /= lu_(i, i);
    }
    return x;
  }

 private:
  Mat3T<S> lu_;
  int order_[3] = {0, 1, 2};
};

/// One torque-free step of Euler's equations, Π̇ = Π × I⁻¹Π, in the body
/// frame: Π⁺ = exp(−h ω̂ₘ) Π with the mean angular velocity
/// ωₘ = I⁻¹(Π + Π⁺)/2, and the orientation advanced by R⁺ = R exp(h ω̂ₘ).
/// World momentum R⁺Π⁺ = RΠ exactly (Π⁺ is Π rotated back by the same
/// rotation), and the kinetic energy is kept to solver tolerance:
/// E⁺ − E = (Π⁺ − Π)·ωₘ = 0 since a rotation about ωₘ leaves the component
/// of Π along ωₘ unchanged. Unlike an explicit −ω×Iω torque (energy grows)
/// or implicit Euler (energy decays), a free body keeps spinning as it
/// should, and flips about its intermediate axis (Dzhanibekov). The implicit
/// equation is solved by Newton steps with the Jacobian I − (h/2)[Π]ₓ I⁻¹.
template <Scalar S>
FreeRotation<S> freeRotationStep(const Mat3T<S>& inertiaInverse, const Vec3T<S>& momentum, S h) {
  using Vec3 = spook::Vec3T<S>;
  const S scale = momentum.norm();
  if (!(scale > S(0))) return {QuatT<S>::Identity(), momentum, true};
  const S tolerance = ScalarTraits<S>::solveTolerance() * scale;
  const Mat3T<S> jacobian = Mat3T<S>::Identity() - S(0.5) * h * skew<S>(momentum) * inertiaInverse;
  // J = I − (h/2)[Π]ₓI⁻¹ is similar to I minus a skew matrix (eigenvalues
  // 1 ± iλ): never singular, |det J| ≥ 1.
  const PivotedLu3<S> jacobianLu(jacobian);

  Vec3 next = momentum;
  Vec3 meanVelocity = inertiaInverse * momentum;
  bool converged = false;
  constexpr int kMaxIterations = 30;
  for (int i = 0; i < kMaxIterations && !converged; ++i) {
    meanVelocity = S(0.5) * inertiaInverse * (momentum + next);
    const Vec3 residual = next - expRotation<S>(-h * meanVelocity) * momentum;
    const Vec3 correction = jacobianLu.solve(residual);
    next -= correction;
    converged = correction.norm() <= tolerance;
  }
  meanVelocity = S(0.5) * inertiaInverse * (momentum + next);
  const QuatT<S> increment = expRotation<S>(h * meanVelocity);
  // Π⁺ from the final rotation, so that the world momentum is exact.
  return {increment, increment.conjugate() * momentum, converged};
}

/// freeRotationStep, split into 2, 4, … 64 substeps when the Newton solve
/// does not converge in one (very fast spin relative to the step).
template <Scalar S>
FreeRotation<S> rotateFreely(const Mat3T<S>& inertiaInverse, const Vec3T<S>& momentum, S h) {
  FreeRotation<S> result{};
  for (int substeps = 1; substeps <= 64; substeps *= 2) {
    result = {QuatT<S>::Identity(), momentum, true};
    const S dt = h / S(substeps);
    for (int k = 0; k < substeps; ++k) {
      const FreeRotation<S> part = freeRotationStep<S>(inertiaInverse, result.momentum, dt);
      result.increment = (result.increment * part.increment).normalized();
      result.momentum = part.momentum;
      result.converged = result.converged && part.converged;
    }
    if (result.converged) break;
  }
  return result;
}

}  // namespace spook::detail
