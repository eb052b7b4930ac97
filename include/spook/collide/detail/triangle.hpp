#pragma once

#include <array>
#include <cmath>

#include <spook/collide/bounding_box.hpp>
#include <spook/collide/detail/aabb_tree.hpp>
#include <spook/collide/supporting_feature.hpp>
#include <spook/core/math.hpp>

namespace spook::detail {

/// One triangle of a mesh or height field, as a convex shape for the
/// colliders: vertices in the mesh frame, counter-clockwise seen from the
/// outside (the solid side is behind the face).
template <Scalar S>
struct Triangle {
  using Vec3 = spook::Vec3T<S>;
  std::array<Vec3, 3> v;

  [[nodiscard]] Vec3 support(const Vec3& d) const {
    const S a = v[0].dot(d), b = v[1].dot(d), c = v[2].dot(d);
    return a >= b ? (a >= c ? v[0] : v[2]) : (b >= c ? v[1] : v[2]);
  }
  /// The whole triangle when its plane is across `d` within the feature
  /// angle (from either side), else the edge across `d`, else the corner.
  void supportingFeature(const Vec3& d, SupportingFeatureT<S>& out) const {
    out.count = 0;
    const S length = d.norm();
    const Vec3 area = (v[1] - v[0]).cross(v[2] - v[0]);
    if (length > S(0) && std::abs(area.dot(d)) >= S(kSupportingFeatureCos) * area.norm() * length) {
      for (const Vec3& p : v) out.add(p);
      return;
    }
    const Vec3 top = support(d);
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = v[k];
      const Vec3& q = v[(k + 1) % 3];
      if ((p == top || q == top) && std::abs((q - p).dot(d)) <= S(kSupportingFeatureSin) * (q - p).norm() * length) {
        out.add(p);
        out.add(q);
        return;
      }
    }
    out.add(top);
  }
  [[nodiscard]] Vec3 getCenterOfVolume() const { return (v[0] + v[1] + v[2]) / S(3); }
  [[nodiscard]] BoundingBoxT<S> getBoundingBox() const {
    return {v[0].cwiseMin(v[1]).cwiseMin(v[2]), v[0].cwiseMax(v[1]).cwiseMax(v[2])};
  }
  /// Unit outward normal (+z for a degenerate triangle).
  [[nodiscard]] Vec3 normal() const {
    const Vec3 n = (v[1] - v[0]).cross(v[2] - v[0]);
    const S length = n.norm();
    return length > S(0) ? Vec3(n / length) : Vec3::UnitZ();
  }
};

}  // namespace spook::detail
