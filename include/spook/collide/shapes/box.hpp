#pragma once

#include <cmath>
#include <utility>

#include <spook/collide/shapes/shape.hpp>
#include <spook/core/implementation.hpp>

namespace spook {

/// A box centered on its origin, given by its half extents along x, y, z (m).
template <Scalar S>
class BoxT : public ShapeT<S> {
 public:
  static constexpr ShapeType kType = ShapeType::BOX;
  using Vec3 = spook::Vec3T<S>;

  explicit BoxT(const Vec3& halfExtents) { setHalfExtents(halfExtents); }

  [[nodiscard]] const Vec3& getHalfExtents() const { return halfExtents_; }
  void setHalfExtents(const Vec3& halfExtents);

  [[nodiscard]] ShapeType getType() const override { return kType; }
  bool collideWithLowerRank(const TransformT<S>& X_WA, const ShapeT<S>& other, const TransformT<S>& X_WB,
                            ContactSinkT<S>& sink) const override {
    return detail::collideWithLowerRank(*this, X_WA, other, X_WB, sink);
  }

  [[nodiscard]] S getVolume() const override { return S(8) * halfExtents_.prod(); }

  /// I = m/3 (b² + c², a² + c², a² + b²) for half extents a, b, c.
  [[nodiscard]] SPDMat3T<S> calculateInertia(S mass) const override;

  [[nodiscard]] BoundingBoxT<S> getBoundingBox() const override { return {-halfExtents_, halfExtents_}; }

  /// The corner farthest along `direction` (a zero component picks +).
  [[nodiscard]] Vec3 support(const Vec3& direction) const {
    return Vec3(direction.x() < S(0) ? -halfExtents_.x() : halfExtents_.x(),
                direction.y() < S(0) ? -halfExtents_.y() : halfExtents_.y(),
                direction.z() < S(0) ? -halfExtents_.z() : halfExtents_.z());
  }

  /// The face, edge or corner supporting `direction` (SupportingFeatureT):
  /// the face whose normal is within the feature angle of it, else the edge
  /// across which it is, else the corner.
  void supportingFeature(const Vec3& direction, SupportingFeatureT<S>& out) const {
    out.count = 0;
    const Vec3 corner = support(direction);
    const S length = direction.norm();
    if (!(length > S(0))) {
      out.add(corner);
      return;
    }
    int most = 0, least = 0;
    direction.cwiseAbs().maxCoeff(&most);
    direction.cwiseAbs().minCoeff(&least);
    if (std::abs(direction[most]) >= S(kSupportingFeatureCos) * length) {
      // The face across axis `most`: its corners, counter-clockwise.
      const int i = (most + 1) % 3, j = (most + 2) % 3;
      for (const auto& [si, sj] : {std::pair{1, 1}, std::pair{-1, 1}, std::pair{-1, -1}, std::pair{1, -1}}) {
        Vec3 p = corner;
        p[i] = S(si) * halfExtents_[i];
        p[j] = S(sj) * halfExtents_[j];
        out.add(p);
      }
    } else if (std::abs(direction[least]) <= S(kSupportingFeatureSin) * length) {
      Vec3 p = corner;
      p[least] = halfExtents_[least];
      out.add(p);
      p[least] = -halfExtents_[least];
      out.add(p);
    } else {
      out.add(corner);
    }
  }

 protected:
  ~BoxT() override = default;

 private:
  Vec3 halfExtents_ = Vec3::Zero();
};

template <Scalar S>
void BoxT<S>::setHalfExtents(const Vec3& halfExtents) {
  if (!(halfExtents.allFinite() && halfExtents.minCoeff() > S(0)))
    throw detail::makeError("Box", "", "half extents must be finite and > 0 m", halfExtents);
  const Vec3 old = halfExtents_;
  this->change([&] { halfExtents_ = halfExtents; }, [&] { halfExtents_ = old; });
}

template <Scalar S>
auto BoxT<S>::calculateInertia(S mass) const -> SPDMat3T<S> {
  this->requireMass("Box", mass);
  const Vec3 sq = halfExtents_.cwiseAbs2();
  return SPDMat3T<S>(Vec3(sq.y() + sq.z(), sq.x() + sq.z(), sq.x() + sq.y()) * (mass / S(3)));
}

SPOOK_COMPILED_WITH_COLLIDERS(class, BoxT)

using Box = BoxT<double>;
using BoxRef = ref_ptr<Box>;
namespace f32 {
using Box = BoxT<float>;
using BoxRef = ref_ptr<Box>;
}  // namespace f32

}  // namespace spook
