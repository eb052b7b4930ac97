#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include <spook/collide/contact_point.hpp>
#include <spook/collide/geometry.hpp>
#include <spook/core/ref_ptr.hpp>

namespace spook {

/// The contact points between two geometries found in one collision pass.
/// Normals point from geometry(0) toward geometry(1).
template <Scalar S>
class GeometryContactT {
 public:
  using Geometry = GeometryT<S>;

  GeometryContactT(ref_ptr<Geometry> first, ref_ptr<Geometry> second)
      : geometries_{std::move(first), std::move(second)} {}

  /// The first (0) or second (1) geometry.
  [[nodiscard]] Geometry* geometry(std::size_t i) const { return geometries_[i & 1].get(); }
  /// The body of the first (0) or second (1) geometry; nullptr for a static one.
  [[nodiscard]] RigidBodyT<S>* rigidBody(std::size_t i) const { return geometries_[i & 1]->getRigidBody(); }
  [[nodiscard]] std::vector<ContactPointT<S>>& points() { return points_; }
  [[nodiscard]] const std::vector<ContactPointT<S>>& points() const { return points_; }
  /// Number of points still enabled after contact reduction.
  [[nodiscard]] std::size_t getNumEnabledPoints() const {
    std::size_t n = 0;
    for (const auto& p : points_) n += p.enabled ? 1 : 0;
    return n;
  }
  /// False once a contact listener returned REMOVE_CONTACT: the solver does
  /// not see it; the listeners called after that one see it disabled.
  [[nodiscard]] bool isEnabled() const { return enabled_; }
  void setEnable(bool enable) { enabled_ = enable; }
  /// True when the two geometries did not touch in the previous pass.
  [[nodiscard]] bool isImpact() const { return impact_; }
  void setImpact(bool impact) { impact_ = impact; }
  /// True when either geometry is a sensor: reported, never solved.
  [[nodiscard]] bool isSensor() const { return geometries_[0]->isSensor() || geometries_[1]->isSensor(); }

 private:
  ref_ptr<Geometry> geometries_[2];
  std::vector<ContactPointT<S>> points_;
  bool enabled_ = true;
  bool impact_ = true;
};

/// Two geometries that touched in the previous pass and no longer do; either
/// may have been deleted since (the observers are then null).
template <Scalar S>
struct GeometryPairT {
  observer_ptr<GeometryT<S>> first;
  observer_ptr<GeometryT<S>> second;
};

using GeometryContact = GeometryContactT<double>;
using GeometryPair = GeometryPairT<double>;
namespace f32 {
using GeometryContact = GeometryContactT<float>;
using GeometryPair = GeometryPairT<float>;
}  // namespace f32

}  // namespace spook
