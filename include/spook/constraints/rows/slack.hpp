#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include <spook/constraints/rows/elementary.hpp>
#include <spook/core/implementation.hpp>

namespace spook::detail {

// Rows of the slack joints (seed 001 §12, "constraints with slack"). Each
// constrained DOF of a slack joint is a coordinate x (m or rad) that is zero
// in the relaxed configuration, with a slack interval [lower, upper] inside
// which it moves freely. Its row type writes the bilateral row g = x (the
// rigid version of that DOF, which is what a zero interval gives);
// SlackInterval::restrict then makes it one-sided at the nearer end, like a
// Range1D that is always engaged.
//
// Translational DOFs are the separation along the axes of frame 2, which is
// exactly what Dot2<K> writes (g = (p₁ − p₂)·n_K). Rotational DOFs need
// angles in radians rather than the Dot1/QuatLock sines, so that a slack of
// 0.05 rad means 0.05 rad: TiltAngle and RotationAngle below. Inside its
// slack a DOF is off the rigid joint's manifold, so the angles carry their
// second-order term κ (SecondOrder::curvature) like the elementary rows.

/// A quantity's value, rate and κ = ½ of its second derivative at constant
/// body velocities (SecondOrder::curvature).
struct Rates {
  double value = 0.0, rate = 0.0, curvature = 0.0;
};

/// u·w of an axis u of frame 1 and an axis w of frame 2, turning with ω₁ and
/// ω₂ (as Dot1).
SPOOK_INLINE Rates axisDot(const Attachments& a, const Vec3d& u, const Vec3d& w);

/// atan2(s, c) of two such quantities: θ̇ = (c ṡ − s ċ)/r² and
/// ½θ̈ = (c κ_s − s κ_c)/r² − θ̇ (s ṡ + c ċ)/r², r² = s² + c².
SPOOK_INLINE Rates angleRates(const Rates& s, const Rates& c);

/// Tilt of frame 1's z axis about axis K (0: x, 1: y) of frame 2 (rad): the
/// angle of z₁ projected on the plane normal to that axis, measured from z₂.
/// Independent of the twist about z, so it suits joints whose rotation about
/// z is free (hinge, cylindrical). K = 0: atan2(−z₁·y₂, z₁·z₂);
/// K = 1: atan2(z₁·x₂, z₁·z₂). With s and c those two dot products,
/// ṡ = ±(ω₁ − ω₂)·(z₁ × m), ċ = (ω₁ − ω₂)·(z₁ × z₂), and
/// d(angle)/dt = (c ṡ − s ċ)/(s² + c²).
template <int K>
struct TiltAngle {
  static_assert(K == 0 || K == 1, "TiltAngle is about x (0) or y (1) of frame 2");
  static constexpr int kRows = 1;

  static Coordinate coordinate(const Attachments& a) {
    const Vec3d z1 = a.R1.col(2), z2 = a.R2.col(2);
    const Vec3d m = K == 0 ? Vec3d(a.R2.col(1)) : Vec3d(a.R2.col(0));
    const double sign = K == 0 ? -1.0 : 1.0;
    const double s = sign * z1.dot(m), c = z1.dot(z2);
    const double r2 = std::max(s * s + c * c, 1e-300);
    const Vec3d j = (c * sign * z1.cross(m) - s * z1.cross(z2)) / r2;
    Coordinate out;
    out.rotational = true;
    out.value = std::atan2(s, c);
    out.J1 = linearAngular(Vec3d::Zero(), j);
    out.J2 = linearAngular(Vec3d::Zero(), -j);
    out.speed = a.speed(out.J1, out.J2);
    out.curvature = a.h > 0.0 ? remainderCurvature(a, out.value, angle(turnedFrames(a)), out.speed)
                              : angleRates(axisDot(a, z1, sign * m), axisDot(a, z1, z2)).curvature;
    return out;
  }
  static double angle(const Attachments& a) {
    const Vec3d z1 = a.R1.col(2);
    return K == 0 ? std::atan2(-z1.dot(a.R2.col(1)), z1.dot(a.R2.col(2)))
                  : std::atan2(z1.dot(a.R2.col(0)), z1.dot(a.R2.col(2)));
  }
  static void addRows(const Attachments& a, RowSink& sink, const RowParameters* p, double* impulse,
                      const ElementaryOptions&) {
    const Coordinate c = coordinate(a);
    holonomicRow(sink, c.J1, c.J2, c.value, p[0], impulse);
    sink.setCurvature(c.curvature);
  }
};

/// Rotation of frame 1 about axis K of frame 2 (rad), 2·atan2(v_K, w) with
/// (w, v) = q₂* q₁ (w ≥ 0): exact for a rotation about that axis alone, and
/// the three together vanish only at the relaxed orientation. With
/// Ω = R₂ᵀ(ω₁ − ω₂), v̇ = ½(wΩ + Ω × v) and ẇ = −½ Ω·v, so
/// d(angle)/dt = Ω·(w² e_K + w v × e_K + v_K v)/(w² + v_K²). At constant
/// velocities Ω̇ = −R₂ᵀ(ω₂ × (ω₁ − ω₂)), v̈ = ½(wΩ̇ + Ω̇ × v) − ¼|Ω|² v and
/// ẅ = −½ Ω̇·v − ¼|Ω|² w.
template <int K>
struct RotationAngle {
  static_assert(K >= 0 && K <= 2, "RotationAngle is about x, y or z (0, 1, 2) of frame 2");
  static constexpr int kRows = 1;

