#pragma once

#include <unordered_set>
#include <vector>

#include <spook/core/frame.hpp>
#include <spook/core/implementation.hpp>
#include <spook/sim/collection.hpp>

namespace spook {

/// A collection with a frame: moving the assembly moves its content rigidly
/// (positions, orientations, and the direction of velocities) and the frames
/// of nested assemblies. Adding an object does not move it.
template <Scalar S>
class AssemblyT : public CollectionT<S> {
 public:
  using Vec3 = spook::Vec3T<S>;
  using Quat = spook::QuatT<S>;
  using Transform = spook::TransformT<S>;

  explicit AssemblyT(std::string name = "") : CollectionT<S>(std::move(name)) {}

  /// The assembly's frame (world).
  [[nodiscard]] FrameT<S>* getFrame() const { return frame_.get(); }

  /// Assembly origin, world (m).
  [[nodiscard]] Vec3 getPosition() const { return frame_->getTranslate(); }
  void setPosition(const Vec3& p_W);
  /// Assembly orientation, world.
  [[nodiscard]] Quat getRotation() const { return frame_->getRotate(); }
  void setRotation(const Quat& q_W);
  [[nodiscard]] Transform getTransform() const { return frame_->getMatrix(); }
  void setTransform(const Transform& X_W);

 protected:
  ~AssemblyT() override = default;

  void gatherMovable(std::vector<RigidBodyT<S>*>& bodies, std::vector<FrameT<S>*>& frames,
                     std::unordered_set<const void*>& seen) const override;
  [[nodiscard]] const char* kind() const override { return "Assembly"; }

 private:
  ref_ptr<FrameT<S>> frame_ = new FrameT<S>();
};

template <Scalar S>
void AssemblyT<S>::setPosition(const Vec3& p_W) {
  if (!p_W.allFinite()) throw this->error("position must be finite (m)", p_W);
  setTransform(makeTransform<S>(p_W, getRotation()));
}

template <Scalar S>
void AssemblyT<S>::setRotation(const Quat& q_W) {
  if (!isRotationQuaternion<S>(q_W))
    throw this->error("rotation must be a finite non-zero quaternion (x, y, z, w)", q_W.coeffs());
  setTransform(makeTransform<S>(getPosition(), q_W));
}

template <Scalar S>
void AssemblyT<S>::setTransform(const Transform& X_W) {
  if (!X_W.matrix().allFinite() || !isRotation<S>(X_W.linear()))
    throw this->error("transform must be finite with a rotation as linear part", X_W.translation());
  const Transform delta = makeTransform<S>(X_W.translation(), Quat(X_W.linear())) * frame_->getMatrix().inverse();
  const Quat turn(delta.linear());
  std::vector<RigidBodyT<S>*> bodies;
  std::vector<FrameT<S>*> frames;
  std::unordered_set<const void*> seen;
  this->gatherMovable(bodies, frames, seen);
  for (FrameT<S>* frame : frames) frame->setMatrix(delta * frame->getMatrix());
  for (RigidBodyT<S>* body : bodies) {
    body->setTransform(delta * body->getTransform());
    body->setVelocity(turn * body->getVelocity());
    body->setAngularVelocity(turn * body->getAngularVelocity());
  }
}

template <Scalar S>
void AssemblyT<S>::gatherMovable(std::vector<RigidBodyT<S>*>& bodies, std::vector<FrameT<S>*>& frames,
                                 std::unordered_set<const void*>& seen) const {
  if (seen.insert(frame_.get()).second) frames.push_back(frame_.get());
  CollectionT<S>::gatherMovable(bodies, frames, seen);
}

SPOOK_COMPILED_ONCE(class, AssemblyT)

using Assembly = AssemblyT<double>;
using AssemblyRef = ref_ptr<Assembly>;
namespace f32 {
using Assembly = AssemblyT<float>;
using AssemblyRef = ref_ptr<Assembly>;
}  // namespace f32

}  // namespace spook
