#pragma once

// How a wire runs over an edge of a polyhedral shape where it is routed over
// one (wire/wire_node.hpp's ContactNode on a box, a convex, a trimesh or a
// height field): it turns there as through an eye (a wrap of radius 0,
// sheave_wrap.hpp), at the point of the edge where its path from the point
// before to the point after is shortest, so that the point slides along the
// edge as they move.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>

#include <Eigen/Core>

#include <spook/collide/shapes/box.hpp>
#include <spook/collide/shapes/convex.hpp>
#include <spook/collide/shapes/height_field.hpp>
#include <spook/collide/shapes/trimesh.hpp>

namespace spook::detail {

/// An edge of a shape, in the shape's frame (m).
struct ShapeEdge {
  Eigen::Vector3d from = Eigen::Vector3d::Zero(), to = Eigen::Vector3d::Zero();
};

/// The edge of a box of half extents `half` (its frame) nearest `point`.
inline ShapeEdge nearestBoxEdge(const Eigen::Vector3d& half, const Eigen::Vector3d& point) {
  ShapeEdge best;
  double closest = std::numeric_limits<double>::infinity();
  for (int axis = 0; axis < 3; ++axis) {
    const int i = (axis + 1) % 3, j = (axis + 2) % 3;
    for (const double si : {-1.0, 1.0})
      for (const double sj : {-1.0, 1.0}) {
        ShapeEdge edge;
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

/// Keeps the edge a → b where it is nearer `point` than `best` so far.
class NearestEdge {
 public:
  explicit NearestEdge(const Eigen::Vector3d& point) : point_(point) {}

  void consider(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    const Eigen::Vector3d edge = b - a;
    const double squared = edge.squaredNorm();
    if (!(squared > 0.0)) return;
    const double t = std::clamp((point_ - a).dot(edge) / squared, 0.0, 1.0);
    const double distance = (a + t * edge - point_).norm();
    if (distance < closest_) {
      closest_ = distance;
      best_ = ShapeEdge{a, b};
    }
  }

  [[nodiscard]] std::optional<ShapeEdge> best() const { return best_; }

 private:
  Eigen::Vector3d point_;
  double closest_ = std::numeric_limits<double>::infinity();
  std::optional<ShapeEdge> best_;
};

/// The edges of triangle `index` that fold away seen from its front (the
/// outside of a mesh, above a height field: bits 0-2 of getActiveEdges):
/// the ridges a wire can run over, not a flat surface's diagonals.
template <class Surface>
void considerRidges(const Surface& surface, std::size_t index, NearestEdge& nearest) {
  const auto corners = surface.getTriangle(index);
  const std::uint8_t active = surface.getActiveEdges(index);
  for (std::size_t k = 0; k < 3; ++k)
    if (active & (1u << k))
      nearest.consider(corners[k].template cast<double>(), corners[(k + 1) % 3].template cast<double>());
}

/// The edge a wire routed at `point` (shape frame) runs over: of a box, a
/// convex (its hull's edges between faces), a trimesh or a height field
/// (their ridges, considerRidges; of a height field, those of the cells
/// around the point's), the one nearest the point; none for other shapes.
template <Scalar S>
std::optional<ShapeEdge> nearestShapeEdge(const ShapeT<S>& shape, const Eigen::Vector3d& point) {
  NearestEdge nearest(point);
  switch (shape.getType()) {
    case ShapeType::BOX:
      return nearestBoxEdge(static_cast<const BoxT<S>&>(shape).getHalfExtents().template cast<double>(), point);
    case ShapeType::CONVEX: {
      const auto& convex = static_cast<const ConvexT<S>&>(shape);
      for (const auto& edge : convex.getEdges())
        nearest.consider(convex.getVertices()[static_cast<std::size_t>(edge.from)].template cast<double>(),
                         convex.getVertices()[static_cast<std::size_t>(edge.to)].template cast<double>());
      break;
    }
    case ShapeType::TRIMESH: {
      const auto& mesh = static_cast<const TrimeshT<S>&>(shape);
      for (std::size_t i = 0; i < mesh.getNumTriangles(); ++i) considerRidges(mesh, i, nearest);
      break;
    }
    case ShapeType::HEIGHTFIELD: {
      const auto& field = static_cast<const HeightFieldT<S>&>(shape);
      const std::size_t cellsX = field.getResolutionX() - 1, cellsY = field.getResolutionY() - 1;
      const auto cell = [](double coordinate, double size, double spacing, std::size_t cells) {
        const double c = std::floor((coordinate + 0.5 * size) / spacing);
        return static_cast<long>(std::clamp(std::isfinite(c) ? c : 0.0, 0.0, double(cells - 1)));
      };
      const long ci = cell(point.x(), double(field.getSizeX()), double(field.getSpacing().x()), cellsX);
      const long cj = cell(point.y(), double(field.getSizeY()), double(field.getSpacing().y()), cellsY);
      for (long j = std::max(cj - 1, 0L); j <= std::min(cj + 1, long(cellsY) - 1); ++j)
        for (long i = std::max(ci - 1, 0L); i <= std::min(ci + 1, long(cellsX) - 1); ++i)
          for (std::size_t k = 0; k < 2; ++k)
            considerRidges(field, 2 * (std::size_t(i) + cellsX * std::size_t(j)) + k, nearest);
      break;
    }
    default:
      break;
  }
  return nearest.best();
}

}  // namespace spook::detail
