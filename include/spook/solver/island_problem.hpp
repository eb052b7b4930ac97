#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <limits>
#include <vector>

#include <Eigen/Core>

#include <spook/core/geometric_growth.hpp>
#include <spook/core/implementation.hpp>
#include <spook/solver/row.hpp>

// The iterative sweeps' innermost calls, which GCC 12 left out of line
// (a tenth of a 210-cube pyramid's hybrid step in the calls themselves).
#if defined(__GNUC__) || defined(__clang__)
#define SPOOK_ALWAYS_INLINE [[gnu::always_inline]] inline
#else
#define SPOOK_ALWAYS_INLINE inline
#endif

namespace spook::detail {

using Vec3d = Eigen::Vector3d;
using Mat3d = Eigen::Matrix3d;
using Mat6d = Eigen::Matrix<double, 6, 6>;

// v += w·s, written out: GCC 12 leaves Eigen's `v += w * s` out of line in
// the sweeps. In pairs, as the row velocities read v (Eigen's packets): a
// pair of 8-byte stores cannot be forwarded to the next row's 16-byte load,
// which then waits for the cache (the sweeps took 10-25% longer with scalar
// stores).
SPOOK_ALWAYS_INLINE void addScaled(Vec6d& v, const Vec6d& w, double s) {
  using Pair = Eigen::Matrix<double, 2, 1>;
  for (int k = 0; k < 6; k += 2) {
    Eigen::Map<Pair> out(v.data() + k);
    out = out + Eigen::Map<const Pair>(w.data() + k) * s;
  }
}

/// A body as the solver sees it: velocities of the center of mass (world)
/// at the start of the step and after the applied forces, and the inverse
/// mass and inertia in world coordinates (zero unless dynamic).
struct SolverBody {
  Vec6d velocity = Vec6d::Zero();      ///< v_k: (linear, angular)
  Vec6d freeVelocity = Vec6d::Zero();  ///< v*: v_k advanced by the applied forces
  Vec6d displacement = Vec6d::Zero();  ///< post-stabilization: (Δx, Δθ)
  Mat3d inverseMass = Mat3d::Zero();
  Mat3d inverseInertia = Mat3d::Zero();
  bool dynamic = false;
};

/// The rows of one island in solver form: (S + Σ) Λ = q + w with
/// S = G M⁻¹ Gᵀ, bounds lo ≤ Λ ≤ hi (impulses, N·s) and the complementarity
/// of PHYSICS.md §2.1. Bodies are numbered locally (−1: none or not dynamic).
struct IslandProblem {
  struct Entry {
    /// The row's dynamic bodies (distinct): body1, body2 and, for the rare
    /// row of three (a wire's bend row), extraBodies[extra].
    int body1 = -1, body2 = -1;
    int extra = -1;
    Vec6d J1 = Vec6d::Zero(), J2 = Vec6d::Zero();
    Vec6d W1 = Vec6d::Zero(), W2 = Vec6d::Zero();  ///< M⁻¹Jᵀ per body
    double q = 0.0;                                ///< right-hand side, m/s or rad/s
    double sigma = 0.0;                            ///< regularization Σ
    double diagonal = 0.0;                         ///< S_ii + Σ_i
    double lower = 0.0, upper = 0.0;               ///< impulse bounds
    double impulse = 0.0;                          ///< Λ (warm start in, result out)
    /// The impulse the direct solver's pivoting starts its active set from:
    /// the last step's, then each direct solve's own result.
    double guess = 0.0;
    SolveType solveType = SolveType::DIRECT;
    int constraint = -1;  ///< local index of its constraint's first row (Row::constraint)
    int normal = -1;      ///< friction rows: local index of their normal row
    int partner = -1;     ///< cone rows: the other tangent row of the point
    double mu = 0.0;      ///< friction coefficient
    FrictionBound frictionBound = FrictionBound::FIXED;
    /// Cone rows in a direct solve: the share |d_i| of the bound μΛn this
    /// tangent gets, d the friction direction of the point (friction_bounds.hpp).
    double coneShare = 1.0;

    [[nodiscard]] bool bounded() const {
      return lower > -std::numeric_limits<double>::infinity() || upper < std::numeric_limits<double>::infinity();
    }
    [[nodiscard]] bool followsNormal() const { return normal >= 0 && frictionBound != FrictionBound::FIXED; }
    /// A friction row solved by the iterative pass of a SPLIT contact.
    [[nodiscard]] bool splitFriction() const { return normal >= 0 && solveType == SolveType::SPLIT; }
  };

  /// A row's third body: its block of G and of M⁻¹Gᵀ.
  struct ExtraBody {
    int body = -1;
    Vec6d J = Vec6d::Zero(), W = Vec6d::Zero();
  };

