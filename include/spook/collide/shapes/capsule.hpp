#pragma once

#include <cmath>
#include <numbers>

#include <spook/collide/shapes/shape.hpp>
#include <spook/core/implementation.hpp>

namespace spook {

/// A capsule centered on its origin with its axis along y, as in the seeds:
/// a cylinder of `height` (m, between the hemisphere centers) capped by two
/// hemispheres of `radius` (m). Total length height + 2·radius.
template <Scalar S>
class CapsuleT : public ShapeT<S> {
 public:
  static constexpr ShapeType kType = ShapeType::CAPSULE;
  using Vec3 = spook::Vec3T<S>;

  CapsuleT(S radius, S height);

  [[nodiscard]] S getRadius() const { return radius_; }
  void setRadius(S radius);
  [[nodiscard]] S getHeight() const { return height_; }
  void setHeight(S height);

  /// V = π r² h + 4/3 π r³.
  [[nodiscard]] ShapeType getType() const override { return kType; }
  bool collideWithLowerRank(const TransformT<S>& X_WA, const ShapeT<S>& other, const TransformT<S>& X_WB,
                            ContactSinkT<S>& sink) const override {
    return detail::collideWithLowerRank(*this, X_WA, other, X_WB, sink);
  }

  [[nodiscard]] S getVolume() const override;

  /// Cylinder part m_c and the two hemispheres m_s share the mass by volume:
  /// I_yy = m_c r²/2 + 2/5 m_s r²,
  /// I_xx = I_zz = m_c (3r² + h²)/12 + m_s (2r²/5 + h²/4 + 3hr/8), the last
  /// term from each hemisphere's centroid at 3r/8 and the parallel-axis rule.
  [[nodiscard]] SPDMat3T<S> calculateInertia(S mass) const override;

  [[nodiscard]] BoundingBoxT<S> getBoundingBox() const override { return detail::boundingBoxFromSupport<S>(*this); }

  /// The surface point farthest along `direction`: the end sphere's support.
  [[nodiscard]] Vec3 support(const Vec3& direction) const {
    const Vec3 end(S(0), direction.y() < S(0) ? -S(0.5) * height_ : S(0.5) * height_, S(0));
    const S length = direction.norm();
    return length > S(0) ? Vec3(end + direction * (radius_ / length)) : Vec3(end + Vec3(radius_, S(0), S(0)));
  }

  /// Across its axis (within the feature angle) the side line, from one end
  /// sphere's support to the other's; else the support point.
  void supportingFeature(const Vec3& direction, SupportingFeatureT<S>& out) const {
    out.count = 0;
    const S length = direction.norm();
    if (length > S(0) && std::abs(direction.y()) <= S(kSupportingFeatureSin) * length) {
      const Vec3 side = direction * (radius_ / length);
      out.add(Vec3(side + Vec3(S(0), S(0.5) * height_, S(0))));
      out.add(Vec3(side - Vec3(S(0), S(0.5) * height_, S(0))));
      return;
    }
    out.add(support(direction));
  }

 protected:
  ~CapsuleT() override = default;

 private:
  S radius_ = S(0);
  S height_ = S(0);
};

template <Scalar S>
CapsuleT<S>::CapsuleT(S radius, S height) {
  setRadius(radius);
  setHeight(height);
}

template <Scalar S>
void CapsuleT<S>::setRadius(S radius) {
  const S checked = this->requireLength("Capsule", "radius", radius), old = radius_;
  this->change([&] { radius_ = checked; }, [&] { radius_ = old; });
}

template <Scalar S>
void CapsuleT<S>::setHeight(S height) {
  const S checked = this->requireLength("Capsule", "height", height), old = height_;
  this->change([&] { height_ = checked; }, [&] { height_ = old; });
}

template <Scalar S>
S CapsuleT<S>::getVolume() const {
  return std::numbers::pi_v<S> * radius_ * radius_ * (height_ + S(4) / S(3) * radius_);
}

template <Scalar S>
auto CapsuleT<S>::calculateInertia(S mass) const -> SPDMat3T<S> {
  this->requireMass("Capsule", mass);
  const S r = radius_, h = height_, r2 = r * r;
  const S cylinderShare = h / (h + S(4) / S(3) * r);
  const S mc = mass * cylinderShare, ms = mass - mc;
  const S axial = S(0.5) * mc * r2 + S(0.4) * ms * r2;
  const S across = mc * (S(3) * r2 + h * h) / S(12) + ms * (S(0.4) * r2 + S(0.25) * h * h + S(0.375) * h * r);
  return SPDMat3T<S>(Vec3(across, axial, across));
}

SPOOK_COMPILED_WITH_COLLIDERS(class, CapsuleT)

using Capsule = CapsuleT<double>;
using CapsuleRef = ref_ptr<Capsule>;
namespace f32 {
using Capsule = CapsuleT<float>;
using CapsuleRef = ref_ptr<Capsule>;
}  // namespace f32

}  // namespace spook