  static Coordinate coordinate(const Attachments& a) {
    const Quatd q = relativeRotation(a);
    const Vec3d v = q.vec(), e = Vec3d::Unit(K);
    const double w = q.w(), vk = v[K];
    const double r2 = std::max(w * w + vk * vk, 1e-300);
    const Vec3d j = a.R2 * ((w * w * e + w * v.cross(e) + vk * v) / r2);
    Coordinate out;
    out.rotational = true;
    out.value = 2.0 * std::atan2(vk, w);
    out.J1 = linearAngular(Vec3d::Zero(), j);
    out.J2 = linearAngular(Vec3d::Zero(), -j);
    out.speed = a.speed(out.J1, out.J2);
    if (a.h > 0.0) {
      const Quatd turned = relativeRotation(turnedFrames(a));
      out.curvature = remainderCurvature(a, out.value, 2.0 * std::atan2(turned.vec()[K], turned.w()), out.speed);
      return out;
    }
    const Vec3d omega2 = a.v2.tail<3>(), relative = a.v1.tail<3>() - omega2;
    const Vec3d W = a.R2.transpose() * relative, dW = -a.R2.transpose() * omega2.cross(relative);
    const Vec3d dv = 0.5 * (w * W + W.cross(v)), ddv = 0.5 * (w * dW + dW.cross(v)) - 0.25 * W.squaredNorm() * v;
    const double dw = -0.5 * W.dot(v), ddw = -0.5 * dW.dot(v) - 0.25 * W.squaredNorm() * w;
    out.curvature = 2.0 * angleRates({vk, dv[K], 0.5 * ddv[K]}, {w, dw, 0.5 * ddw}).curvature;
    return out;
  }
  static void addRows(const Attachments& a, RowSink& sink, const RowParameters* p, double* impulse,
                      const ElementaryOptions&) {
    const Coordinate c = coordinate(a);
    holonomicRow(sink, c.J1, c.J2, c.value, p[0], impulse);
    sink.setCurvature(c.curvature);
  }
};

/// Whether a slack row is an angle (rad) or a separation (m): what
/// setSlackParameters(positional, rotational) applies to.
template <class Row>
inline constexpr bool kRotationalSlackRow = false;
template <int K>
inline constexpr bool kRotationalSlackRow<TiltAngle<K>> = true;
template <int K>
inline constexpr bool kRotationalSlackRow<RotationAngle<K>> = true;

/// The slack of one DOF: the coordinate moves freely in [lower, upper]
/// (m or rad).
struct SlackInterval {
  double lower = 0.0, upper = 0.0;

  /// Turns the bilateral row g = x of a slack row type into this step's
  /// row. A zero-width interval keeps it bilateral (g = x − lower). Otherwise
  /// it becomes a one-sided row at the nearer end, pushing inward only, with
  /// g = x − end: SPOOK's −a g on the right-hand side lets x approach that end
  /// freely and brakes it only in the last ~2 steps before it (at
  /// |ẋ| ≳ a·(distance), a = 4/(h(1+4τ/h))), as Range1D's look-ahead does,
  /// so the row carries no force while the DOF is inside its slack. It stays
  /// in the system throughout: a look-ahead on the DOF's own speed misses
  /// the kicks that other rows' impacts give it within one step (measured:
  /// 3–6 mm past a 1 cm slack in a swinging chain).
  void restrict(Row& row) const;

  /// For post-stabilization, which projects equalities: a zero-width
  /// interval keeps its row (g = x − lower), and so does an end the step's
  /// solve pressed the DOF against (its `impulse` non-zero): like a rigid
  /// row, it is projected onto the violation x − end the solve predicted,
  /// which removes the step's second-order drift past the end while the DOF
  /// is held there. A DOF moving inside its slack is left to the solve.
  bool restrictProjection(Row& row, const double* impulse) const;
};

#if defined(SPOOK_DEFINES_NON_TEMPLATES)
SPOOK_INLINE void SlackInterval::restrict(Row& row) const {
  const double x = row.violation;
  if (lower == upper) {
    row.violation = x - lower;
    return;
  }
  const bool lowerSide = x - lower <= upper - x;
  row.violation = x - (lowerSide ? lower : upper);
  if (lowerSide)
    row.lower = 0.0;  // may only push x up
  else
    row.upper = 0.0;  // may only push x down
}

SPOOK_INLINE bool SlackInterval::restrictProjection(Row& row, const double* impulse) const {
  if (lower == upper) {
    row.violation -= lower;
    return true;
  }
  if (!impulse || *impulse == 0.0) return false;
  const double x = row.violation;
  row.violation = x - (x - lower <= upper - x ? lower : upper);
  return true;
}
#endif

#if defined(SPOOK_DEFINES_NON_TEMPLATES)
SPOOK_INLINE Rates axisDot(const Attachments& a, const Vec3d& u, const Vec3d& w) {
  const Vec3d w1 = a.v1.tail<3>(), w2 = a.v2.tail<3>(), du = w1.cross(u), dw = w2.cross(w);
  return {u.dot(w), du.dot(w) + u.dot(dw), 0.5 * (w1.cross(du).dot(w) + u.dot(w2.cross(dw))) + du.dot(dw)};
}

SPOOK_INLINE Rates angleRates(const Rates& s, const Rates& c) {
  const double r2 = std::max(s.value * s.value + c.value * c.value, 1e-300);
  const double rate = (c.value * s.rate - s.value * c.rate) / r2;
  return {std::atan2(s.value, c.value), rate,
          (c.value * s.curvature - s.value * c.curvature) / r2 - rate * (s.value * s.rate + c.value * c.rate) / r2};
}
#endif
}  // namespace spook::detail
