#pragma once

#include <cmath>
#include <numbers>

#include <spook/collide/shapes/shape.hpp>
#include <spook/core/implementation.hpp>

namespace spook {

/// A solid cylinder centered on its origin with its axis along y, as in the
/// seeds: radius and height (the full length along y), both in m.
template <Scalar S>
class CylinderT : public ShapeT<S> {
 public:
  static constexpr ShapeType kType = ShapeType::CYLINDER;
  using Vec3 = spook::Vec3T<S>;

  CylinderT(S radius, S height);

  [[nodiscard]] S getRadius() const { return radius_; }
  void setRadius(S radius);
  [[nodiscard]] S getHeight() const { return height_; }
  void setHeight(S height);

  /// V = π r² h.
  [[nodiscard]] ShapeType getType() const override { return kType; }
  bool collideWithLowerRank(const TransformT<S>& X_WA, const ShapeT<S>& other, const TransformT<S>& X_WB,
                            ContactSinkT<S>& sink) const override {
    return detail::collideWithLowerRank(*this, X_WA, other, X_WB, sink);
  }

  [[nodiscard]] S getVolume() const override;

  /// I_yy = m r²/2 about the axis; I_xx = I_zz = m (3r² + h²)/12.
  [[nodiscard]] SPDMat3T<S> calculateInertia(S mass) const override;

  [[nodiscard]] BoundingBoxT<S> getBoundingBox() const override { return detail::boundingBoxFromSupport<S>(*this); }

  /// The point of the rim (or cap center, along the axis) farthest along `direction`.
  [[nodiscard]] Vec3 support(const Vec3& direction) const {
    const S radial = std::hypot(direction.x(), direction.z());
    const S y = direction.y() < S(0) ? -S(0.5) * height_ : S(0.5) * height_;
    if (!(radial > S(0))) return Vec3(S(0), y, S(0));
    return Vec3(direction.x() * (radius_ / radial), y, direction.z() * (radius_ / radial));
  }

  /// Along its axis (within the feature angle) a cap, a disc with
  /// kCapCorners rim points starting from the rim's support; across it the side line at
  /// the support's azimuth; else the support point (on a rim).
  void supportingFeature(const Vec3& direction, SupportingFeatureT<S>& out) const {
    out.count = 0;
    out.radius = S(0);
    const S length = direction.norm(), radial = std::hypot(direction.x(), direction.z());
    const S y = direction.y() < S(0) ? -S(0.5) * height_ : S(0.5) * height_;
    if (length > S(0) && std::abs(direction.y()) >= S(kSupportingFeatureCos) * length) {
      const S start = radial > S(0) ? std::atan2(direction.z(), direction.x()) : S(0);
      for (int k = 0; k < kCapCorners; ++k) {
        const S angle = start + S(2) * std::numbers::pi_v<S> * S(k) / S(kCapCorners);
        out.add(Vec3(radius_ * std::cos(angle), y, radius_ * std::sin(angle)));
      }
      out.radius = radius_;
      out.center = Vec3(S(0), y, S(0));
      out.axis = Vec3::UnitY();
      return;
    }
    if (radial > S(0) && std::abs(direction.y()) <= S(kSupportingFeatureSin) * length) {
      const S x = direction.x() * (radius_ / radial), z = direction.z() * (radius_ / radial);
      out.add(Vec3(x, S(0.5) * height_, z));
      out.add(Vec3(x, -S(0.5) * height_, z));
      return;
    }
    out.add(support(direction));
  }

 protected:
  ~CylinderT() override = default;

 private:
  S radius_ = S(0);
  S height_ = S(0);
};

template <Scalar S>
CylinderT<S>::CylinderT(S radius, S height) {
  setRadius(radius);
  setHeight(height);
}

template <Scalar S>
void CylinderT<S>::setRadius(S radius) {
  const S checked = this->requireLength("Cylinder", "radius", radius), old = radius_;
  this->change([&] { radius_ = checked; }, [&] { radius_ = old; });
}

template <Scalar S>
void CylinderT<S>::setHeight(S height) {
  const S checked = this->requireLength("Cylinder", "height", height), old = height_;
  this->change([&] { height_ = checked; }, [&] { height_ = old; });
}

template <Scalar S>
S CylinderT<S>::getVolume() const {
  return std::numbers::pi_v<S> * radius_ * radius_ * height_;
}

template <Scalar S>
auto CylinderT<S>::calculateInertia(S mass) const -> SPDMat3T<S> {
  this->requireMass("Cylinder", mass);
  const S r2 = radius_ * radius_, across = mass * (S(3) * r2 + height_ * height_) / S(12);
  return SPDMat3T<S>(Vec3(across, S(0.5) * mass * r2, across));
}

SPOOK_COMPILED_WITH_COLLIDERS(class, CylinderT)

using Cylinder = CylinderT<double>;
using CylinderRef = ref_ptr<Cylinder>;
namespace f32 {
using Cylinder = CylinderT<float>;
using CylinderRef = ref_ptr<Cylinder>;
}  // namespace f32

}  // namespace spook
