#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include <Eigen/Eigenvalues>

#include <spook/core/implementation.hpp>
#include <spook/core/math.hpp>
#include <spook/solver/island_problem.hpp>
#include <spook/solver/row.hpp>
#include <spook/solver/small_dense.hpp>

namespace spook::detail {

/// Geometric stiffness of the joint forces (Tournier et al., "Stable
/// Constrained Dynamics", SIGGRAPH 2015; Andrews, Teichmann & Kry,
/// "Geometric Stiffness for Real-time Constrained Multibody Dynamics", 2017).
///
/// A force f acting at lever arm r of a body turns with the body: the torque
/// r × f changes by K dθ with K = [f]ₓ[r]ₓ. A light body pulled hard at its
/// ends (a 1 kg link under the weight of 1e6 kg) is a stiff spring of
/// frequency ω² ~ |f||r|/I; the velocity-level step treats it explicitly and
/// is unstable once hω > 2. Taking the term implicitly gives the step
/// (I + h²K̃) ω⁺ = I ω* + h τ_c: the body's inertia grows
/// by h²K̃ and its free rotation is damped by the same factor (backward Euler
/// in the geometry). K̃ is the symmetric, tension-only (negative) part of K.
///
/// The price is backward Euler's damping of the swing the body takes part
/// in, ~h²ω² of its energy per step, so each mode of the body's turn gets it
/// only in proportion to how unstable the explicit step would be: mode k of
/// I⁻¹K̃ with ρ_k = h²ω_k² takes weight max(0, 1 − ρ₀/ρ_k) for a threshold ρ₀
/// (0: every mode at full weight).
///
/// A body held at a single point (a pendulum bob, a load on a hook) has no
/// such spring: turning about its center moves the held point, so its mode
/// is the turn about that point, with inertia I + m([r]ₓᵀ[r]ₓ), about which
/// the force has no torque. Its ρ is taken with that inertia, which keeps
/// the damping off free swinging (a 1 kg bob with I = 0.004 kg·m² on a 1 m
/// hinge has ρ = 2 about its center at 60 Hz, 0.008 about the pivot).
/// Only the directions the point is held in count: with P the projector
/// on the span of its rows' directions the inertia is I + [r]ₓᵀP M P[r]ₓ.
/// A point held along one line (the end of a wire or a distance joint)
/// moves freely across it, so the body rocks about its center against the
/// tension's lever, a spring of ω² = |f||r|/I: 1e5 kg of I = 1 kg·m² hung
/// 0.5 m below its center by a steel wire spun up to 1e4 rad/s at 60 Hz
/// when its turn was taken as about a fixed point. Such a body's modes take
/// the stiffness at full weight (threshold 0): its rocking's (hω)² passes
/// through small values as the held direction turns across its arm, where
/// the weights left it explicit (I = 100 kg·m² at h = 0.1 s: 4,800 rad/s);
/// the swing it takes part in is the wire's, which that does not damp.
///
/// K̃ is taken first from the last step's forces, then from the step's own:
/// a chain's tension jumps from step to step (a 1:1e6 chain released
/// horizontally at h = 0.1 goes from 0 to ~5e6 N in one step), and any part
/// ΔK of the stiffness left out is integrated explicitly, unstable once
/// h²ΔK/I > 4. After each solve refresh() computes the stiffness of the
/// forces just found and, where it exceeds the one the solve used by more
/// than kRefreshTolerance (h²ΔK against I + h²K̃ on the worst axis), the
/// caller solves again with it: a fixed-point iteration of at most
/// kMaxSolves solves. The README's 1:1e6 chain at h = 0.1 holds 2 mm
/// (1.8 repeated solves per step) where the last step's forces let it
/// blow up; at 60 Hz it takes 0.7 repeated solves per step, chains of
/// ratio 1:100 and below almost none.
class GeometricStiffness {
 public:
  /// A solve whose stiffness falls short by less than this (in units of
  /// the body's augmented inertia) leaves a stable explicit remainder
  /// (below 4, with margin).
  static constexpr double kRefreshTolerance = 1.0;
  /// Solves per step at most, the first included.
  static constexpr int kMaxSolves = 4;

  /// Augments `bodies` (inverse inertia, free angular velocity) from the
  /// rows' impulses, for a step of length h, and keeps what it changed for
  /// refresh().
  void apply(const RowSet& rows, std::vector<SolverBody>& bodies, double h, double threshold);

  /// After a solve of the bodies apply() augmented: whether the stiffness
  /// of the rows' impulses now exceeds the one applied by more than
  /// kRefreshTolerance for some body; if so, `bodies` are augmented afresh
  /// with it, to be solved again.
  bool refresh(const RowSet& rows, std::vector<SolverBody>& bodies, double h, double threshold);

