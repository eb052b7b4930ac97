#pragma once

#include <cmath>
#include <limits>

#include <spook/collide/shapes/shape.hpp>
#include <spook/core/implementation.hpp>

namespace spook {

/// An infinite plane through `point` with unit `normal`, both in the shape
/// frame. As in AGX the solid half-space lies below it, opposite the normal.
/// It has no volume, no mass and no support point.
template <Scalar S>
class PlaneT : public ShapeT<S> {
 public:
  static constexpr ShapeType kType = ShapeType::PLANE;
  using Vec3 = spook::Vec3T<S>;

  /// Plane through `point` (m) with normal `normal` (any non-zero length; normalized).
  explicit PlaneT(const Vec3& normal, const Vec3& point = Vec3::Zero()) { set(normal, point); }
  /// Plane normal·x = distance (m), i.e. through normal·distance for a unit normal.
  PlaneT(const Vec3& normal, S distance);
  /// Plane through three points (m), its normal (p2 − p1) × (p3 − p1) by the
  /// right-hand rule (counter-clockwise points seen from above the plane);
  /// throws on coincident or collinear points.
  PlaneT(const Vec3& p1, const Vec3& p2, const Vec3& p3) { set(normalThrough(p1, p2, p3), p1); }
  /// Plane a·x + b·y + c·z = d (AGX's order): normal (a, b, c) normalized,
  /// d (m·|(a, b, c)|) scaled with it to the distance d / |(a, b, c)| (m).
  PlaneT(S a, S b, S c, S d) : PlaneT(Vec3(a, b, c), distanceOf(Vec3(a, b, c), d)) {}

  /// Unit outward normal, shape frame.
  [[nodiscard]] const Vec3& getNormal() const { return normal_; }
  /// The point the plane was given through, shape frame (m).
  [[nodiscard]] const Vec3& getPoint() const { return point_; }
  /// Signed distance of the plane from the shape origin along the normal, normal·point (m).
  [[nodiscard]] S getDistance() const { return normal_.dot(point_); }
  /// Moves the plane (shape frame; normal normalized, point in m); throws and keeps it on bad input.
  void set(const Vec3& normal, const Vec3& point);

  /// Signed distance of `p` (shape frame, m) above the plane; negative inside the solid (m).
  [[nodiscard]] S signedDistance(const Vec3& p) const { return normal_.dot(p - point_); }

  /// Which kind of shape this is.
  [[nodiscard]] ShapeType getType() const override { return kType; }
  bool collideWithLowerRank(const TransformT<S>& X_WA, const ShapeT<S>& other, const TransformT<S>& X_WB,
                            ContactSinkT<S>& sink) const override {
    return detail::collideWithLowerRank(*this, X_WA, other, X_WB, sink);
  }
  /// A plane encloses no volume: 0 m³.
  [[nodiscard]] S getVolume() const override { return S(0); }
  /// Always throws: a plane has no volume and so no inertia.
  [[nodiscard]] SPDMat3T<S> calculateInertia(S mass) const override;
  /// Unbounded: every component ±infinity (the Space treats such boxes apart).
  [[nodiscard]] BoundingBoxT<S> getBoundingBox() const override;

 protected:
  ~PlaneT() override = default;

 private:
  // Scaled by its largest component first, so that tiny normals do not
  // underflow when squared.
  static Vec3 unitNormal(const Vec3& normal) {
    const S largest = normal.cwiseAbs().maxCoeff();
    if (!(normal.allFinite() && largest > S(0)))
      throw detail::makeError("Plane", "", "normal must be finite and non-zero", normal);
    return (normal / largest).normalized();
  }

  // Each edge scaled by its largest component first, so that the cross
  // product neither overflows nor underflows. The points are collinear when
  // the sine of the angle between the edges is within round-off of zero.
  static Vec3 normalThrough(const Vec3& p1, const Vec3& p2, const Vec3& p3) {
    const Vec3 e1 = p2 - p1, e2 = p3 - p1;
    const auto points = [&] {
      Eigen::Matrix<S, 9, 1> all;
      all << p1, p2, p3;
      return all;
    };
    if (!(e1.allFinite() && e2.allFinite()))
      throw detail::makeError("Plane", "", "three points must be finite and their differences too (m)", points());
    const S l1 = e1.cwiseAbs().maxCoeff(), l2 = e2.cwiseAbs().maxCoeff();
    if (!(l1 > S(0) && l2 > S(0))) throw detail::makeError("Plane", "", "three points must not coincide (m)", points());
    const Vec3 u1 = (e1 / l1).normalized(), u2 = (e2 / l2).normalized();
    const Vec3 n = u1.cross(u2);
    if (!(n.norm() > S(16) * std::numeric_limits<S>::epsilon()))
      throw detail::makeError("Plane", "", "three points must not be collinear (m)", points());
    return n;
  }
  // d / |n| without squaring n's components (which could overflow or underflow).
  static S distanceOf(const Vec3& normal, S d) {
    const S largest = normal.cwiseAbs().maxCoeff();
    if (!(normal.allFinite() && largest > S(0)))
      throw detail::makeError("Plane", "", "normal (a, b, c) must be finite and non-zero", normal);
    const S distance = (d / largest) / (normal / largest).norm();
    if (!std::isfinite(distance))
      throw detail::makeError("Plane", "", "d / |(a, b, c)| must be finite (m)",
                              Eigen::Matrix<S, 4, 1>(normal.x(), normal.y(), normal.z(), d));
    return distance;
  }

  Vec3 normal_ = Vec3::UnitZ();
  Vec3 point_ = Vec3::Zero();
};

template <Scalar S>
PlaneT<S>::PlaneT(const Vec3& normal, S distance) {
  if (!std::isfinite(distance)) throw detail::makeError("Plane", "", "distance must be finite (m)", distance);
  const Vec3 n = unitNormal(normal);
  set(n, Vec3(n * distance));
}

template <Scalar S>
void PlaneT<S>::set(const Vec3& normal, const Vec3& point) {
  const Vec3 n = unitNormal(normal);
  if (!point.allFinite()) throw detail::makeError("Plane", "", "point must be finite (m)", point);
  const Vec3 oldNormal = normal_, oldPoint = point_;
  this->change([&] { normal_ = n, point_ = point; }, [&] { normal_ = oldNormal, point_ = oldPoint; });
}

template <Scalar S>
auto PlaneT<S>::calculateInertia(S mass) const -> SPDMat3T<S> {
  throw detail::makeError("Plane", "", "a Plane has no volume and no inertia (kg)", mass);
}

template <Scalar S>
auto PlaneT<S>::getBoundingBox() const -> BoundingBoxT<S> {
  constexpr S inf = std::numeric_limits<S>::infinity();
  return {Vec3::Constant(-inf), Vec3::Constant(inf)};
}

SPOOK_COMPILED_WITH_COLLIDERS(class, PlaneT)

using Plane = PlaneT<double>;
using PlaneRef = ref_ptr<Plane>;
namespace f32 {
using Plane = PlaneT<float>;
using PlaneRef = ref_ptr<Plane>;
}  // namespace f32

}  // namespace spook
