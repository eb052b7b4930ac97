#pragma once

#include <spook/core/frame.hpp>
#include <spook/sim/collection.hpp>

namespace spook {

/// A collection with a frame: moving the assembly moves its content rigidly
/// (positions, orientations, and the direction of velocities) and the frames
/// of nested assemblies. Adding an object does not move it.
template <Scalar S>
class AssemblyT : public CollectionT<S> {
 public:
  using Vec3 = spook::Vec3<S>;
  using Quat = spook::Quat<S>;
  using Transform = spook::Transform<S>;

  explicit AssemblyT(std::string name = "") : CollectionT<S>(std::move(name)) {}

  /// The assembly's frame (world).
  [[nodiscard]] FrameT<S>* getFrame() const { return frame_.get(); }

  /// Assembly origin, world (m).
  [[nodiscard]] Vec3 getPosition() const { return frame_->getTranslate(); }
  void setPosition(const Vec3& p_W) {
    if (!p_W.allFinite()) throw this->error("position must be finite (m)", p_W);
    setTransform(makeTransform<S>(p_W, getRotation()));
  }
  /// Assembly orientation, world.
  [[nodiscard]] Quat getRotation() const { return frame_->getRotate(); }
  void setRotation(const Quat& q_W) {
    if (!q_W.coeffs().allFinite() || !(q_W.norm() > S(0)))
      throw this->error("rotation must be a finite non-zero quaternion (x, y, z, w)", q_W.coeffs());
    setTransform(makeTransform<S>(getPosition(), q_W));
  }
  [[nodiscard]] Transform getTransform() const { return frame_->getMatrix(); }
  void setTransform(const Transform& X_W) {
    if (!X_W.matrix().allFinite()) throw this->error("transform must be finite", X_W.translation());
    const Transform normalized = makeTransform<S>(X_W.translation(), Quat(X_W.linear()));
    this->applyTransform(normalized * frame_->getMatrix().inverse());
  }

 protected:
  ~AssemblyT() override = default;

  void applyTransform(const Transform& delta) override {
    frame_->setMatrix(delta * frame_->getMatrix());
    CollectionT<S>::applyTransform(delta);
  }
  [[nodiscard]] const char* kind() const override { return "Assembly"; }

 private:
  ref_ptr<FrameT<S>> frame_ = new FrameT<S>();
};

using Assembly = AssemblyT<double>;
using AssemblyRef = ref_ptr<Assembly>;
namespace f32 {
using Assembly = AssemblyT<float>;
using AssemblyRef = ref_ptr<Assembly>;
}  // namespace f32

}  // namespace spook