  /// The same inertia for the post-stabilization projection of this step.
  void addInertia(std::vector<SolverBody>& bodies) const;

  void clear() {
    added_.clear();
    original_.clear();
    freeVelocity_.clear();
    used_.clear();
  }

 private:
  /// A cheap gate before refresh()'s test: the stiffness of the change of
  /// each row's force, h²Σ|Δf||J||r|, against ‖(I + h²K̃)⁻¹‖ in Frobenius
  /// norms. At threshold 0 it bounds the test from above (the tension-only
  /// part shrinks a change); with a threshold the mode weights (1 − ρ₀/ρ)
  /// can make a small change of force a larger change of K̃, so it is a
  /// heuristic there, one that errs on the side of the last solve.
  bool mayHaveChanged(const RowSet& rows, const std::vector<SolverBody>& bodies, double h);

  /// h²K̃ per body, mode-weighted (class comment), of the rows' impulses
  /// acting on `bodies` (not augmented).
  void compute(const RowSet& rows, const std::vector<SolverBody>& bodies, double h, double threshold,
               std::vector<Mat3d>& added);

  /// The bodies with added_: I → I + h²K̃, and the free angular velocity
  /// with the same angular momentum; the inverse inertias it changes are
  /// kept in original_.
  void augment(std::vector<SolverBody>& bodies);

  /// Exchanges the augmented bodies' inverse inertia with the one they had
  /// before augment().
  void swapOriginalInertia(std::vector<SolverBody>& bodies) {
    for (Original& o : original_) std::swap(bodies[o.body].inverseInertia, o.inverseInertia);
  }

  void accumulate(int body, const Vec3d& force, const Vec3d& arm, const std::vector<SolverBody>& bodies);

  static bool isPositiveSemidefinite(const Mat3d& A) {
    const double minors = A(0, 0) * A(1, 1) - A(0, 1) * A(1, 0) + A(0, 0) * A(2, 2) - A(0, 2) * A(2, 0) +
                          A(1, 1) * A(2, 2) - A(1, 2) * A(2, 1);
    return A.trace() >= 0.0 && minors >= 0.0 && A.determinant() >= 0.0;
  }

  /// Where a body's row forces act: one point (arm from its center) or several.
  struct Held {
    Vec3d arm = Vec3d::Zero();
    Mat3d directions = Mat3d::Zero();  ///< Σ d dᵀ of the rows' unit directions there
    int rows = 0;
    bool single = false;
  };

  /// Whether two rows' arms reach one point: those of one joint's rows
  /// differ by its violation (Dot2 rows act at p₁).
  static bool sameArm(const Vec3d& arm, const Vec3d& heldArm) {
    return (arm - heldArm).norm() <= 1e-3 * (1.0 + arm.norm());
  }

  /// Projector on the span of a held point's row directions (Held::directions).
  static Mat3d heldDirections(const Mat3d& directions) {
    const Eigen::SelfAdjointEigenSolver<Mat3d> eigen(directions);
    Mat3d projector = Mat3d::Zero();
    const double largest = eigen.eigenvalues().maxCoeff();
    for (int k = 0; k < 3; ++k)
      if (eigen.eigenvalues()(k) > 1e-6 * largest)
        projector.noalias() += eigen.eigenvectors().col(k) * eigen.eigenvectors().col(k).transpose();
    return projector;
  }

