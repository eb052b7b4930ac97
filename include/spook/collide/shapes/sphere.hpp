#pragma once

#include <numbers>

#include <spook/collide/shapes/shape.hpp>
#include <spook/core/implementation.hpp>

namespace spook {

/// A sphere centered on its origin (radius in m).
template <Scalar S>
class SphereT : public ShapeT<S> {
 public:
  static constexpr ShapeType kType = ShapeType::SPHERE;
  using Vec3 = spook::Vec3T<S>;

  explicit SphereT(S radius) { setRadius(radius); }

  [[nodiscard]] S getRadius() const { return radius_; }
  /// Throws, keeping the radius, on a value that is not finite and > 0 m or
  /// that a body holding the sphere could not take.
  void setRadius(S radius);

  /// V = 4/3 π r³.
  [[nodiscard]] ShapeType getType() const override { return kType; }
  bool collideWithLowerRank(const TransformT<S>& X_WA, const ShapeT<S>& other, const TransformT<S>& X_WB,
                            ContactSinkT<S>& sink) const override {
    return detail::collideWithLowerRank(*this, X_WA, other, X_WB, sink);
  }

  [[nodiscard]] S getVolume() const override;

  /// I = 2/5 m r² about every axis.
  [[nodiscard]] SPDMat3T<S> calculateInertia(S mass) const override;

  [[nodiscard]] BoundingBoxT<S> getBoundingBox() const override;

  /// The surface point farthest along `direction` (+x for a zero direction).
  [[nodiscard]] Vec3 support(const Vec3& direction) const {
    const S length = direction.norm();
    return length > S(0) ? Vec3(direction * (radius_ / length)) : Vec3(radius_, S(0), S(0));
  }

  /// A sphere's supporting feature is always its support point.
  void supportingFeature(const Vec3& direction, SupportingFeatureT<S>& out) const {
    out.count = 0;
    out.add(support(direction));
  }

 protected:
  ~SphereT() override = default;

 private:
  S radius_ = S(0);
};

template <Scalar S>
void SphereT<S>::setRadius(S radius) {
  const S checked = this->requireLength("Sphere", "radius", radius), old = radius_;
  this->change([&] { radius_ = checked; }, [&] { radius_ = old; });
}

template <Scalar S>
S SphereT<S>::getVolume() const {
  return S(4) / S(3) * std::numbers::pi_v<S> * radius_ * radius_ * radius_;
}

template <Scalar S>
auto SphereT<S>::calculateInertia(S mass) const -> SPDMat3T<S> {
  this->requireMass("Sphere", mass);
  return SPDMat3T<S>(Vec3::Constant(S(0.4) * mass * radius_ * radius_));
}

template <Scalar S>
auto SphereT<S>::getBoundingBox() const -> BoundingBoxT<S> {
  return {Vec3::Constant(-radius_), Vec3::Constant(radius_)};
}

SPOOK_COMPILED_WITH_COLLIDERS(class, SphereT)

using Sphere = SphereT<double>;
using SphereRef = ref_ptr<Sphere>;
namespace f32 {
using Sphere = SphereT<float>;
using SphereRef = ref_ptr<Sphere>;
}  // namespace f32

}  // namespace spook
