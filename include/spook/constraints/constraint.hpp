#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <utility>

#include <spook/constraints/attachments.hpp>
#include <spook/core/error.hpp>
#include <spook/core/frame.hpp>
#include <spook/core/implementation.hpp>
#include <spook/core/math.hpp>
#include <spook/core/ref_ptr.hpp>
#include <spook/core/referenced.hpp>
#include <spook/dynamics/rigid_body.hpp>
#include <spook/solver/row.hpp>

namespace spook {

namespace detail {
struct SimulationMembership;
struct ConstraintAccess;
}  // namespace detail

/// A geometrical relation between a body and the world, or between two
/// bodies, held by rows with compliance and damping (seed 001 §12). Each body
/// carries an attachment frame; the constraint is relaxed when the two frames
/// coincide in the way the joint defines. A frame without a parent is fixed
/// to its body's model frame (or to the world for a missing second body) and
/// keeps its local transform; an attachment frame of the body is used as it
/// is. Position and orient the bodies before attaching them.
template <Scalar S>
class ConstraintT : public Referenced {
 public:
  using Vec3 = spook::Vec3T<S>;
  using Quat = spook::QuatT<S>;
  using Body = RigidBodyT<S>;
  using Frame = FrameT<S>;

  static constexpr SolveType DIRECT = SolveType::DIRECT;
  static constexpr SolveType ITERATIVE = SolveType::ITERATIVE;
  static constexpr SolveType DIRECT_AND_ITERATIVE = SolveType::DIRECT_AND_ITERATIVE;

  [[nodiscard]] const std::string& getName() const { return name_; }
  void setName(std::string name) { name_ = std::move(name); }
  /// The joint type, e.g. "Hinge".
  [[nodiscard]] const char* getKind() const { return kind_; }

  /// A disabled constraint adds no rows.
  [[nodiscard]] bool getEnable() const { return enable_; }
  void setEnable(bool enable) { enable_ = enable; }

  /// Whether the geometries of the two bodies collide with each other while
  /// this constraint is enabled. Default false: jointed bodies do not
  /// collide (a machine's links overlap at their pins), as with PhysX's
  /// joints and MuJoCo's parent–child filter. Other filters
  /// (Geometry::setEnableCollisions, groups) still apply when on. A body
  /// constrained to the world keeps colliding with static geometry.
  [[nodiscard]] bool getEnableCollisions() const { return enableCollisions_; }
  void setEnableCollisions(bool enable) { enableCollisions_ = enable; }

  /// Body 0 or 1 (nullptr for the world).
  [[nodiscard]] Body* getBodyAt(int index) const { return index == 0 ? body1_.get() : index == 1 ? body2_.get() : nullptr; }
  /// Attachment frame 0 or 1.
  [[nodiscard]] Frame* getAttachmentFrame(int index) const {
    return index == 0 ? frame1_.get() : index == 1 ? frame2_.get() : nullptr;
  }

  /// Degrees of freedom the joint removes (its DOF enum's NUM_DOF, seed 001 table 12.4).
  [[nodiscard]] virtual int getNumDOF() const = 0;

  /// Which solver handles the rows under the hybrid policy (default
  /// DIRECT_AND_ITERATIVE, as AGX's joints).
  [[nodiscard]] SolveType getSolveType() const { return solveType_; }
  void setSolveType(SolveType type);

  /// When on, the force and torque the constraint applied in the last step
  /// are kept for getLastForce (default off: costs a little per row).
  [[nodiscard]] bool getEnableComputeForces() const { return computeForces_; }
  void setEnableComputeForces(bool enable);
  /// The force (N) and torque (N·m) the constraint applied on body `index`
  /// (0 or 1) in the last step, in world coordinates. As AGX's getLastForce
  /// (seed 000), the torque is about the body's attachment point (its
  /// attachment frame origin) by default, and about its center of mass with
  /// giveForceAtCm true; the two differ by (c − p) × force. False (and zeros)
  /// when force computation is off or the index names no body.
  bool getLastForce(int index, Vec3& force, Vec3& torque, bool giveForceAtCm = false) const;
  /// As getLastForce(index, ...) for the constraint's body `body`; false for another body.
  bool getLastForce(const Body* body, Vec3& force, Vec3& torque, bool giveForceAtCm = false) const;