  struct Original {
    std::size_t body;
    Mat3d inverseInertia;
  };
  std::vector<Original> original_;   ///< the augmented bodies' inverse inertia before augment()
  std::vector<Vec6d> freeVelocity_;  ///< every body's free velocity before apply()
  std::vector<Mat3d> added_, fresh_, stiffness_, solvedWith_;
  std::vector<double> used_;    ///< the impulses added_ was computed from
  std::vector<double> change_;  ///< per body, mayHaveChanged's bound
  std::vector<Held> heldAt_;
  bool any_ = false;
};

#if defined(SPOOK_DEFINES_NON_TEMPLATES)
SPOOK_INLINE void GeometricStiffness::apply(const RowSet& rows, std::vector<SolverBody>& bodies, double h,
                                            double threshold) {
  freeVelocity_.resize(bodies.size());
  for (std::size_t i = 0; i < bodies.size(); ++i) freeVelocity_[i] = bodies[i].freeVelocity;
  compute(rows, bodies, h, threshold, added_);
  augment(bodies);
  used_ = rows.impulses;
}

SPOOK_INLINE bool GeometricStiffness::refresh(const RowSet& rows, std::vector<SolverBody>& bodies, double h,
                                              double threshold) {
  if (added_.size() != bodies.size() || used_.size() != rows.size() || !mayHaveChanged(rows, bodies, h)) return false;
  // The inverse inertia each body was solved with; the fresh stiffness is
  // computed on the bodies' own inertia.
  solvedWith_.resize(bodies.size());
  for (std::size_t i = 0; i < bodies.size(); ++i) solvedWith_[i] = bodies[i].inverseInertia;
  swapOriginalInertia(bodies);
  compute(rows, bodies, h, threshold, fresh_);
  bool changed = false;
  for (std::size_t i = 0; i < bodies.size() && !changed; ++i) {
    const Mat3d change = fresh_[i] - added_[i];
    if (!bodies[i].dynamic || change.isZero(0.0)) continue;
    // The largest eigenvalue of LᵀΔA L, L Lᵀ = (I + h²K̃)⁻¹: the stiffness
    // the solve left out, in units of the inertia it used, on the worst
    // axis. Stiffness it took in excess only damps more.
    Mat3d L;
    if (!choleskyLower<3>(solvedWith_[i], L)) continue;
    changed = Eigen::SelfAdjointEigenSolver<Mat3d>(L.transpose() * change * L, Eigen::EigenvaluesOnly)
                  .eigenvalues()
                  .maxCoeff() > kRefreshTolerance;
  }
  if (!changed) {
    swapOriginalInertia(bodies);
    return false;
  }
  // The bodies as apply() found them (the solve added its impulses to
  // the free velocities), augmented afresh.
  for (std::size_t i = 0; i < bodies.size(); ++i) bodies[i].freeVelocity = freeVelocity_[i];
  std::swap(added_, fresh_);
  used_ = rows.impulses;
  augment(bodies);
  return true;
}

SPOOK_INLINE void GeometricStiffness::addInertia(std::vector<SolverBody>& bodies) const {
  if (added_.size() != bodies.size()) return;
  for (std::size_t i = 0; i < bodies.size(); ++i)
    if (bodies[i].dynamic && !added_[i].isZero(0.0))
      bodies[i].inverseInertia = (bodies[i].inverseInertia.inverse() + added_[i]).inverse();
}

SPOOK_INLINE bool GeometricStiffness::mayHaveChanged(const RowSet& rows, const std::vector<SolverBody>& bodies,
                                                     double h) {
  change_.assign(bodies.size(), 0.0);
  for (const LeverArms& a : rows.arms) {
    const auto k = static_cast<std::size_t>(a.row);
    const Row& r = rows.rows[k];
    const double force = std::abs(rows.impulses[k] - used_[k]) / h;
    if (force == 0.0) continue;
    if (r.body1 >= 0) change_[std::size_t(r.body1)] += force * r.J1.head<3>().norm() * a.arm1.norm();
    if (r.body2 >= 0) change_[std::size_t(r.body2)] += force * r.J2.head<3>().norm() * a.arm2.norm();
  }
  for (std::size_t i = 0; i < bodies.size(); ++i)
    if (bodies[i].dynamic && h * h * change_[i] * bodies[i].inverseInertia.norm() > kRefreshTolerance) return true;
  return false;
}

SPOOK_INLINE void GeometricStiffness::compute(const RowSet& rows, const std::vector<SolverBody>& bodies, double h,
                                              double threshold, std::vector<Mat3d>& added) {
  added.assign(bodies.size(), Mat3d::Zero());
  stiffness_.assign(bodies.size(), Mat3d::Zero());
  heldAt_.assign(bodies.size(), Held{});
  any_ = false;
  for (const LeverArms& a : rows.arms) {
    const Row& r = rows.rows[static_cast<std::size_t>(a.row)];
    const double force = rows.impulses[static_cast<std::size_t>(a.row)] / h;
    if (force == 0.0) continue;
    accumulate(r.body1, force * r.J1.head<3>(), a.arm1, bodies);
    accumulate(r.body2, force * r.J2.head<3>(), a.arm2, bodies);
  }
  if (!any_) return;
  // The directions a single held point is held in: those of every row
  // acting there, loaded or not (a bob hanging on a hinge loads only the
  // row along its rod); gathered once a body needs them.
  bool directionsGathered = false;
  const auto gatherDirections = [&] {
    const auto holdAlong = [&](int body, const Vec3d& direction, const Vec3d& arm) {
      if (body < 0) return;
      Held& held = heldAt_[static_cast<std::size_t>(body)];
      const double length = direction.norm();
      if (held.single && length > 0.0 && sameArm(arm, held.arm))
        held.directions.noalias() += direction * direction.transpose() / (length * length);
    };
    for (const LeverArms& a : rows.arms) {
      const Row& r = rows.rows[static_cast<std::size_t>(a.row)];
      holdAlong(r.body1, r.J1.head<3>(), a.arm1);
      holdAlong(r.body2, r.J2.head<3>(), a.arm2);
    }
    directionsGathered = true;
  };
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const SolverBody& b = bodies[i];
    if (!b.dynamic || stiffness_[i].isZero(0.0)) continue;
    const Mat3d symmetric = 0.5 * (stiffness_[i] + stiffness_[i].transpose());
    // ρ ≤ h²‖K̃‖‖I⁻¹‖: most bodies of an ordinary scene stop here.
    if (h * h * symmetric.norm() * b.inverseInertia.norm() <= threshold) continue;
    // No tension where every eigenvalue is ≥ 0, that is where the trace,
    // the sum of the principal 2×2 minors and the determinant all are (the
    // coefficients of a real-rooted characteristic polynomial): a body
    // pressed by contacts, spared the eigensolver.
    if (isPositiveSemidefinite(symmetric)) continue;
    const Eigen::SelfAdjointEigenSolver<Mat3d> eigen(symmetric);
    const Vec3d tension = (-eigen.eigenvalues()).cwiseMax(0.0);
    if (tension.maxCoeff() <= 0.0) continue;
    const Mat3d stiffness = eigen.eigenvectors() * tension.asDiagonal() * eigen.eigenvectors().transpose();
    const Held& held = heldAt_[i];
    const Mat3d arm = skew<double>(held.arm);
    Mat3d modeInverseInertia = b.inverseInertia;
    double modeThreshold = threshold;
    if (held.single) {
      if (!directionsGathered) gatherDirections();
      const Mat3d P = heldDirections(held.directions);
      modeInverseInertia =
          (b.inverseInertia.inverse() + arm.transpose() * P * b.inverseMass.inverse() * P * arm).inverse();
      if (P.trace() < 2.5) modeThreshold = 0.0;
    }
    // Modes of the body's turn: I⁻¹K̃ has eigenvalues ω_k²; with
    // I⁻¹ = L Lᵀ they are those of LᵀK̃L = U diag(ω²) Uᵀ, and mode k adds
    // L⁻ᵀu_k ω_k² u_kᵀL⁻¹ to K̃. Each mode is taken with its own weight,
    // so that a stiff turn (a point-like bob twisting about its rod) does
    // not damp the body's other, soft ones (its swing).
    Mat3d L, inverseL;
    if (!choleskyLower<3>(modeInverseInertia, L)) continue;
    invertLowerTriangular<3>(L, inverseL);
    const Eigen::SelfAdjointEigenSolver<Mat3d> modes(L.transpose() * stiffness * L);
    const Mat3d toStiffness = inverseL.transpose() * modes.eigenvectors();
    Vec3d weighted = Vec3d::Zero();
    for (int k = 0; k < 3; ++k) {
      const double rho = h * h * modes.eigenvalues()(k);
      if (rho > modeThreshold) weighted(k) = (1.0 - modeThreshold / rho) * modes.eigenvalues()(k);
    }
    if (!weighted.isZero(0.0)) added[i] = h * h * toStiffness * weighted.asDiagonal() * toStiffness.transpose();
  }
}

