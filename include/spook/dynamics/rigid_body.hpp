#pragma once

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <spook/collide/geometry.hpp>
#include <spook/core/error.hpp>
#include <spook/core/frame.hpp>
#include <spook/core/implementation.hpp>
#include <spook/core/math.hpp>
#include <spook/core/observer_ptr.hpp>
#include <spook/core/ref_ptr.hpp>
#include <spook/core/referenced.hpp>
#include <spook/dynamics/mass_from_geometries.hpp>
#include <spook/dynamics/mass_properties.hpp>

namespace spook {

template <Scalar S>
class SpaceT;
template <Scalar S>
class RigidBodyT;

namespace detail {
/// The continuous-collision stage of the step (detail::stopAtFirstContact
/// in collide/continuous.hpp), bound by the first
/// RigidBody::setEnableCCD(true) of a program, so that a program without
/// CCD bodies does not compile it; null until then.
template <Scalar S>
using CcdStage = void (*)(const std::vector<ref_ptr<RigidBodyT<S>>>& bodies, const SpaceT<S>& space, S h);
template <Scalar S>
inline std::atomic<CcdStage<S>> ccdStage{nullptr};

template <Scalar S>
struct BodyIntegrator;
struct SimulationMembership;
template <Scalar S>
struct BodySleep;
}  // namespace detail

/// A rigid body: a model frame (where the user places it), a center-of-mass
/// frame fixed in it, mass properties, and velocities of the center of mass
/// in world coordinates.
template <Scalar S>
class RigidBodyT : public Referenced, private detail::GeometryOwner<S> {
 public:
  using Vec3 = spook::Vec3T<S>;
  using Quat = spook::QuatT<S>;
  using Mat3 = spook::Mat3T<S>;
  using Transform = spook::TransformT<S>;
  using Frame = FrameT<S>;
  using Geometry = GeometryT<S>;

  enum MotionControl {
    DYNAMICS,   ///< moved by forces, gravity and (later) constraints
    STATIC,     ///< never moves; infinite mass; velocities read as zero
    KINEMATICS  ///< follows its set velocities (or moveTo), unaffected by forces
  };

  explicit RigidBodyT(std::string name = "") : name_(std::move(name)), massProperties_(&name_) {
    cmFrame_->setParent(frame_.get());
  }
  /// A body with one geometry, its mass properties generated from it (AGX's
  /// `new RigidBody(geometry)`). Throws as add() does: for a null geometry
  /// or one that belongs to a body or stands in a space.
  explicit RigidBodyT(ref_ptr<Geometry> geometry, std::string name = "") : RigidBodyT(std::move(name)) {
    add(std::move(geometry));
  }

  [[nodiscard]] const std::string& getName() const { return name_; }
  void setName(std::string name) { name_ = std::move(name); }

  /// A disabled body is not stepped and feels no gravity.
  [[nodiscard]] bool getEnable() const { return enable_; }
  void setEnable(bool enable) { enable_ = enable; }

  [[nodiscard]] MotionControl getMotionControl() const { return motionControl_; }
  [[nodiscard]] static const char* toString(MotionControl control);
  /// Switching to STATIC zeroes the velocities and cancels a moveTo.
  void setMotionControl(MotionControl control);

  /// Mass, inertia and added-mass coefficients. Changing them keeps the
  /// center-of-mass offset.
  [[nodiscard]] MassPropertiesT<S>* getMassProperties() { return &massProperties_; }
  [[nodiscard]] const MassPropertiesT<S>* getMassProperties() const { return &massProperties_; }

  // --- Pose -----------------------------------------------------------------

  /// The model frame: its world transform is the body's transform.
  [[nodiscard]] Frame* getFrame() const { return frame_.get(); }
  /// The center-of-mass frame, a child of the model frame.
  [[nodiscard]] Frame* getCmFrame() const { return cmFrame_.get(); }

  /// Model frame origin, world coordinates (m).
  [[nodiscard]] Vec3 getPosition() const { return frame_->getTranslate(); }
  void setPosition(const Vec3& p_W);
  void setPosition(S x, S y, S z) { setPosition(Vec3(x, y, z)); }

  /// Model frame orientation in world coordinates (normalized on set).
  [[nodiscard]] Quat getRotation() const { return frame_->getRotate(); }
  void setRotation(const Quat& q_W);

  /// Model frame to world transform.
  [[nodiscard]] Transform getTransform() const { return frame_->getMatrix(); }
  void setTransform(const Transform& X_W);

