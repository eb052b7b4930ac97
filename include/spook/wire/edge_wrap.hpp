#pragma once

// How a wire runs over an edge of a box where it is routed over one
// (wire/wire_node.hpp's ContactNode on a box): it turns there as through an
// eye (a wrap of radius 0, sheave_wrap.hpp), at the point of the edge where
// its path from the point before to the point after is shortest, so that the
// point slides along the edge as they move.

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Core>

namespace spook::detail {

struct BoxEdge {
  Eigen::Vector3d from = Eigen::Vector3d::Zero(), to = Eigen::Vector3d::Zero();
};

/// The edge of a box of half extents `half` (its frame) nearest `point`.
inline BoxEdge nearestBoxEdge(const Eigen::Vector3d& half, const Eigen::Vector3d& point) {
  BoxEdge best;
  double closest = std::numeric_limits<double>::infinity();
  for (int axis = 0; axis < 3; ++axis) {
    const int i = (axis + 1) % 3, j = (axis + 2) % 3;
    for (const double si : {-1.0, 1.0})
      for (const double sj : {-1.0, 1.0}) {
        BoxEdge edge;
        edge.from[axis] = -half[axis];
        edge.to[axis] = half[axis];
        edge.from[i] = edge.to[i] = si * half[i];
        edge.from[j] = edge.to[j] = sj * half[j];
        const double along = std::clamp(point[axis], -half[axis], half[axis]);
        const double distance = std::hypot(point[axis] - along, point[i] - edge.from[i], point[j] - edge.from[j]);
        if (distance < closest) {
          closest = distance;
          best = edge;
        }
      }
  }
  return best;
}

/// The point of the edge a → b (world) where the path from `from` over it to
/// `to` is shortest: unrolled about the edge's line, the path is straight,
/// at s = (t₁ r₂ + t₂ r₁)/(r₁ + r₂) along it (t the points' positions along
/// the line, r their distances from it); within the edge.
inline Eigen::Vector3d shortestOverEdge(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                        const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
  const Eigen::Vector3d edge = b - a;
  const double length = edge.norm();
  if (!(length > 0.0)) return a;
  const Eigen::Vector3d u = edge / length;
  const double t1 = (from - a).dot(u), t2 = (to - a).dot(u);
  const double r1 = (from - a - t1 * u).norm(), r2 = (to - a - t2 * u).norm();
  const double s = r1 + r2 > 0.0 ? (t1 * r2 + t2 * r1) / (r1 + r2) : 0.5 * (t1 + t2);
  return a + std::clamp(std::isfinite(s) ? s : 0.5 * length, 0.0, length) * u;
}

}  // namespace spook::detail
