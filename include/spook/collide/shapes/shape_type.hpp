#pragma once

#include <array>
#include <cstddef>
#include <string_view>

namespace spook {

/// The kinds of shape, in the order of the collider-matrix table in the
/// seeds. A pair (A, B) of colliding shapes is handled by the collider of
/// the ordered pair with index(A) <= index(B).
enum class ShapeType : unsigned char { BOX, CAPSULE, CONVEX, CYLINDER, LINE, PLANE, SPHERE, TRIMESH, COMPOSITE, HEIGHTFIELD };

inline constexpr std::size_t kNumShapeTypes = 10;

inline constexpr std::array<std::string_view, kNumShapeTypes> kShapeTypeNames = {
    "Box", "Capsule", "Convex", "Cylinder", "Line", "Plane", "Sphere", "Trimesh", "Composite", "HeightField"};

[[nodiscard]] constexpr std::string_view shapeTypeName(ShapeType type) {
  return kShapeTypeNames[static_cast<std::size_t>(type)];
}

}  // namespace spook