  /// Center of mass in world coordinates (m). Setting it moves the body.
  [[nodiscard]] Vec3 getCmPosition() const { return cmFrame_->getTranslate(); }
  void setCmPosition(const Vec3& p_W);
  /// Orientation of the center-of-mass frame in world coordinates.
  [[nodiscard]] Quat getCmRotation() const { return cmFrame_->getRotate(); }
  /// Center-of-mass frame to world transform.
  [[nodiscard]] Transform getCmTransform() const { return cmFrame_->getMatrix(); }

  /// Center-of-mass offset in the model frame (m); the model frame stays put.
  [[nodiscard]] const Vec3& getCmLocalTranslate() const { return cmFrame_->getLocalTranslate(); }
  /// Stops the offset from being generated from the geometries.
  void setCmLocalTranslate(const Vec3& offset);

  // --- Velocities (world coordinates, of the center of mass) ----------------

  /// Linear velocity of the center of mass (m/s). Zero for a static body.
  [[nodiscard]] const Vec3& getVelocity() const { return velocity_; }
  void setVelocity(const Vec3& v_W);
  void setVelocity(S x, S y, S z) { setVelocity(Vec3(x, y, z)); }

  /// Angular velocity (rad/s). Zero for a static body.
  [[nodiscard]] const Vec3& getAngularVelocity() const { return angularVelocity_; }
  void setAngularVelocity(const Vec3& w_W);
  void setAngularVelocity(S x, S y, S z) { setAngularVelocity(Vec3(x, y, z)); }

  /// Velocity of the body-fixed point currently at p_W (m/s).
  [[nodiscard]] Vec3 getVelocityAtPoint(const Vec3& p_W) const;

  // --- Forces (world coordinates; cleared after each step) -----------------

  /// Adds a force through the center of mass (N).
  void addForce(const Vec3& f_W);
  void addForce(S x, S y, S z) { addForce(Vec3(x, y, z)); }
  /// Adds a force (N) acting at world point p_W (m): a force and a torque about the CM.
  void addForceAtPosition(const Vec3& f_W, const Vec3& p_W);
  /// Adds a torque about the center of mass (N·m).
  void addTorque(const Vec3& t_W);
  void addTorque(S x, S y, S z) { addTorque(Vec3(x, y, z)); }
  /// Sum of the forces added since the last step (N).
  [[nodiscard]] const Vec3& getForce() const { return force_; }
  /// Sum of the torques about the CM added since the last step (N·m).
  [[nodiscard]] const Vec3& getTorque() const { return torque_; }

  // --- Velocity damping ------------------------------------------------------

  /// Linear velocity damping d (1/s) along the CM frame axes:
  /// dv/dt = −d v, stepped implicitly, v ← v / (1 + h d) per step.
  [[nodiscard]] const Vec3& getLinearVelocityDamping() const { return linearDamping_; }
  void setLinearVelocityDamping(const Vec3& d) { linearDamping_ = checkedDamping(d, "linear"); }
  void setLinearVelocityDamping(S d) { setLinearVelocityDamping(Vec3::Constant(d)); }
  /// Angular velocity damping d (1/s) about the CM frame axes, same law.
  [[nodiscard]] const Vec3& getAngularVelocityDamping() const { return angularDamping_; }
  void setAngularVelocityDamping(const Vec3& d) { angularDamping_ = checkedDamping(d, "angular"); }
  void setAngularVelocityDamping(S d) { setAngularVelocityDamping(Vec3::Constant(d)); }

  // --- Derived quantities ----------------------------------------------------

  /// Inertia tensor about the CM in world coordinates (kg·m²).
  [[nodiscard]] Mat3 getInertiaWorld() const;
  /// Linear momentum with the inertial (added) mass, world (kg·m/s).
  [[nodiscard]] Vec3 getLinearMomentum() const;
  /// Angular momentum about the CM, world (kg·m²/s).
  [[nodiscard]] Vec3 getAngularMomentum() const { return getInertiaWorld() * angularVelocity_; }
  /// Kinetic energy ½vᵀMv + ½ωᵀIω with the inertial mass (J).
  [[nodiscard]] S getKineticEnergy() const;

  // --- Continuous collision detection ---------------------------------------

  /// Off by default. When on, a dynamic body that moves more than its
  /// thinnest half-width in a step is swept along its path and stopped at
  /// its first contact instead of passing through (collide/continuous.hpp
  /// states what is covered and what is not).
  [[nodiscard]] bool getEnableCCD() const { return enableCCD_; }
  void setEnableCCD(bool enable);  // defined with the CCD stage, which it binds

