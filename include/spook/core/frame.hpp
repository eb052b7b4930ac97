#pragma once

#include <spook/core/error.hpp>
#include <spook/core/implementation.hpp>
#include <spook/core/math.hpp>
#include <spook/core/ref_ptr.hpp>
#include <spook/core/referenced.hpp>

namespace spook {

/// A coordinate system: a rigid transform relative to an optional parent
/// frame. "Local" values are relative to the parent; the others are in
/// world coordinates. Lengths in meters.
template <Scalar S>
class FrameT : public Referenced {
 public:
  using Vec3 = spook::Vec3T<S>;
  using Quat = spook::QuatT<S>;
  using Transform = spook::TransformT<S>;

  FrameT() = default;
  explicit FrameT(const Transform& localMatrix) { setLocalMatrix(localMatrix); }

  /// The parent frame, or nullptr for a root frame.
  [[nodiscard]] FrameT* getParent() const { return parent_.get(); }
  /// Re-parents the frame keeping its local transform; throws if that would make a cycle.
  void setParent(FrameT* parent);

  /// Transform from this frame to its parent (world when root).
  [[nodiscard]] Transform getLocalMatrix() const;
  void setLocalMatrix(const Transform& X);

  /// Transform from this frame to the world.
  [[nodiscard]] Transform getMatrix() const;
  void setMatrix(const Transform& X_W);

  /// Origin relative to the parent (m).
  [[nodiscard]] const Vec3& getLocalTranslate() const { return localTranslate_; }
  void setLocalTranslate(const Vec3& p) { setLocal(p, localRotate_); }
  void setLocalTranslate(S x, S y, S z) { setLocalTranslate(Vec3(x, y, z)); }

  /// Orientation relative to the parent (normalized on set).
  [[nodiscard]] const Quat& getLocalRotate() const { return localRotate_; }
  void setLocalRotate(const Quat& q) { setLocal(localTranslate_, q); }

  /// Origin in world coordinates (m).
  [[nodiscard]] Vec3 getTranslate() const;
  void setTranslate(const Vec3& p_W);
  void setTranslate(S x, S y, S z) { setTranslate(Vec3(x, y, z)); }

  /// Orientation in world coordinates.
  [[nodiscard]] Quat getRotate() const;
  void setRotate(const Quat& q_W);

  /// A point given in this frame, expressed in world coordinates.
  [[nodiscard]] Vec3 transformPointToWorld(const Vec3& p) const { return getMatrix() * p; }
  /// A direction given in this frame, expressed in world coordinates.
  [[nodiscard]] Vec3 transformVectorToWorld(const Vec3& v) const { return getRotate() * v; }
  /// A world point expressed in this frame.
  [[nodiscard]] Vec3 transformPointToLocal(const Vec3& p_W) const { return getMatrix().inverse() * p_W; }
  /// A world direction expressed in this frame.
  [[nodiscard]] Vec3 transformVectorToLocal(const Vec3& v_W) const { return getRotate().conjugate() * v_W; }

 protected:
  ~FrameT() override = default;

 private:
  void setLocal(const Vec3& p, const Quat& q);
  static void checkVector(const Vec3& v, const char* what);
  static void checkQuat(const Quat& q);
  static void checkMatrix(const Transform& X);

  ref_ptr<FrameT> parent_;
  Vec3 localTranslate_ = Vec3::Zero();
  Quat localRotate_ = Quat::Identity();
};

template <Scalar S>
void FrameT<S>::setParent(FrameT* parent) {
  for (const FrameT* f = parent; f; f = f->getParent())
    if (f == this) throw detail::makeError("Frame", "", "parent would create a cycle", "a frame of its own chain");
  parent_ = parent;
}

template <Scalar S>
auto FrameT<S>::getLocalMatrix() const -> Transform {
  return makeTransform<S>(localTranslate_, localRotate_);
}

template <Scalar S>
void FrameT<S>::setLocalMatrix(const Transform& X) {
  checkMatrix(X);
  setLocal(X.translation(), Quat(X.linear()));
}

template <Scalar S>
auto FrameT<S>::getMatrix() const -> Transform {
  return parent_ ? parent_->getMatrix() * getLocalMatrix() : getLocalMatrix();
}

template <Scalar S>
void FrameT<S>::setMatrix(const Transform& X_W) {
  checkMatrix(X_W);
  const Transform X_P = parent_ ? Transform(parent_->getMatrix().inverse() * X_W) : X_W;
  setLocal(X_P.translation(), Quat(X_P.linear()));
}

template <Scalar S>
auto FrameT<S>::getTranslate() const -> Vec3 {
  return parent_ ? parent_->transformPointToWorld(localTranslate_) : localTranslate_;
}

template <Scalar S>
void FrameT<S>::setTranslate(const Vec3& p_W) {
  checkVector(p_W, "translate must be finite");
  setLocalTranslate(parent_ ? parent_->transformPointToLocal(p_W) : p_W);
}

template <Scalar S>
auto FrameT<S>::getRotate() const -> Quat {
  return parent_ ? Quat(parent_->getRotate() * localRotate_) : localRotate_;
}

template <Scalar S>
void FrameT<S>::setRotate(const Quat& q_W) {
  checkQuat(q_W);
  setLocalRotate(parent_ ? Quat(parent_->getRotate().conjugate() * unitQuaternion<S>(q_W)) : q_W);
}

template <Scalar S>
void FrameT<S>::setLocal(const Vec3& p, const Quat& q) {
  checkVector(p, "translate must be finite");
  checkQuat(q);
  localTranslate_ = p;
  localRotate_ = unitQuaternion<S>(q);
}

template <Scalar S>
void FrameT<S>::checkVector(const Vec3& v, const char* what) {
  if (!v.allFinite()) throw detail::makeError("Frame", "", what, v);
}

template <Scalar S>
void FrameT<S>::checkQuat(const Quat& q) {
  if (!isRotationQuaternion<S>(q))
    throw detail::makeError("Frame", "", "rotation must be a finite non-zero quaternion (x, y, z, w)", q.coeffs());
}

template <Scalar S>
void FrameT<S>::checkMatrix(const Transform& X) {
  if (!X.matrix().allFinite() || !isRotation<S>(X.linear()))
    throw detail::makeError("Frame", "", "transform must be finite with a rotation as linear part",
                            SPDMat3T<S>::flat(X.linear()));
}

SPOOK_COMPILED_ONCE(class, FrameT)

using Frame = FrameT<double>;
using FrameRef = ref_ptr<Frame>;
namespace f32 {
using Frame = FrameT<float>;
using FrameRef = ref_ptr<Frame>;
}  // namespace f32

}  // namespace spook