SPOOK_INLINE void GeometricStiffness::augment(std::vector<SolverBody>& bodies) {
  original_.clear();
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (added_[i].isZero(0.0)) continue;
    SolverBody& b = bodies[i];
    original_.push_back({i, b.inverseInertia});
    const Mat3d inertia = b.inverseInertia.inverse();
    b.inverseInertia = (inertia + added_[i]).inverse();
    b.freeVelocity.tail<3>() = b.inverseInertia * (inertia * b.freeVelocity.tail<3>());
  }
}

SPOOK_INLINE void GeometricStiffness::accumulate(int body, const Vec3d& force, const Vec3d& arm,
                                                 const std::vector<SolverBody>& bodies) {
  if (body < 0 || !bodies[static_cast<std::size_t>(body)].dynamic || arm.isZero(0.0)) return;
  const auto i = static_cast<std::size_t>(body);
  // [f]ₓ[r]ₓ = r fᵀ − (f·r) 1
  stiffness_[i].noalias() += arm * force.transpose();
  stiffness_[i].diagonal().array() -= force.dot(arm);
  Held& held = heldAt_[i];
  if (held.rows == 0) held.arm = arm;
  held.single = (held.rows == 0 || held.single) && sameArm(arm, held.arm);
  ++held.rows;
  any_ = true;
}
#endif

}  // namespace spook::detail
