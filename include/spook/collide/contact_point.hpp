#pragma once

#include <cstdint>

#include <spook/core/math.hpp>

namespace spook {

/// One point of contact between two shapes, in world coordinates. The
/// normal is a unit vector pointing from the first shape toward the second:
/// moving the second shape by `depth` along it separates them. The point
/// lies midway between the two surfaces, so point ∓ normal·depth/2 are the
/// deepest points of the first and the second shape. A negative depth is a
/// gap point of a speculative contact (Simulation::
/// setEnableSpeculativeContacts): the shapes are apart by −depth there and
/// may meet within the step; its force is not zero only if they do.
template <Scalar S>
struct ContactPointT {
  Vec3T<S> point = Vec3T<S>::Zero();   ///< world (m)
  Vec3T<S> normal = Vec3T<S>::UnitZ();  ///< world, unit, from the first shape toward the second
  S depth = S(0);                       ///< penetration along the normal (m); < 0: a gap
  bool enabled = true;                ///< false once contact reduction or a listener has dropped it
  Vec3T<S> force = Vec3T<S>::Zero();    ///< contact force on the second shape's body (N), after the solve
  S normalForce = S(0);               ///< its component along the normal (N); negative only under adhesion
  std::uint32_t faceIndex1 = 0;       ///< the triangle touched when the first shape is a Trimesh or HeightField
  std::uint32_t faceIndex2 = 0;       ///< the same for the second shape

  [[nodiscard]] bool getEnabled() const { return enabled; }
  [[nodiscard]] const Vec3T<S>& getPoint() const { return point; }
  [[nodiscard]] const Vec3T<S>& getNormal() const { return normal; }
  [[nodiscard]] S getDepth() const { return depth; }
  /// False for a gap point (depth < 0).
  [[nodiscard]] bool isTouching() const { return depth >= S(0); }
  [[nodiscard]] const Vec3T<S>& getForce() const { return force; }
  /// Normal and tangential (friction) magnitudes of getForce (N).
  [[nodiscard]] S getNormalForceMagnitude() const { return normalForce; }
  [[nodiscard]] S getTangentialForceMagnitude() const { return (force - normal * normalForce).norm(); }
  [[nodiscard]] std::uint32_t getFaceIndex1() const { return faceIndex1; }
  [[nodiscard]] std::uint32_t getFaceIndex2() const { return faceIndex2; }
};

}  // namespace spook