  // --- Sleeping ----------------------------------------------------------------

  /// Asleep: the simulation's auto sleep (SimulationT::getAutoSleep) found
  /// its island at rest and no longer steps it. It wakes, with the bodies
  /// it touches or is jointed to, when an awake or moving body meets it, when
  /// a contact of its ends, when a joint is added or removed, when a row
  /// drives it (a motor given a speed), when it is moved or given a
  /// velocity, force or torque, or by wakeUp() (after changing a joint's
  /// other settings, e.g. a lock's position).
  [[nodiscard]] bool isSleeping() const { return sleeping_; }
  void wakeUp() {
    sleeping_ = false;
    restingTime_ = S(0);
  }

  // --- Kinematic control -----------------------------------------------------

  /// Sets, on a KINEMATICS body, the constant velocities that bring the
  /// model frame to `target` (world) after `duration` seconds, then stops it
  /// there. The velocities are re-aimed every step; the body lands exactly on
  /// the target at the step boundary nearest to `duration` (at least one step).
  void moveTo(const Transform& target, S duration);
  /// True while a moveTo is under way.
  [[nodiscard]] bool isMovingToTarget() const { return target_.has_value(); }

  // --- Geometries ------------------------------------------------------------

  /// Adds a geometry; its local transform is now relative to the model
  /// frame. Recomputes the generated mass properties. Throws, and adds
  /// nothing, if the geometry is null, belongs to a body, stands on its own
  /// in a space, or would make mass properties that are not finite and
  /// valid (e.g. a box whose mass or inertia overflows).
  void add(ref_ptr<Geometry> geometry);
  /// Removes a geometry (it keeps its local transform, now a world one);
  /// false when it is not this body's.
  bool remove(Geometry* geometry);
  [[nodiscard]] const std::vector<ref_ptr<Geometry>>& getGeometries() const { return geometries_; }
  /// The first geometry with this name, or nullptr.
  [[nodiscard]] Geometry* getGeometry(const std::string& name) const;

  /// Recomputes mass, center of mass and inertia from the geometries'
  /// shape volumes and material densities, for the properties still in the
  /// auto-generate mask (a hand-set mass scales the generated inertia). The
  /// model frame stays put; the center-of-mass velocity follows the new
  /// center so that no body point changes velocity. Nothing changes when no
  /// shape has volume. Throws, changing nothing, when the result would not
  /// be finite and valid (e.g. after a material's density was raised until
  /// the mass overflows).
  void updateMassProperties();

  // --- Attachments -----------------------------------------------------------

  /// Adds a named frame fixed in the body; its local transform is relative to
  /// the model frame. Throws if the name is taken or the frame already has a
  /// parent.
  void addAttachment(ref_ptr<Frame> frame, const std::string& name);
  /// The attachment called `name`, or nullptr.
  [[nodiscard]] Frame* getAttachment(const std::string& name) const;
  /// Removes an attachment; returns false when there is none by that name.
  bool removeAttachment(const std::string& name);

 protected:
  ~RigidBodyT() override;

 private:
  using Access = detail::GeometryAccess<S>;
  void checkGeometryChange(const detail::GeometryEdit<S>& edit) const override;
  void geometryChanged() override {
    updateMassProperties();
    wakeUp();  // its shapes may have moved under the contacts it slept on
  }

  // Generated mass properties, validated and ready to store.
  struct MassUpdate {
    S mass;               // kg
    SPDMat3T<S> inertia;  // CM frame (kg·m²)
    Vec3 center;          // generated center of mass, model frame (m)
  };
  // What updateMassProperties would store for `geometries` (with `edit`
  // applied); throws, naming the body or geometry and the value, when it
  // would not be finite and valid. Changes nothing.
  [[nodiscard]] std::optional<MassUpdate> planMassProperties(const std::vector<ref_ptr<Geometry>>& geometries,
                                                             const detail::GeometryEdit<S>& edit = {}) const;
  void applyMassProperties(const MassUpdate& update);

  friend struct detail::BodyIntegrator<S>;
  friend struct detail::SimulationMembership;
  friend struct detail::BodySleep<S>;

  struct KinematicTarget {
    Transform pose;
    S remaining;  // s
  };

  // Velocities that reach the target in `time`.
  void aimAtTarget(S time);

