#pragma once

#include <algorithm>
#include <cmath>

#include <spook/collide/collider.hpp>
#include <spook/collide/shapes/cylinder.hpp>
#include <spook/collide/shapes/sphere.hpp>

namespace spook {

/// Cylinder–sphere, in the cylinder frame (axis y, half height k, radius
/// R). A sphere center c outside the cylinder pushes away from the point q
/// of the solid cylinder closest to it (c with y clamped to ±k and its
/// radial part to length R): depth r − |c − q|. A center inside, or on the
/// surface, pushes out through the nearer of the cap (gap k − |c_y|) and the
/// barrel (gap R − |c_xz|), the cap on a tie, the barrel along the
/// cylinder's x axis when c is on the axis: depth r + gap.
template <Scalar S>
struct Collider<CylinderT<S>, SphereT<S>> {
  static void collide(const CylinderT<S>& a, const TransformT<S>& X_WA, const SphereT<S>& b, const TransformT<S>& X_WB,
                      ContactSinkT<S>& sink) {
    const S R = a.getRadius(), k = S(0.5) * a.getHeight(), r = b.getRadius();
    const Vec3T<S> c = X_WA.inverse(Eigen::Isometry) * X_WB.translation();
    const S radial = std::hypot(c.x(), c.z());
    Vec3T<S> q(c.x(), std::clamp(c.y(), -k, k), c.z());
    if (radial > R) {
      q.x() *= R / radial;
      q.z() *= R / radial;
    }
    const Vec3T<S> d = c - q;
    const S distance = d.norm();
    const S tiny = ScalarTraits<S>::epsilon() * (R + k + r);
    Vec3T<S> n;           // cylinder frame, from the cylinder toward the sphere
    Vec3T<S> onCylinder;  // the cylinder's deepest point along n
    S depth;
    if (distance > tiny) {
      depth = r - distance;
      if (!(depth >= S(0))) return;
      n = d / distance;
      onCylinder = q;
    } else {
      const S capGap = k - std::abs(c.y()), barrelGap = R - radial;
      const S gap = std::min(capGap, barrelGap);
      if (capGap <= barrelGap)
        n = Vec3T<S>(S(0), c.y() < S(0) ? S(-1) : S(1), S(0));
      else if (radial > tiny)
        n = Vec3T<S>(c.x() / radial, S(0), c.z() / radial);
      else
        n = Vec3T<S>::UnitX();
      depth = r + gap;
      onCylinder = c + gap * n;
    }
    // Midway between the cylinder's deepest point and the sphere's, c − r n.
    sink.add(X_WA * Vec3T<S>(S(0.5) * (onCylinder + c - r * n)), X_WA.linear() * n, depth);
  }
};

}  // namespace spook