  /// Takes the current configuration as the relaxed one: frame 2 is moved
  /// onto frame 1 (seed 001 §12.16), and rest lengths and angles restart.
  void rebind();

  /// The simulation this constraint was added to, or nullptr.
  [[nodiscard]] const void* getSimulationHandle() const { return simulation_; }

  /// Frames at a world point with z along a world axis, one per body,
  /// expressed in each body's model frame (the world for body2 == nullptr):
  /// a relaxed configuration for any joint whose free axis is z.
  static void calculateFramesFromWorld(const Vec3& point, const Vec3& axis, const Body* body1, ref_ptr<Frame>& frame1,
                                       const Body* body2, ref_ptr<Frame>& frame2);
  /// A joint of type `Joint` at a world point with its z axis along a world
  /// axis (seed 001 §12.18), relaxed in the current configuration.
  template <class Joint>
  [[nodiscard]] static ref_ptr<Joint> createFromWorld(const Vec3& point, const Vec3& axis, Body* body1,
                                                      Body* body2 = nullptr);
  /// As createFromWorld with the point and axis in body1's model frame.
  template <class Joint>
  [[nodiscard]] static ref_ptr<Joint> createFromBody(const Vec3& point, const Vec3& axis, Body* body1,
                                                     Body* body2 = nullptr);

  /// As calculateFramesFromWorld with the point and axis given in body1's model frame.
  static void calculateFramesFromBody(const Vec3& point, const Vec3& axis, const Body* body1, ref_ptr<Frame>& frame1,
                                      const Body* body2, ref_ptr<Frame>& frame2);

 protected:
  ConstraintT(const char* kind, Body* body1, Frame* frame1, Body* body2, Frame* frame2);
  ~ConstraintT() override = default;

  /// Writes this step's rows; called once per step while enabled.
  virtual void addRows(const detail::Attachments& a, detail::RowSink& sink, double h) = 0;
  /// Writes the equality rows that post-stabilization projects onto the
  /// constraint manifold (joints: the elementary rows, unbounded locks and
  /// slack rows the step held at an end).
  virtual void addProjectionRows(const detail::Attachments& a, detail::RowSink& sink) {
    (void)a;
    (void)sink;
  }
  /// Called after the solve with the step length, to read back forces.
  virtual void afterSolve(double h) { (void)h; }
  virtual void onRebind() {}
  /// False for joints whose relaxed state is not coincident frames (DistanceJoint).
  [[nodiscard]] virtual bool rebindsFrames() const { return true; }

  template <class T>
  [[nodiscard]] Error error(const std::string& what, const T& value) const {
    return detail::makeError(kind_, name_, what, value);
  }

  /// The attachment frames and the bodies' state, in world coordinates.
  [[nodiscard]] detail::Attachments attachments() const;

 private:
  friend struct detail::SimulationMembership;
  friend struct detail::ConstraintAccess;

  static bool isMovable(const Body* body) { return body && body->getMotionControl() != Body::STATIC; }

  void checkParent(const Frame* frame, const Body* body, int index) const;
  static ref_ptr<Frame> attach(Frame* frame, Body* body);
  static ref_ptr<Frame> attachNew(Body* body);

  const char* kind_;
  std::string name_;
  bool enable_ = true;
  bool enableCollisions_ = false;
  SolveType solveType_ = SolveType::DIRECT_AND_ITERATIVE;
  bool computeForces_ = false;
  std::array<detail::Vec6d, 2> wrench_{detail::Vec6d::Zero(), detail::Vec6d::Zero()};
  ref_ptr<Body> body1_, body2_;
  ref_ptr<Frame> frame1_, frame2_;