  template <class T>
  [[nodiscard]] Error error(const std::string& what, const T& value) const {
    return detail::makeError("RigidBody", name_, what, value);
  }
  void requireFinite(const Vec3& v, const char* what) const;
  void requireRotation(const Quat& q) const;
  void requireTransform(const Transform& X, const std::string& what) const;
  Vec3 checkedDamping(const Vec3& d, const char* kind) const;

  std::string name_;
  bool enable_ = true;
  bool enableCCD_ = false;
  MotionControl motionControl_ = DYNAMICS;
  ref_ptr<Frame> frame_ = new Frame();
  ref_ptr<Frame> cmFrame_ = new Frame();
  MassPropertiesT<S> massProperties_;
  Vec3 velocity_ = Vec3::Zero();
  Vec3 angularVelocity_ = Vec3::Zero();
  Vec3 force_ = Vec3::Zero();
  Vec3 torque_ = Vec3::Zero();
  Vec3 linearDamping_ = Vec3::Zero();
  Vec3 angularDamping_ = Vec3::Zero();
  std::optional<KinematicTarget> target_;
  bool sleeping_ = false;
  S restingTime_ = S(0);  ///< s below the auto sleep's thresholds
  Transform sleepPose_;   ///< the model frame when it fell asleep
  std::vector<std::pair<std::string, ref_ptr<Frame>>> attachments_;
  std::vector<ref_ptr<Geometry>> geometries_;

