#pragma once

#include <cmath>

#include <spook/collide/shapes/shape.hpp>
#include <spook/core/implementation.hpp>

namespace spook {

/// A straight segment from a first to a second point in the shape frame (m).
/// It has no volume and no mass; its support point is an endpoint.
template <Scalar S>
class LineT : public ShapeT<S> {
 public:
  static constexpr ShapeType kType = ShapeType::LINE;
  using Vec3 = spook::Vec3T<S>;

  /// Segment from `first` to `second` (shape frame, m).
  LineT(const Vec3& first, const Vec3& second) { setPoints(first, second); }

  /// First endpoint, shape frame (m).
  [[nodiscard]] const Vec3& getFirstPoint() const { return first_; }
  /// Second endpoint, shape frame (m).
  [[nodiscard]] const Vec3& getSecondPoint() const { return second_; }
  /// Length of the segment (m).
  [[nodiscard]] S getLength() const { return (second_ - first_).norm(); }
  /// Moves both endpoints (shape frame, m); throws and keeps the line unless
  /// they are finite and apart.
  void setPoints(const Vec3& first, const Vec3& second);

  /// Which kind of shape this is.
  [[nodiscard]] ShapeType getType() const override { return kType; }
  bool collideWithLowerRank(const TransformT<S>& X_WA, const ShapeT<S>& other, const TransformT<S>& X_WB,
                            ContactSinkT<S>& sink) const override {
    return detail::collideWithLowerRank(*this, X_WA, other, X_WB, sink);
  }
  /// A segment encloses no volume: 0 m³.
  [[nodiscard]] S getVolume() const override { return S(0); }
  /// The midpoint, shape frame (m).
  [[nodiscard]] Vec3 getCenterOfVolume() const override { return S(0.5) * (first_ + second_); }
  /// Always throws: a line has no volume, and a rod of zero thickness has a
  /// singular inertia (none about its own axis).
  [[nodiscard]] SPDMat3T<S> calculateInertia(S mass) const override;
  /// Box around both endpoints, shape frame (m).
  [[nodiscard]] BoundingBoxT<S> getBoundingBox() const override;

  /// The endpoint farther along `direction`, the first one on a tie (shape frame, m).
  [[nodiscard]] Vec3 support(const Vec3& direction) const {
    return second_.dot(direction) > first_.dot(direction) ? second_ : first_;
  }

  /// Both endpoints when the line is across `direction` within the feature
  /// angle, else the supporting endpoint.
  void supportingFeature(const Vec3& direction, SupportingFeatureT<S>& out) const {
    out.count = 0;
    const Vec3 along = second_ - first_;
    if (std::abs(along.dot(direction)) <= S(kSupportingFeatureSin) * along.norm() * direction.norm()) {
      out.add(first_);
      out.add(second_);
      return;
    }
    out.add(support(direction));
  }

 protected:
  ~LineT() override = default;

 private:
  Vec3 first_ = Vec3::Zero();
  Vec3 second_ = Vec3::Zero();
};

template <Scalar S>
void LineT<S>::setPoints(const Vec3& first, const Vec3& second) {
  const Eigen::Matrix<S, 6, 1> both = (Eigen::Matrix<S, 6, 1>() << first, second).finished();
  if (!both.allFinite()) throw detail::makeError("Line", "", "points must be finite (m)", both);
  const Vec3 span = second - first;
  if (!(span.allFinite() && span.squaredNorm() > S(0)))
    throw detail::makeError("Line", "", "points must be apart (length > 0 m)", both);
  const Vec3 oldFirst = first_, oldSecond = second_;
  this->change([&] { first_ = first, second_ = second; }, [&] { first_ = oldFirst, second_ = oldSecond; });
}

template <Scalar S>
auto LineT<S>::calculateInertia(S mass) const -> SPDMat3T<S> {
  throw detail::makeError("Line", "", "a Line has no volume and no inertia (kg)", mass);
}

template <Scalar S>
auto LineT<S>::getBoundingBox() const -> BoundingBoxT<S> {
  return {first_.cwiseMin(second_), first_.cwiseMax(second_)};
}

SPOOK_COMPILED_WITH_COLLIDERS(class, LineT)

using Line = LineT<double>;
using LineRef = ref_ptr<Line>;
namespace f32 {
using Line = LineT<float>;
using LineRef = ref_ptr<Line>;
}  // namespace f32

}  // namespace spook
