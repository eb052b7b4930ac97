#pragma once

// How a wire wraps a cylinder (a sheave) where it is routed over one
// (wire/wire_node.hpp's ContactNode): in the plane across the cylinder's
// axis through its center (the groove), the wire arrives along the tangent
// from the point before, follows the circle through the wrap angle θ in one
// sense and leaves along the tangent to the point after. Angles are in the
// geometry's frame (about its y axis, from its x axis), so that a point at a
// fixed angle turns with the geometry's body. An eye (wire_node.hpp's
// EyeNode) is a wrap of radius 0.

#include <cmath>
#include <numbers>

#include <Eigen/Core>

namespace spook::detail {

struct SheaveWrap {
  using Vec3d = Eigen::Vector3d;

  double radius = 0.0;
  /// +1: the wire turns counterclockwise about the axis, −1 clockwise.
  int sense = 1;
  /// θ (rad), tracked continuously from step to step (more than 2π when the
  /// wire turns around the cylinder).
  double wrap = 0.0;
  /// The angle of the wire's material point C that splits the wrap between
  /// the segments before and after (rad): the bisector of the wrap when
  /// anchored, then fixed to the geometry.
  double anchor = 0.0;
  /// Tangent angles where the wire arrives and leaves (rad).
  double in = 0.0, out = 0.0;
  /// The plane now (world): center, axis and the frame's x and −z axes
  /// (e1 × e2 = axis).
  Vec3d center = Vec3d::Zero(), axis = Vec3d::UnitY(), e1 = Vec3d::UnitX(), e2 = -Vec3d::UnitZ();

  [[nodiscard]] Vec3d point(double angle) const {
    return center + radius * (std::cos(angle) * e1 + std::sin(angle) * e2);
  }
  [[nodiscard]] double angleOf(const Vec3d& p) const {
    const Vec3d a = p - center;
    return std::atan2(a.dot(e2), a.dot(e1));
  }
  /// The tangent angle from p: where a wire from p arrives (`arriving`) or
  /// towards p leaves, turning in `turn` (±1). From inside the circle (in
  /// projection), the angle of p itself.
  [[nodiscard]] double tangentAngle(const Vec3d& p, int turn, bool arriving) const {
    const Vec3d a = p - center;
    const double x = a.dot(e1), y = a.dot(e2), d = std::hypot(x, y);
    const double beta = d > radius ? std::acos(radius / d) : 0.0;
    return std::atan2(y, x) + (arriving ? turn : -turn) * beta;
  }
  /// θ in [0, 2π) from `in` to `out` in sense `turn`.
  static double forward(double from, double to, int turn) {
    const double a = std::fmod(turn * (to - from), 2.0 * std::numbers::pi);
    return a < 0.0 ? a + 2.0 * std::numbers::pi : a;
  }

  /// Picks the sense and wrap at routing: the wire arrives from `from`,
  /// passes the routed point `through` and leaves towards `to`; of the two
  /// senses, the one with the shorter wrap, plus `turns` whole turns.
  /// Anchors C at the bisector.
  void route(const Vec3d& from, const Vec3d& through, const Vec3d& to, int turns = 0) {
    const double at = angleOf(through);
    // A routed point on the tangent itself is reached without turning (not
    // after a turn less round-off).
    const auto reach = [](double from, double to, int turn) {
      const double a = forward(from, to, turn);
      return 2.0 * std::numbers::pi - a < 1e-9 ? 0.0 : a;
    };
    double best = 1e30;
    for (const int turn : {1, -1}) {
      const double a = tangentAngle(from, turn, true), b = tangentAngle(to, turn, false);
      const double theta = reach(a, at, turn) + reach(at, b, turn);
      if (theta < best) {
        best = theta;
        sense = turn;
        in = a;
        out = b;
      }
    }
    wrap = best + 2.0 * std::numbers::pi * turns;
    anchor = in + sense * wrap / 2.0;
  }
  /// New tangents for the points before and after; the wrap changes
  /// continuously (by less than π a step).
  void place(const Vec3d& from, const Vec3d& to) {
    in = tangentAngle(from, sense, true);
    out = tangentAngle(to, sense, false);
    wrap += std::remainder(forward(in, out, sense) - wrap, 2.0 * std::numbers::pi);
  }
  /// The wire's end at `end`, beside this wrap (`arriving`: before it), that
  /// has passed the tangent point it had in `was` (beyond it along the wire)
  /// stays there: that tangent keeps its angle and the wrap changes by the
  /// other one only. A wire's end that reaches a sheave stops at it, as at
  /// an edge, instead of being dragged around it.
  void holdEnd(const SheaveWrap& was, const Vec3d& end, bool arriving) {
    const double angle = arriving ? was.in : was.out;
    const Vec3d along = sense * (std::cos(angle) * e2 - std::sin(angle) * e1);  // the wire's direction there
    const double beyond = (end - point(angle)).dot(along);
    if (!(arriving ? beyond > 0.0 : beyond < 0.0)) return;
    if (arriving) {
      wrap += sense * std::remainder(in - angle, 2.0 * std::numbers::pi);
      in = angle;
    } else {
      wrap -= sense * std::remainder(out - angle, 2.0 * std::numbers::pi);
      out = angle;
    }
  }
  /// An eye at `at` (a sheave of radius 0): the wire turns there by the
  /// angle between its directions from `from` and towards `to` (kept when
  /// either is not defined).
  void eye(const Vec3d& at, const Vec3d& from, const Vec3d& to) {
    radius = 0.0;
    center = at;
    in = out = anchor = 0.0;
    const Vec3d a = at - from, b = to - at;
    const double turn = std::atan2(a.cross(b).norm(), a.dot(b));
    if (a.squaredNorm() > 0.0 && b.squaredNorm() > 0.0 && std::isfinite(turn)) wrap = turn;
  }
  /// C's offset from the bisector along the wire (rad, in the sense of the wrap).
  [[nodiscard]] double offset() const {
    return sense * std::remainder(anchor - (in + sense * wrap / 2.0), 2.0 * std::numbers::pi);
  }
  /// Arc lengths (m) from where the wire arrives to C and from C to where it leaves.
  [[nodiscard]] double arcIn() const { return radius * (wrap / 2.0 + offset()); }
  [[nodiscard]] double arcOut() const { return radius * (wrap / 2.0 - offset()); }
  /// Moves C to the bisector; returns how much the arc before it shrank (m).
  double reanchor() {
    const double moved = radius * offset();
    anchor = in + sense * wrap / 2.0;
    return moved;
  }
};

}  // namespace spook::detail
