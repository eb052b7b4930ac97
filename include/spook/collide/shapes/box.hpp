#pragma once

#include <spook/collide/shapes/shape.hpp>

namespace spook {

/// A box centered on its origin, given by its half extents along x, y, z (m).
template <Scalar S>
class BoxT : public ShapeT<S> {
 public:
  static constexpr ShapeType kType = ShapeType::BOX;
  using Vec3 = spook::Vec3T<S>;

  explicit BoxT(const Vec3& halfExtents) { setHalfExtents(halfExtents); }

  [[nodiscard]] const Vec3& getHalfExtents() const { return halfExtents_; }
  void setHalfExtents(const Vec3& halfExtents) {
    if (!(halfExtents.allFinite() && halfExtents.minCoeff() > S(0)))
      throw detail::makeError("Box", "", "half extents must be finite and > 0 m", halfExtents);
    halfExtents_ = halfExtents;
  }

  [[nodiscard]] ShapeType getType() const override { return kType; }

  [[nodiscard]] S getVolume() const override { return S(8) * halfExtents_.prod(); }

  /// I = m/3 (b² + c², a² + c², a² + b²) for half extents a, b, c.
  [[nodiscard]] SPDMat3T<S> calculateInertia(S mass) const override {
    this->requireMass("Box", mass);
    const Vec3 sq = halfExtents_.cwiseAbs2();
    return SPDMat3T<S>(Vec3(sq.y() + sq.z(), sq.x() + sq.z(), sq.x() + sq.y()) * (mass / S(3)));
  }

  [[nodiscard]] BoundingBoxT<S> getBoundingBox() const override { return {-halfExtents_, halfExtents_}; }

  /// The corner farthest along `direction` (a zero component picks +).
  [[nodiscard]] Vec3 support(const Vec3& direction) const {
    return Vec3(direction.x() < S(0) ? -halfExtents_.x() : halfExtents_.x(),
                direction.y() < S(0) ? -halfExtents_.y() : halfExtents_.y(),
                direction.z() < S(0) ? -halfExtents_.z() : halfExtents_.z());
  }

 protected:
  ~BoxT() override = default;

 private:
  Vec3 halfExtents_;
};

using Box = BoxT<double>;
using BoxRef = ref_ptr<Box>;
namespace f32 {
using Box = BoxT<float>;
using BoxRef = ref_ptr<Box>;
}  // namespace f32

}  // namespace spook
