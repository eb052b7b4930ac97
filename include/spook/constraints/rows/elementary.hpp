#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

#include <spook/constraints/attachments.hpp>
#include <spook/core/implementation.hpp>
#include <spook/core/second_order.hpp>

namespace spook::detail {

/// Compliance and damping of one row, in double.
struct RowParameters {
  double compliance = 1e-8;
  double damping = 2.0 / 60.0;
};

/// Options shared by the elementary constraints of one joint.
struct ElementaryOptions {
  bool linearize = false;  ///< QuatLock compliance per radian (seed 001 §12.1.3)
};

// Elementary constraints (seed 001 §12.1). Each writes kRows holonomic rows
// g(q) = 0 with Jacobians G = ∂ġ/∂(v₁, ω₁, v₂, ω₂), centers of mass as the
// reference points, frame 2 (body 2 or the world) as the reference frame.

SPOOK_INLINE Row& holonomicRow(RowSink& sink, const Vec6d& J1, const Vec6d& J2, double g, const RowParameters& p,
                         double* impulse);

/// turnShare (core/second_order.hpp) of a body turning at ω.
SPOOK_INLINE double turnShare(const Vec3d& w, double h);

/// The frames of `a` a step of a.h later at constant velocities, each turned
/// by its ω h (origins unchanged: for angles).
SPOOK_INLINE Attachments turnedFrames(const Attachments& a);
/// A vector x turned by ω h (Rodrigues).
SPOOK_INLINE Vec3d turned(const Vec3d& x, const Vec3d& w, double h);

/// κ of an angle or an axes' dot product of `a` (SecondOrder::curvature)
/// from its value `after` a step of a.h at constant velocities:
/// h²κ = Δg − h ġ with Δg = after − before wrapped to (−π, π], the exact
/// remainder of the step's first-order prediction, scaled by turnShare of
/// the frames' relative turn |ω₁ − ω₂|h (the step's impulses change the
/// velocities it is predicted from, the more the farther the frames turn)
/// and kept within ½ a step. The Taylor term ½g̈ grows as the square of the
/// turn: slack joints of a pair spinning at 50 rad/s gained 1e44 to 1e283
/// times their energy at h = 1/30 and 0.1 s; with the exact remainder alone
/// up to 6e3 (1/30) and 4e14 (0.1); with both bounds at most 1.3 and 4e3.
/// The slack hinge on a body spinning at 23 rad/s, h = 1/30, reached
/// 1e54 m/s.
SPOOK_INLINE double remainderCurvature(const Attachments& a, double before, double after, double rate);

/// Centripetal part of the separation's second derivative,
/// ω₁×(ω₁×r₁) − ω₂×(ω₂×r₂), and its rate ḋ = v₁ + ω₁×r₁ − v₂ − ω₂×r₂.
SPOOK_INLINE Vec3d separationCentripetal(const Attachments& a);
SPOOK_INLINE Vec3d separationRate(const Attachments& a);

/// κ = ½ vᵀ∇²g v (SecondOrder::curvature) of g = (p₁ − p₂)·n with the frame-2 axis
/// n turning with ω₂: ½(d̈·n + d·n̈) + ḋ·ṅ, d̈ and n̈ their centripetal parts.
SPOOK_INLINE double separationCurvature(const Attachments& a, const Vec3d& n);

/// Frame origins coincide: g = p₁ − p₂ (3 rows, world axes).
struct Spherical {
  static constexpr int kRows = 3;
  static void addRows(const Attachments& a, RowSink& sink, const RowParameters* p, double* impulse,
                      const ElementaryOptions&);
};

#if defined(SPOOK_DEFINES_NON_TEMPLATES)
SPOOK_INLINE void Spherical::addRows(const Attachments& a, RowSink& sink, const RowParameters* p, double* impulse, const ElementaryOptions&) {
  const Vec3d d = a.p1 - a.p2, r1 = a.r1(), r2 = a.r2();
  const Vec3d curvature = sink.secondOrder ? Vec3d(0.5 * separationCentripetal(a)) : Vec3d::Zero();
  for (int k = 0; k < 3; ++k) {
    const Vec3d e = Vec3d::Unit(k);
    holonomicRow(sink, linearAngular(e, r1.cross(e)), linearAngular(-e, -r2.cross(e)), d[k], p[k], impulse + k);
    sink.setArms(r1, r2);
    sink.setCurvature(curvature[k]);
  }
}
#endif

/// Axis A1 of frame 1 stays perpendicular to axis A2 of frame 2: g = a·b,
/// ġ = (ω₁ − ω₂)·(a × b).
template <int A1, int A2>
struct Dot1 {
  static constexpr int kRows = 1;
  static void addRows(const Attachments& a, RowSink& sink, const RowParameters* p, double* impulse,
                      const ElementaryOptions&) {
    const Vec3d u = a.R1.col(A1), w = a.R2.col(A2), n = u.cross(w);
    holonomicRow(sink, linearAngular(Vec3d::Zero(), n), linearAngular(Vec3d::Zero(), -n), u.dot(w), p[0], impulse);
    if (!sink.secondOrder) return;
    const Vec3d w1 = a.v1.tail<3>(), w2 = a.v2.tail<3>();
    if (a.h > 0.0) {
      // From the axes a step later (remainderCurvature): with the Taylor
      // terms, each scaled by its body's turnShare, a hinged pair whose
      // bodies turned 1.6 rad a step relative to each other gained 2.5
      // times its energy at h = 1/30 (0.78 now).
      const double later = turned(u, w1, a.h).dot(turned(w, w2, a.h));
      sink.setCurvature(remainderCurvature(a, u.dot(w), later, n.dot(w1 - w2)));
      return;
    }
    // κ = ½(ü·w + u·ẅ) + u̇·ẇ with u̇ = ω₁×u, ü = ω₁×u̇ (SecondOrder::curvature).
    const Vec3d du = w1.cross(u), dw = w2.cross(w);
    sink.setCurvature(0.5 * (w1.cross(du).dot(w) + u.dot(w2.cross(dw))) + du.dot(dw));
  }
};

/// The separation d = p₁ − p₂ stays perpendicular to axis A of frame 2:
/// g = d·n, ġ = (v₁ + ω₁×r₁ − v₂ − ω₂×(p₁ − c₂))·n.
template <int A>
struct Dot2 {
  static constexpr int kRows = 1;
  static void addRows(const Attachments& a, RowSink& sink, const RowParameters* p, double* impulse,
                      const ElementaryOptions&) {
    const Vec3d n = a.R2.col(A);
    holonomicRow(sink, linearAngular(n, a.r1().cross(n)), linearAngular(-n, n.cross(a.p1 - a.c2)),
                 (a.p1 - a.p2).dot(n), p[0], impulse);
    sink.setArms(a.r1(), a.p1 - a.c2);
    if (sink.secondOrder) sink.setCurvature(separationCurvature(a, n));
  }
};

/// All relative rotation locked: g = 2·vec(q₂* q₁) in frame 2, with
/// ġ = (w I − [v]ₓ) R₂ᵀ (ω₁ − ω₂). For a rotation θ about n the rows hold
/// the torque sin θ/ε instead of θ/ε; linearization scales ε by sin θ/θ
/// (θ at the start of the step) so that the deflection obeys Hooke's law in
/// radians (seed 001 §12.1.3).
struct QuatLock {
  static constexpr int kRows = 3;
  static void addRows(const Attachments& a, RowSink& sink, const RowParameters* p, double* impulse,
                      const ElementaryOptions& options);
};

#if defined(SPOOK_DEFINES_NON_TEMPLATES)
SPOOK_INLINE void QuatLock::addRows(const Attachments& a, RowSink& sink, const RowParameters* p, double* impulse, const ElementaryOptions& options) {
  const Quatd q = relativeRotation(a);
  const Vec3d v = q.vec();
  Mat3d B = q.w() * Mat3d::Identity();
  B(0, 1) = v.z();
  B(0, 2) = -v.y();
  B(1, 0) = -v.z();
  B(1, 2) = v.x();
  B(2, 0) = v.y();
  B(2, 1) = -v.x();
  const Mat3d A = B * a.R2.transpose();
  double scale = 1.0;
  if (options.linearize) {
    const double theta = 2.0 * std::atan2(v.norm(), q.w());
    if (theta > 1e-6) scale = std::sin(theta) / theta;
  }
  for (int k = 0; k < 3; ++k) {
    const Vec3d n = A.row(k).transpose();
    RowParameters pk = p[k];
    pk.compliance *= scale;
    holonomicRow(sink, linearAngular(Vec3d::Zero(), n), linearAngular(Vec3d::Zero(), -n), 2.0 * v[k], pk,
                 impulse + k);
  }
}
#endif

// Coordinates of the free motion.

/// Angle of frame 1 about axis z of frame 2 (rad, −π..π before winding): the
/// twist of the relative rotation about z.
SPOOK_INLINE Coordinate rotationalCoordinate(const Attachments& a);

/// Position of frame 1 along axis z of frame 2 (m).
SPOOK_INLINE Coordinate translationalCoordinate(const Attachments& a);

/// Distance between the frame origins (m); along z of frame 2 when they meet.
SPOOK_INLINE Coordinate distanceCoordinate(const Attachments& a);


#if defined(SPOOK_DEFINES_NON_TEMPLATES)
SPOOK_INLINE Row& holonomicRow(RowSink& sink, const Vec6d& J1, const Vec6d& J2, double g, const RowParameters& p, double* impulse) {
  Row& row = sink.add(J1, J2, impulse);
  row.violation = g;
  row.compliance = p.compliance;
  row.damping = p.damping;
  return row;
}

SPOOK_INLINE double turnShare(const Vec3d& w, double h) { return turnShare(w.norm(), h); }

SPOOK_INLINE Attachments turnedFrames(const Attachments& a) {
  Attachments after = a;
  const auto turn = [h = a.h](Quatd& q, Mat3d& R, const Vec3d& w) {
    const double angle = w.norm() * h;
    if (!(angle > 0.0)) return;
    q = (Quatd(Eigen::AngleAxisd(angle, w / w.norm())) * q).normalized();
    R = q.toRotationMatrix();
  };
  turn(after.q1, after.R1, a.v1.tail<3>());
  turn(after.q2, after.R2, a.v2.tail<3>());
  return after;
}

SPOOK_INLINE Vec3d turned(const Vec3d& x, const Vec3d& w, double h) {
  const double speed = w.norm(), angle = speed * h;
  if (!(angle > 0.0)) return x;
  const Vec3d k = w / speed;
  const double c = std::cos(angle);
  return c * x + std::sin(angle) * k.cross(x) + (1.0 - c) * k.dot(x) * k;
}

SPOOK_INLINE double remainderCurvature(const Attachments& a, double before, double after, double rate) {
  const double change = std::remainder(after - before, 2.0 * std::numbers::pi);
  const double remainder = turnShare((a.v1.tail<3>() - a.v2.tail<3>()).norm(), a.h) * (change - a.h * rate);
  return std::clamp(remainder, -0.5, 0.5) / (a.h * a.h);
}

SPOOK_INLINE Vec3d separationCentripetal(const Attachments& a) {
  const Vec3d w1 = a.v1.tail<3>(), w2 = a.v2.tail<3>();
  return turnShare(w1, a.h) * w1.cross(w1.cross(a.r1())) - turnShare(w2, a.h) * w2.cross(w2.cross(a.r2()));
}

SPOOK_INLINE Vec3d separationRate(const Attachments& a) {
  return a.v1.head<3>() + a.v1.tail<3>().cross(a.r1()) - a.v2.head<3>() - a.v2.tail<3>().cross(a.r2());
}

SPOOK_INLINE double separationCurvature(const Attachments& a, const Vec3d& n) {
  // The axis' own second-order term and the product of first-order terms
  // bounded alike for frame 2's turn in the step (turnShare).
  const Vec3d w2 = a.v2.tail<3>(), dn = w2.cross(n);
  const double share2 = turnShare(w2, a.h);
  return 0.5 * (separationCentripetal(a).dot(n) + share2 * (a.p1 - a.p2).dot(w2.cross(dn))) +
         std::sqrt(share2) * separationRate(a).dot(dn);
}

SPOOK_INLINE Coordinate rotationalCoordinate(const Attachments& a) {
  const Quatd q = relativeRotation(a);
  return angleAbout(a, 2.0 * std::atan2(q.z(), q.w()), a.R2.col(2));
}

SPOOK_INLINE Coordinate translationalCoordinate(const Attachments& a) {
  const Vec3d n = a.R2.col(2);
  Coordinate c;
  c.value = (a.p1 - a.p2).dot(n);
  c.J1 = linearAngular(n, a.r1().cross(n));
  c.J2 = linearAngular(-n, n.cross(a.p1 - a.c2));
  c.speed = a.speed(c.J1, c.J2);
  c.curvature = separationCurvature(a, n);
  return c;
}

SPOOK_INLINE Coordinate distanceCoordinate(const Attachments& a) {
  const Vec3d d = a.p1 - a.p2;
  const double length = d.norm();
  const Vec3d n = length > 1e-12 ? Vec3d(d / length) : Vec3d(a.R2.col(2));
  Coordinate c;
  c.value = length;
  c.J1 = linearAngular(n, a.r1().cross(n));
  c.J2 = linearAngular(-n, -a.r2().cross(n));
  c.speed = a.speed(c.J1, c.J2);
  if (length > 1e-12) {
    // κ = ½ L̈ with L̈ = n·d̈ + |ḋ⊥|²/L, d̈ its centripetal part, the turning
    // term as the exact lengthening over the step and h²κ within half the
    // length (core/second_order.hpp): a 390 kg body spinning at 22 rad/s on
    // a short distance joint reached 5e6 m/s in its first step.
    const Vec3d rate = separationRate(a);
    const double across = std::sqrt(std::max(rate.squaredNorm() - std::pow(n.dot(rate), 2), 0.0));
    c.curvature =
        halfLengthBound(0.5 * n.dot(separationCentripetal(a)) + partingCurvature(across, length, a.h), length, a.h);
  }
  return c;
}
#endif
}  // namespace spook::detail