  // Membership, maintained by the simulation.
  const void* simulation_ = nullptr;
  std::size_t simulationIndex_ = 0;
};

template <Scalar S>
RigidBodyT<S>::~RigidBodyT() {
  for (auto& g : geometries_) {
    Access::body(*g) = nullptr;
    Access::owner(*g) = nullptr;
    g->getFrame()->setParent(nullptr);
  }
}

template <Scalar S>
const char* RigidBodyT<S>::toString(MotionControl control) {
  switch (control) {
    case DYNAMICS:
      return "DYNAMICS";
    case STATIC:
      return "STATIC";
    case KINEMATICS:
      return "KINEMATICS";
  }
  return "unknown";
}

template <Scalar S>
void RigidBodyT<S>::setMotionControl(MotionControl control) {
  if (control != DYNAMICS && control != STATIC && control != KINEMATICS)
    throw error("unknown motion control", static_cast<int>(control));
  motionControl_ = control;
  if (control != KINEMATICS) target_.reset();
  if (control == STATIC) velocity_ = angularVelocity_ = Vec3::Zero();
}

template <Scalar S>
void RigidBodyT<S>::setPosition(const Vec3& p_W) {
  requireFinite(p_W, "position must be finite (m)");
  frame_->setTranslate(p_W);
}

template <Scalar S>
void RigidBodyT<S>::setRotation(const Quat& q_W) {
  requireRotation(q_W);
  frame_->setRotate(q_W);
}

template <Scalar S>
void RigidBodyT<S>::setTransform(const Transform& X_W) {
  requireTransform(X_W, "transform");
  frame_->setMatrix(X_W);
}

template <Scalar S>
void RigidBodyT<S>::setCmPosition(const Vec3& p_W) {
  requireFinite(p_W, "center of mass position must be finite (m)");
  setPosition(p_W - getRotation() * getCmLocalTranslate());
}

template <Scalar S>
void RigidBodyT<S>::setCmLocalTranslate(const Vec3& offset) {
  requireFinite(offset, "center of mass offset must be finite (m)");
  cmFrame_->setLocalTranslate(offset);
  massProperties_.setAutoGenerateMask(massProperties_.getAutoGenerateMask() & ~unsigned(MassPropertiesT<S>::CM_OFFSET));
}

template <Scalar S>
void RigidBodyT<S>::setVelocity(const Vec3& v_W) {
  requireFinite(v_W, "velocity must be finite (m/s)");
  if (motionControl_ != STATIC) velocity_ = v_W;
}

template <Scalar S>
void RigidBodyT<S>::setAngularVelocity(const Vec3& w_W) {
  requireFinite(w_W, "angular velocity must be finite (rad/s)");
  if (motionControl_ != STATIC) angularVelocity_ = w_W;
}

template <Scalar S>
auto RigidBodyT<S>::getVelocityAtPoint(const Vec3& p_W) const -> Vec3 {
  return velocity_ + angularVelocity_.cross(p_W - getCmPosition());
}

template <Scalar S>
void RigidBodyT<S>::addForce(const Vec3& f_W) {
  requireFinite(f_W, "force must be finite (N)");
  force_ += f_W;
}

template <Scalar S>
void RigidBodyT<S>::addForceAtPosition(const Vec3& f_W, const Vec3& p_W) {
  requireFinite(f_W, "force must be finite (N)");
  requireFinite(p_W, "force position must be finite (m)");
  const Vec3 torque = (p_W - getCmPosition()).cross(f_W);
  requireFinite(torque, "torque of the force must be finite (N·m)");
  force_ += f_W;
  torque_ += torque;
}

template <Scalar S>
void RigidBodyT<S>::addTorque(const Vec3& t_W) {
  requireFinite(t_W, "torque must be finite (N·m)");
  torque_ += t_W;
}

template <Scalar S>
auto RigidBodyT<S>::getInertiaWorld() const -> Mat3 {
  const Mat3 R = getCmRotation().toRotationMatrix();
  return R * massProperties_.getInertiaTensor() * R.transpose();
}

template <Scalar S>
auto RigidBodyT<S>::getLinearMomentum() const -> Vec3 {
  const Mat3 R = getCmRotation().toRotationMatrix();
  return R * massProperties_.getEffectiveMass().cwiseProduct(R.transpose() * velocity_);
}

template <Scalar S>
S RigidBodyT<S>::getKineticEnergy() const {
  return S(0.5) * (velocity_.dot(getLinearMomentum()) + angularVelocity_.dot(getAngularMomentum()));
}

template <Scalar S>
void RigidBodyT<S>::moveTo(const Transform& target, S duration) {
  if (motionControl_ != KINEMATICS) throw error("moveTo needs motion control KINEMATICS", toString(motionControl_));
  if (!(std::isfinite(duration) && duration > S(0))) throw error("moveTo duration must be finite and > 0 s", duration);
  requireTransform(target, "moveTo target");
  target_ = KinematicTarget{target, duration};
  aimAtTarget(duration);
}

template <Scalar S>
void RigidBodyT<S>::add(ref_ptr<Geometry> geometry) {
  if (!geometry) throw error("cannot add a null Geometry", "nullptr");
  if (geometry->getRigidBody() == this) throw error("Geometry already added to this body", geometry->getName());
  if (geometry->getRigidBody()) throw error("Geometry already belongs to another body", geometry->getName());
  if (Access::space(*geometry)) throw error("Geometry is in a space on its own; remove it first", geometry->getName());
  std::vector<ref_ptr<Geometry>> geometries = geometries_;
  geometries.push_back(geometry);
  const auto update = planMassProperties(geometries);
  geometry->getFrame()->setParent(frame_.get());
  Access::body(*geometry) = this;
  Access::owner(*geometry) = this;
  geometries_ = std::move(geometries);
  if (update) applyMassProperties(*update);
}

template <Scalar S>
bool RigidBodyT<S>::remove(Geometry* geometry) {
  const auto it = std::find_if(geometries_.begin(), geometries_.end(), [&](const auto& g) { return g == geometry; });
  if (it == geometries_.end()) return false;
  ref_ptr<Geometry> keep = *it;
  geometries_.erase(it);
  Access::body(*keep) = nullptr;
  Access::owner(*keep) = nullptr;
  keep->getFrame()->setParent(nullptr);
  updateMassProperties();
  return true;
}

template <Scalar S>
auto RigidBodyT<S>::getGeometry(const std::string& name) const -> Geometry* {
  for (const auto& g : geometries_)
    if (g->getName() == name) return g.get();
  return nullptr;
}

template <Scalar S>
void RigidBodyT<S>::updateMassProperties() {
  if (const auto update = planMassProperties(geometries_)) applyMassProperties(*update);
}

template <Scalar S>
void RigidBodyT<S>::addAttachment(ref_ptr<Frame> frame, const std::string& name) {
  if (!frame) throw error("attachment frame must not be null", name);
  if (getAttachment(name)) throw error("attachment name already used", name);
  if (frame->getParent()) throw error("attachment frame already has a parent", name);
  frame->setParent(frame_.get());
  attachments_.emplace_back(name, std::move(frame));
}

template <Scalar S>
auto RigidBodyT<S>::getAttachment(const std::string& name) const -> Frame* {
  for (const auto& [key, frame] : attachments_)
    if (key == name) return frame.get();
  return nullptr;
}

template <Scalar S>
bool RigidBodyT<S>::removeAttachment(const std::string& name) {
  for (auto it = attachments_.begin(); it != attachments_.end(); ++it)
    if (it->first == name) {
      it->second->setParent(nullptr);
      attachments_.erase(it);
      return true;
    }
  return false;
}

template <Scalar S>
void RigidBodyT<S>::checkGeometryChange(const detail::GeometryEdit<S>& edit) const {
  static_cast<void>(planMassProperties(geometries_, edit));
}

template <Scalar S>
void RigidBodyT<S>::applyMassProperties(const MassUpdate& update) {
  massProperties_.generate(update.mass, update.inertia);
  if (massProperties_.getAutoGenerateMask() & MassPropertiesT<S>::CM_OFFSET) {
    const Vec3 oldCm = getCmPosition();
    cmFrame_->setLocalTranslate(update.center);
    velocity_ += angularVelocity_.cross(getCmPosition() - oldCm);
  }
}

template <Scalar S>
void RigidBodyT<S>::aimAtTarget(S time) {
  const Vec3 cmTarget = target_->pose * getCmLocalTranslate();
  velocity_ = (cmTarget - getCmPosition()) / time;
  const Quat qTarget(target_->pose.linear());
  angularVelocity_ = logRotation<S>(qTarget * getRotation().conjugate()) / time;
}

template <Scalar S>
void RigidBodyT<S>::requireFinite(const Vec3& v, const char* what) const {
  if (!v.allFinite()) throw error(what, v);
}

template <Scalar S>
void RigidBodyT<S>::requireRotation(const Quat& q) const {
  if (!isRotationQuaternion<S>(q))
    throw error("rotation must be a finite non-zero quaternion (x, y, z, w)", q.coeffs());
}

template <Scalar S>
void RigidBodyT<S>::requireTransform(const Transform& X, const std::string& what) const {
  requireFinite(Vec3(X.translation()), (what + " translation must be finite (m)").c_str());
  if (!isRotation<S>(X.linear()))
    throw error(what + " rotation must be orthonormal and right-handed", SPDMat3T<S>::flat(X.linear()));
}

template <Scalar S>
auto RigidBodyT<S>::checkedDamping(const Vec3& d, const char* kind) const -> Vec3 {
  if (!(d.allFinite() && d.minCoeff() >= S(0)))
    throw error(std::string(kind) + " velocity damping must be finite and >= 0 (1/s)", d);
  return d;
}

// Generating mass from geometries is defined outside the class (not inline):
// with SPOOK_EXTERN_TEMPLATES it is compiled once, with the simulation
// (core/implementation.hpp), not in every file that makes a body.
template <Scalar S>
auto RigidBodyT<S>::planMassProperties(const std::vector<ref_ptr<Geometry>>& geometries,
                                       const detail::GeometryEdit<S>& edit) const -> std::optional<MassUpdate> {
  const auto generated = detail::massFromGeometries<S>(geometries, name_, edit);
  if (!generated) return std::nullopt;
  const unsigned mask = massProperties_.getAutoGenerateMask();
  const S mass = (mask & MassPropertiesT<S>::MASS) ? generated->mass : massProperties_.getMass();
  Mat3 inertia = generated->inertia * (mass / generated->mass);
  if (!(mask & MassPropertiesT<S>::CM_OFFSET)) {
    // About the user's center instead of the generated one.
    const Vec3 d = getCmLocalTranslate() - generated->center;
    inertia += mass * (d.squaredNorm() * Mat3::Identity() - d * d.transpose());
  }
  // The tensor is stored in the CM frame, whose axes are the model axes
  // turned by the CM frame's local rotation.
  const Mat3 R = cmFrame_->getLocalRotate().toRotationMatrix();
  const Mat3 inertiaCm = R.transpose() * inertia * R;
  if (const char* why = SPDMat3T<S>::defect(inertiaCm))
    throw error(std::string("inertia generated from the geometries (kg·m²): ") + why, SPDMat3T<S>::flat(inertiaCm));
  return MassUpdate{mass, SPDMat3T<S>(inertiaCm), generated->center};
}

SPOOK_COMPILED_ONCE(class, RigidBodyT)

using RigidBody = RigidBodyT<double>;
using RigidBodyRef = ref_ptr<RigidBody>;
using RigidBodyObserver = observer_ptr<RigidBody>;
namespace f32 {
using RigidBody = RigidBodyT<float>;
using RigidBodyRef = ref_ptr<RigidBody>;
using RigidBodyObserver = observer_ptr<RigidBody>;
}  // namespace f32

}  // namespace spook
