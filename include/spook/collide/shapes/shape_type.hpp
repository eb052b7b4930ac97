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

/// Which shape of a pair the default narrow phase asks for the contacts: the
/// one of the higher rank, which compiles the colliders with the types
/// ranked at or below its own (ShapeT::collideWithLowerRank). Cheap, common
/// shapes rank low, so that a program of boxes on a plane compiles the
/// colliders of planes, spheres and boxes only; a composite ranks highest
/// and hands its children back to the dispatch.
[[nodiscard]] constexpr int dispatchRank(ShapeType type) {
  // From the lowest: plane, sphere, box, capsule, cylinder, line, convex,
  // trimesh, height field, composite (the table is in ShapeType's order).
  constexpr std::array<int, kNumShapeTypes> kRanks = {2, 3, 6, 4, 5, 0, 1, 7, 9, 8};
  return kRanks[static_cast<std::size_t>(type)];
}

}  // namespace spook