  // Membership, maintained by the simulation.
  const void* simulation_ = nullptr;
  std::size_t simulationIndex_ = 0;
};

template <Scalar S>
void ConstraintT<S>::setSolveType(SolveType type) {
  if (type != DIRECT && type != ITERATIVE && type != DIRECT_AND_ITERATIVE)
    throw error("unknown solve type", static_cast<int>(type));
  solveType_ = type;
}

template <Scalar S>
void ConstraintT<S>::setEnableComputeForces(bool enable) {
  computeForces_ = enable;
  if (!enable) wrench_[0] = wrench_[1] = detail::Vec6d::Zero();
}

template <Scalar S>
bool ConstraintT<S>::getLastForce(int index, Vec3& force, Vec3& torque, bool giveForceAtCm) const {
  force = torque = Vec3::Zero();
  Body* body = getBodyAt(index);
  if (!computeForces_ || !body) return false;
  const detail::Vec6d& w = wrench_[static_cast<std::size_t>(index)];
  force = w.head<3>().template cast<S>();
  torque = w.tail<3>().template cast<S>();
  if (!giveForceAtCm) torque += (body->getCmPosition() - getAttachmentFrame(index)->getTranslate()).cross(force);
  return true;
}

template <Scalar S>
bool ConstraintT<S>::getLastForce(const Body* body, Vec3& force, Vec3& torque, bool giveForceAtCm) const {
  const int index = body && body == body1_.get() ? 0 : body && body == body2_.get() ? 1 : -1;
  if (index < 0) {
    force = torque = Vec3::Zero();
    return false;
  }
  return getLastForce(index, force, torque, giveForceAtCm);
}

template <Scalar S>
void ConstraintT<S>::rebind() {
  if (rebindsFrames()) frame2_->setMatrix(frame1_->getMatrix());
  onRebind();
}

template <Scalar S>
void ConstraintT<S>::calculateFramesFromWorld(const Vec3& point, const Vec3& axis, const Body* body1,
                                              ref_ptr<Frame>& frame1, const Body* body2, ref_ptr<Frame>& frame2) {
  if (!point.allFinite()) throw detail::makeError("Constraint", "", "frame point must be finite (m)", point);
  if (!axis.allFinite() || !(axis.norm() > S(0)))
    throw detail::makeError("Constraint", "", "frame axis must be finite and non-zero", axis);
  if (!body1) throw detail::makeError("Constraint", "", "calculateFrames needs a first body", "nullptr");
  const TransformT<S> world = makeTransform<S>(point, detail::shortestArc<S>(Vec3::UnitZ(), axis));
  frame1 = new Frame(TransformT<S>(body1->getTransform().inverse() * world));
  frame2 = new Frame(body2 ? TransformT<S>(body2->getTransform().inverse() * world) : world);
}

template <Scalar S>
template <class Joint>
ref_ptr<Joint> ConstraintT<S>::createFromWorld(const Vec3& point, const Vec3& axis, Body* body1, Body* body2) {
  ref_ptr<Frame> frame1, frame2;
  calculateFramesFromWorld(point, axis, body1, frame1, body2, frame2);
  return new Joint(body1, frame1.get(), body2, frame2.get());
}

template <Scalar S>
template <class Joint>
ref_ptr<Joint> ConstraintT<S>::createFromBody(const Vec3& point, const Vec3& axis, Body* body1, Body* body2) {
  ref_ptr<Frame> frame1, frame2;
  calculateFramesFromBody(point, axis, body1, frame1, body2, frame2);
  return new Joint(body1, frame1.get(), body2, frame2.get());
}

template <Scalar S>
void ConstraintT<S>::calculateFramesFromBody(const Vec3& point, const Vec3& axis, const Body* body1,
                                             ref_ptr<Frame>& frame1, const Body* body2, ref_ptr<Frame>& frame2) {
  if (!body1) throw detail::makeError("Constraint", "", "calculateFrames needs a first body", "nullptr");
  if (!point.allFinite()) throw detail::makeError("Constraint", "", "frame point must be finite (m)", point);
  if (!axis.allFinite()) throw detail::makeError("Constraint", "", "frame axis must be finite and non-zero", axis);
  const TransformT<S> X = body1->getTransform();
  calculateFramesFromWorld(X * point, X.linear() * axis, body1, frame1, body2, frame2);
}

template <Scalar S>
ConstraintT<S>::ConstraintT(const char* kind, Body* body1, Frame* frame1, Body* body2, Frame* frame2) : kind_(kind) {
  if (!body1) throw error("needs a first body (the second may be null: the world)", "nullptr");
  if (body1 == body2) throw error("cannot join a body to itself", body1->getName());
  if (!isMovable(body1) && !isMovable(body2))
    throw error("needs at least one body that is not static",
                body1->getName() + (body2 ? " and " + body2->getName() : std::string(" and the world")));
  checkParent(frame1, body1, 1);
  checkParent(frame2, body2, 2);
  body1_ = body1;
  body2_ = body2;
  frame1_ = attach(frame1, body1);
  if (frame2) {
    frame2_ = attach(frame2, body2);
  } else {
    // Relaxed at creation: frame 2 where frame 1 is now.
    frame2_ = new Frame();
    if (body2) frame2_->setParent(body2->getFrame());
    frame2_->setMatrix(frame1_->getMatrix());
  }
}

template <Scalar S>
detail::Attachments ConstraintT<S>::attachments() const {
  detail::Attachments a;
  const TransformT<S> X1 = frame1_->getMatrix(), X2 = frame2_->getMatrix();
  a.p1 = X1.translation().template cast<double>();
  a.p2 = X2.translation().template cast<double>();
  a.q1 = detail::Quatd(Quat(X1.linear()).template cast<double>()).normalized();
  a.q2 = detail::Quatd(Quat(X2.linear()).template cast<double>()).normalized();
  a.R1 = a.q1.toRotationMatrix();
  a.R2 = a.q2.toRotationMatrix();
  a.c1 = body1_->getCmPosition().template cast<double>();
  a.v1 = detail::linearAngular(body1_->getVelocity().template cast<double>(),
                               body1_->getAngularVelocity().template cast<double>());
  if (body2_) {
    a.c2 = body2_->getCmPosition().template cast<double>();
    a.v2 = detail::linearAngular(body2_->getVelocity().template cast<double>(),
                                 body2_->getAngularVelocity().template cast<double>());
  } else {
    a.c2 = a.p2;
  }
  return a;
}

template <Scalar S>
void ConstraintT<S>::checkParent(const Frame* frame, const Body* body, int index) const {
  if (frame && frame->getParent() && frame->getParent() != (body ? body->getFrame() : nullptr))
    throw error("attachment frame " + std::to_string(index) + " has a parent other than its body's model frame",
                body ? body->getName() : std::string("the world"));
}

template <Scalar S>
ref_ptr<FrameT<S>> ConstraintT<S>::attach(Frame* frame, Body* body) {
  if (!frame) return attachNew(body);
  if (!frame->getParent() && body) frame->setParent(body->getFrame());
  return frame;
}

template <Scalar S>
ref_ptr<FrameT<S>> ConstraintT<S>::attachNew(Body* body) {
  ref_ptr<Frame> frame = new Frame();
  if (body) frame->setParent(body->getFrame());
  return frame;
}

SPOOK_COMPILED_ONCE(class, ConstraintT)

namespace detail {
/// The simulation's access to a constraint's step hooks.
struct ConstraintAccess {
  template <Scalar S>
  static void addRows(ConstraintT<S>& c, RowSink& sink, double h) {
    Attachments a = c.attachments();
    a.h = h;
    c.addRows(a, sink, h);
  }
  template <Scalar S>
  static void addProjectionRows(ConstraintT<S>& c, RowSink& sink) {
    c.addProjectionRows(c.attachments(), sink);
  }
  template <Scalar S>
  static void afterSolve(ConstraintT<S>& c, double h) {
    c.afterSolve(h);
  }
  template <Scalar S>
  static void clearWrench(ConstraintT<S>& c) {
    c.wrench_[0] = c.wrench_[1] = Vec6d::Zero();
  }
  template <Scalar S>
  static void addWrench(ConstraintT<S>& c, const Row& row, double force) {
    c.wrench_[0] += row.J1 * force;
    c.wrench_[1] += row.J2 * force;
  }
};
}  // namespace detail

using Constraint = ConstraintT<double>;
using ConstraintRef = ref_ptr<Constraint>;
namespace f32 {
using Constraint = ConstraintT<float>;
using ConstraintRef = ref_ptr<Constraint>;
}  // namespace f32

}  // namespace spook
