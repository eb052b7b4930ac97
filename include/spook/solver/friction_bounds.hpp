#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include <spook/solver/island_problem.hpp>

namespace spook::detail {

/// |(a, b)|, where std::hypot's guard against overflow (not reachable by
/// impulses and slip speeds, far below 1e154) cost the hybrid solve of a
/// 210-cube pyramid a sixth of its time in the cone projections.
[[nodiscard]] inline double planarLength(double a, double b) { return std::sqrt(a * a + b * b); }

/// The friction limit μΛn (N·s) of friction row e from its normal's current impulse.
[[nodiscard]] inline double frictionLimit(const IslandProblem& problem, const IslandProblem::Entry& e) {
  return e.mu * std::max(0.0, problem.rows[static_cast<std::size_t>(e.normal)].impulse);
}

/// Sets the bounds of the friction rows among `subset` that follow their
/// normal: ±μΛn for a scaled box, ±μΛn·|d_i| for a cone row (the direct
/// solver's box around the cone, see updateConeDirections).
/// Returns the largest change of a bound (N·s).
inline double applyFrictionBounds(IslandProblem& problem, const std::vector<int>& subset) {
  double change = 0.0;
  for (int i : subset) {
    IslandProblem::Entry& e = problem.rows[static_cast<std::size_t>(i)];
    if (!e.followsNormal()) continue;
    const double limit = frictionLimit(problem, e) * (e.frictionBound == FrictionBound::CONE ? e.coneShare : 1.0);
    change = std::max(change, std::abs(limit - e.upper));
    e.lower = -limit;
    e.upper = limit;
  }
  return change;
}

/// Scales the friction impulses among `subset` that follow their normal
/// back within the limit their normal's impulse now sets (Coulomb's law): a
/// box row to ±μΛn, a cone pair along its force onto the disk of radius μΛn
/// (both rows of a pair must be in `subset`). For friction solved against
/// earlier normals: the hybrid's last direct pass moves the normals after
/// its Gauss–Seidel friction (on a settling pile of 64 spheres, friction
/// reached 4 times μΛn).
inline void clampFrictionToNormals(IslandProblem& problem, const std::vector<int>& subset) {
  for (int i : subset) {
    IslandProblem::Entry& e = problem.rows[static_cast<std::size_t>(i)];
    if (!e.followsNormal()) continue;
    const double limit = frictionLimit(problem, e);
    if (e.frictionBound != FrictionBound::CONE || e.partner < 0) {
      e.impulse = std::clamp(e.impulse, -limit, limit);
      continue;
    }
    if (e.partner < i) continue;
    IslandProblem::Entry& f = problem.rows[static_cast<std::size_t>(e.partner)];
    const double force = planarLength(e.impulse, f.impulse);
    if (!(force > limit)) continue;
    const double scale = limit / force;
    e.impulse *= scale;
    f.impulse *= scale;
  }
}

/// The point of the disk |x| ≤ radius closest to `target` in the metric of
/// the 2×2 symmetric positive definite block A (a00, a01, a11): the cone
/// step of Gauss–Seidel, where the pair of tangent impulses minimizes its
/// quadratic within the disk. Outside the disk the minimizer is
/// x(λ) = (A + λI)⁻¹A·target with |x(λ)| = radius, λ > 0: the trust-region
/// subproblem, solved by Newton's method on ψ(λ) = 1/|x(λ)| − 1/radius,
/// which is concave and increasing, so that the iterates rise monotonically
/// from λ = 0 to the root (Moré & Sorensen 1983, "Computing a trust region
/// step"), ψ'(λ) = xᵀ(A + λI)⁻¹x / |x|³. A handful of steps reach round-off
/// where a projected gradient needed dozens on an ill-conditioned block.
[[nodiscard]] inline std::array<double, 2> projectOntoDisk(std::array<double, 2> target, double radius, double a00,
                                                          double a01, double a11) {
  const double length = planarLength(target[0], target[1]);
  if (length <= radius) return target;
  if (!(radius > 0.0)) return {0.0, 0.0};
  const double b0 = a00 * target[0] + a01 * target[1], b1 = a01 * target[0] + a11 * target[1];
  std::array<double, 2> x = target;
  double norm = length;
  double lambda = 0.0;
  for (int k = 0; k < 32; ++k) {
    const double m00 = a00 + lambda, m11 = a11 + lambda;
    const double det = m00 * m11 - a01 * a01;
    if (!(det > 0.0)) break;
    x = {(m11 * b0 - a01 * b1) / det, (m00 * b1 - a01 * b0) / det};
    norm = planarLength(x[0], x[1]);
    if (!(norm > 0.0) || std::abs(norm - radius) <= 1e-13 * radius) break;
    const double y0 = (m11 * x[0] - a01 * x[1]) / det, y1 = (m00 * x[1] - a01 * x[0]) / det;
    const double slope = (x[0] * y0 + x[1] * y1) / (norm * norm * norm);
    if (!(slope > 0.0)) break;
    const double step = (1.0 / norm - 1.0 / radius) / slope;
    if (!std::isfinite(step)) break;
    lambda -= step;
  }
  // On the circle exactly (the iterates approach it from outside).
  if (!(norm > 0.0)) return {0.0, 0.0};
  const double f = radius / norm;
  return {x[0] * f, x[1] * f};
}

/// The cone in a direct (box-constrained) solve, as an outer iteration: each
/// tangent pair (t1, t2) gets the box |Λ_i| ≤ μΛn|d_i|, whose corner d·μΛn
/// lies on the cone. d is the direction of the friction force: opposite the
/// slip w = (S+Σ)Λ − q of the pair while it slides (Coulomb's law), or the
/// force itself when it sticks outside the disk. A sticking pair inside the
/// disk keeps its box. At the fixed point every sliding pair carries μΛn
/// against its slip and every sticking one lies in the disk: the cone's
/// solution. Returns the largest change of a bound (N·s).
inline double updateConeDirections(IslandProblem& problem, const std::vector<int>& subset) {
  const std::vector<Vec6d> dv = problem.velocityChange();
  const auto slip = [&](int i) {
    const IslandProblem::Entry& e = problem.rows[static_cast<std::size_t>(i)];
    return problem.rowVelocity(i, dv) + e.sigma * e.impulse - e.q;
  };
  std::vector<char> inSubset(problem.rows.size(), 0);
  for (int i : subset) inSubset[static_cast<std::size_t>(i)] = 1;
  double change = 0.0;
  for (int a : subset) {
    IslandProblem::Entry& ea = problem.rows[static_cast<std::size_t>(a)];
    if (ea.frictionBound != FrictionBound::CONE || ea.partner < a || !inSubset[static_cast<std::size_t>(ea.partner)])
      continue;
    IslandProblem::Entry& eb = problem.rows[static_cast<std::size_t>(ea.partner)];
    const double limit = frictionLimit(problem, ea);
    // Only a row held at its bound slips; inside, w is round-off.
    const auto held = [](const IslandProblem::Entry& e) {
      return e.upper <= e.lower || std::abs(e.impulse) >= e.upper * (1.0 - 1e-9);
    };
    const double wa = held(ea) ? slip(a) : 0.0, wb = held(eb) ? slip(ea.partner) : 0.0;
    const double slipSpeed = planarLength(wa, wb);
    const double force = planarLength(ea.impulse, eb.impulse);
    double da = ea.coneShare, db = eb.coneShare;
    if (slipSpeed > 0.0) {
      // The force turns against the slip: fully on the first update (from
      // the square around the disk), then halfway from the last direction:
      // the slips of points on one body answer each other's turns, and full
      // turns can oscillate.
      const double oa = std::copysign(ea.coneShare, ea.impulse), ob = std::copysign(eb.coneShare, eb.impulse);
      const double ta = -wa / slipSpeed, tb = -wb / slipSpeed;
      const bool full = ea.coneShare == 1.0 && eb.coneShare == 1.0;
      const double sa = full ? ta : oa + ta, sb = full ? tb : ob + tb;
      const double norm = planarLength(sa, sb);
      da = norm > 1e-12 ? std::abs(sa) / norm : std::abs(ta);
      db = norm > 1e-12 ? std::abs(sb) / norm : std::abs(tb);
    } else if (force > limit * (1.0 + 1e-9) && force > 0.0) {
      da = std::abs(ea.impulse) / force;
      db = std::abs(eb.impulse) / force;
    }
    change = std::max(change, limit * std::max(std::abs(da - ea.coneShare), std::abs(db - eb.coneShare)));
    ea.coneShare = da;
    eb.coneShare = db;
  }
  return change;
}

/// Freezes the cone rows among `subset` whose `keep` flag is set at the
/// friction their last (iterative) solve found: the box |Λ_i| ≤ μΛn|f_i|/|f|
/// holds f and has its corner on the cone (the inscribed square when f = 0).
inline void freezeConeShares(IslandProblem& problem, const std::vector<int>& subset, const std::vector<char>& keep) {
  for (int a : subset) {
    IslandProblem::Entry& ea = problem.rows[static_cast<std::size_t>(a)];
    if (!keep[static_cast<std::size_t>(a)] || ea.frictionBound != FrictionBound::CONE || ea.partner < a) continue;
    IslandProblem::Entry& eb = problem.rows[static_cast<std::size_t>(ea.partner)];
    const double force = planarLength(ea.impulse, eb.impulse);
    ea.coneShare = force > 0.0 ? std::abs(ea.impulse) / force : std::sqrt(0.5);
    eb.coneShare = force > 0.0 ? std::abs(eb.impulse) / force : std::sqrt(0.5);
  }
}

/// Complementarity error of a cone pair (m/s): its slip w must oppose its
/// force f when |f| = μΛn and vanish inside the disk.
[[nodiscard]] inline double coneComplementarityError(const IslandProblem::Entry& a, const IslandProblem::Entry& b,
                                                     double limit, double wa, double wb) {
  const double force = planarLength(a.impulse, b.impulse);
  // On the cone to within the friction iterations' reach (their last solve
  // moves Λn after the bounds were set).
  if (force < limit * (1.0 - 1e-4) || force == 0.0) return planarLength(wa, wb);
  const double fa = a.impulse / force, fb = b.impulse / force;
  const double along = wa * fa + wb * fb;  // must be <= 0
  return std::max(0.0, along) + std::abs(wa * fb - wb * fa);
}

}  // namespace spook::detail
