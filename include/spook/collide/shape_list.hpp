#pragma once

#include <cstddef>

#include <spook/collide/shapes/shape_type.hpp>
#include <spook/core/scalar.hpp>

namespace spook {

/// The shape types a simulation or a space may contain, as class templates
/// on the scalar: `ShapeList<SphereT, PlaneT>`. Only the colliders between
/// these types are compiled (see ColliderMatrixT); `AllShapes`
/// (spook/collide/all_shapes.hpp) lists every shape.
template <template <class> class... Shapes>
struct ShapeList {
  static constexpr std::size_t size = sizeof...(Shapes);

  /// True when the list holds the shape type `kind`.
  [[nodiscard]] static constexpr bool contains(ShapeType kind) {
    return ((Shapes<double>::kType == kind) || ...);
  }
};

}  // namespace spook