  std::vector<Entry> rows;
  std::vector<ExtraBody> extraBodies;
  int numBodies = 0;
  /// Each body's mass matrix M = diag(m, I) (world; the inverse of its
  /// inverse mass and inertia), non-finite where those are singular; empty
  /// unless the rows outnumber the bodies' degrees of freedom
  /// (BodySpaceSolve::outnumbers).
  std::vector<Mat6d> mass;

  /// Calls f(body, J, W) for each body of the entry.
  template <class F>
  void forEachBody(const Entry& e, F&& f) const {
    if (e.body1 >= 0) f(e.body1, e.J1, e.W1);
    if (e.body2 >= 0) f(e.body2, e.J2, e.W2);
    if (e.extra >= 0) {
      const ExtraBody& x = extraBodies[static_cast<std::size_t>(e.extra)];
      f(x.body, x.J, x.W);
    }
  }
  /// The entry's three body slots (−1: none).
  [[nodiscard]] std::array<int, 3> bodiesOf(const Entry& e) const;
  /// Adds body b's block (J, W = M⁻¹Jᵀ) to the entry, or adds to the
  /// block it has for b.
  void addBody(Entry& e, int b, const Vec6d& J, const Vec6d& W);
  /// The same with W = M⁻¹Jᵀ of a body of inverse mass and inertia
  /// (world), formed in the entry's own storage where the body is new to it.
  void addBody(Entry& e, int b, const Vec6d& J, const Mat3d& inverseMass, const Mat3d& inverseInertia);
  /// J·W over the entry's bodies: its diagonal of S = G M⁻¹ Gᵀ.
  [[nodiscard]] double mobility(const Entry& e) const;

  /// Δv of every body from the impulses of all rows.
  [[nodiscard]] std::vector<Vec6d> velocityChange() const;
  void velocityChange(std::vector<Vec6d>& dv) const;
  /// Δv of every body from the impulses of `subset` (rows not in it count zero).
  [[nodiscard]] std::vector<Vec6d> velocityChange(const std::vector<int>& subset) const;
  SPOOK_ALWAYS_INLINE void addImpulse(std::vector<Vec6d>& dv, int i, double impulse) const {
    // Written out (not forEachBody): the iterative sweeps' innermost loop.
    const Entry& e = rows[static_cast<std::size_t>(i)];
    if (e.body1 >= 0) addScaled(dv[static_cast<std::size_t>(e.body1)], e.W1, impulse);
    if (e.body2 >= 0) addScaled(dv[static_cast<std::size_t>(e.body2)], e.W2, impulse);
    if (e.extra >= 0) {
      const ExtraBody& x = extraBodies[static_cast<std::size_t>(e.extra)];
      addScaled(dv[static_cast<std::size_t>(x.body)], x.W, impulse);
    }
  }
  /// The entries of `indices`, for restore() after an attempt is dropped.
  [[nodiscard]] std::vector<Entry> entries(const std::vector<int>& indices) const;
  void restore(const std::vector<int>& indices, const std::vector<Entry>& kept);
  /// G_i Δv.
  [[nodiscard]] SPOOK_ALWAYS_INLINE double rowVelocity(int i, const std::vector<Vec6d>& dv) const {
    const Entry& e = rows[static_cast<std::size_t>(i)];
    double v = 0.0;
    if (e.body1 >= 0) v += e.J1.dot(dv[static_cast<std::size_t>(e.body1)]);
    if (e.body2 >= 0) v += e.J2.dot(dv[static_cast<std::size_t>(e.body2)]);
    if (e.extra >= 0) {
      const ExtraBody& x = extraBodies[static_cast<std::size_t>(e.extra)];
      v += x.J.dot(dv[static_cast<std::size_t>(x.body)]);
    }
    return v;
  }
  /// (S + Σ)_ij for rows i ≠ j: the coupling through their shared bodies.
  [[nodiscard]] double coupling(int i, int j) const;
};

#if defined(SPOOK_DEFINES_NON_TEMPLATES)
SPOOK_INLINE std::array<int, 3> IslandProblem::bodiesOf(const Entry& e) const {
  return {e.body1, e.body2, e.extra >= 0 ? extraBodies[static_cast<std::size_t>(e.extra)].body : -1};
}

SPOOK_INLINE void IslandProblem::addBody(Entry& e, int b, const Vec6d& J, const Vec6d& W) {
  if (e.body1 < 0) {
    e.body1 = b;
    e.J1 = J;
    e.W1 = W;
  } else if (e.body1 == b) {
    e.J1 += J;
    e.W1 += W;
  } else if (e.body2 < 0) {
    e.body2 = b;
    e.J2 = J;
    e.W2 = W;
  } else if (e.body2 == b) {
    e.J2 += J;
    e.W2 += W;
  } else if (e.extra < 0) {
    e.extra = static_cast<int>(extraBodies.size());
    extraBodies.push_back({b, J, W});
  } else {
    ExtraBody& x = extraBodies[static_cast<std::size_t>(e.extra)];
    x.J += J;
    x.W += W;
  }
}

SPOOK_INLINE void IslandProblem::addBody(Entry& e, int b, const Vec6d& J, const Mat3d& inverseMass,
                                         const Mat3d& inverseInertia) {
  Vec6d* slotJ = nullptr;
  Vec6d* slotW = nullptr;
  if (e.body1 < 0) {
    e.body1 = b;
    slotJ = &e.J1;
    slotW = &e.W1;
  } else if (e.body2 < 0 && e.body1 != b) {
    e.body2 = b;
    slotJ = &e.J2;
    slotW = &e.W2;
  }
  if (slotJ) {
    *slotJ = J;
    slotW->head<3>().noalias() = inverseMass * J.head<3>();
    slotW->tail<3>().noalias() = inverseInertia * J.tail<3>();
    return;
  }
  Vec6d W;
  W << inverseMass * J.head<3>(), inverseInertia * J.tail<3>();
  addBody(e, b, J, W);
}

SPOOK_INLINE double IslandProblem::mobility(const Entry& e) const {
  double s = 0.0;
  if (e.body1 >= 0) s += e.J1.dot(e.W1);
  if (e.body2 >= 0) s += e.J2.dot(e.W2);
  if (e.extra >= 0)
    s += extraBodies[static_cast<std::size_t>(e.extra)].J.dot(extraBodies[static_cast<std::size_t>(e.extra)].W);
  return s;
}

SPOOK_INLINE std::vector<Vec6d> IslandProblem::velocityChange() const {
  std::vector<Vec6d> dv;
  velocityChange(dv);
  return dv;
}

SPOOK_INLINE void IslandProblem::velocityChange(std::vector<Vec6d>& dv) const {
  assignGrowing(dv, static_cast<std::size_t>(numBodies), Vec6d(Vec6d::Zero()));
  for (int i = 0; i < static_cast<int>(rows.size()); ++i) addImpulse(dv, i, rows[static_cast<std::size_t>(i)].impulse);
}

SPOOK_INLINE std::vector<Vec6d> IslandProblem::velocityChange(const std::vector<int>& subset) const {
  std::vector<Vec6d> dv(static_cast<std::size_t>(numBodies), Vec6d::Zero());
  for (int i : subset) addImpulse(dv, i, rows[static_cast<std::size_t>(i)].impulse);
  return dv;
}

SPOOK_INLINE auto IslandProblem::entries(const std::vector<int>& indices) const -> std::vector<Entry> {
  std::vector<Entry> kept;
  kept.reserve(indices.size());
  for (int i : indices) kept.push_back(rows[static_cast<std::size_t>(i)]);
  return kept;
}

SPOOK_INLINE void IslandProblem::restore(const std::vector<int>& indices, const std::vector<Entry>& kept) {
  for (std::size_t k = 0; k < indices.size(); ++k) rows[static_cast<std::size_t>(indices[k])] = kept[k];
}

SPOOK_INLINE double IslandProblem::coupling(int i, int j) const {
  const Entry& a = rows[static_cast<std::size_t>(i)];
  const Entry& b = rows[static_cast<std::size_t>(j)];
  double s = 0.0;
  forEachBody(a, [&](int bodyA, const Vec6d& J, const Vec6d&) {
    forEachBody(b, [&](int bodyB, const Vec6d&, const Vec6d& W) {
      if (bodyA == bodyB) s += J.dot(W);
    });
  });
  return s;
}
#endif

/// Complementarity error of row i at residual w = (S+Σ)Λ − q (m/s): |w| for
/// a row strictly inside its bounds, the wrong-signed part of w at a bound.
[[nodiscard]] SPOOK_INLINE double complementarityError(const IslandProblem::Entry& e, double w);

#if defined(SPOOK_DEFINES_NON_TEMPLATES)
SPOOK_INLINE double complementarityError(const IslandProblem::Entry& e, double w) {
  const double tolerance = 1e-12 * (1.0 + std::abs(e.impulse));
  const bool atLower = e.impulse <= e.lower + tolerance;
  const bool atUpper = e.impulse >= e.upper - tolerance;
  if (atLower && atUpper) return 0.0;
  if (atLower) return std::max(0.0, -w);
  if (atUpper) return std::max(0.0, w);
  return std::abs(w);
}
#endif

}  // namespace spook::detail
