#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <string>

#include <spook/constraints/joints/cylindrical_joint.hpp>
#include <spook/constraints/joints/dot1_joint.hpp>
#include <spook/constraints/joints/slack_joints.hpp>
#include <spook/constraints/joints/universal_joint.hpp>
#include <spook/constraints/joints/wheel_joint.hpp>

#include "joint_scenes.hpp"
#include "tolerance.hpp"

using namespace spook;
using spook::test::frameAt;
using spook::test::makeBody;
using spook::test::pick;

namespace {

// Constrained-DOF violations measured from the attachment frames alone, so
// the test does not trust the rows it checks.
template <class S>
struct FramePair {
  Vec3T<double> p1, p2;
  Eigen::Matrix3d R1, R2;
  explicit FramePair(const ConstraintT<S>& c) {
    const TransformT<S> X1 = c.getAttachmentFrame(0)->getMatrix(), X2 = c.getAttachmentFrame(1)->getMatrix();
    p1 = X1.translation().template cast<double>();
    p2 = X2.translation().template cast<double>();
    R1 = X1.linear().template cast<double>();
    R2 = X2.linear().template cast<double>();
  }
  [[nodiscard]] double separation() const { return (p1 - p2).norm(); }
  [[nodiscard]] double offAxis() const {  // separation across z of frame 2
    const Vec3T<double> d = p1 - p2;
    return std::hypot(d.dot(R2.col(0)), d.dot(R2.col(1)));
  }
  [[nodiscard]] double tilt() const { return std::hypot(R1.col(0).dot(R2.col(2)), R1.col(1).dot(R2.col(2))); }
  [[nodiscard]] double rotation() const {
    return Eigen::AngleAxisd(Eigen::Matrix3d(R2.transpose() * R1)).angle();
  }
  [[nodiscard]] double outOfPlane() const { return std::abs((p1 - p2).dot(R2.col(2))); }
  [[nodiscard]] double crossTilt() const { return std::abs(R1.col(0).dot(R2.col(1))); }  // Dot1<0, 1>
  [[nodiscard]] double axleTilt() const { return std::abs(R1.col(1).dot(R2.col(2))); }   // Dot1<1, 2>
  // The slack joints' DOFs (rows/slack.hpp): separation along axis k of frame
  // 2 (m), tilt of z₁ about x₂ or y₂ and rotation about axis k of frame 2 (rad).
  [[nodiscard]] double along(int k) const { return (p1 - p2).dot(R2.col(k)); }
  [[nodiscard]] double tiltAbout(int k) const {
    const Vec3T<double> z1 = R1.col(2);
    return k == 0 ? std::atan2(-z1.dot(R2.col(1)), z1.dot(R2.col(2)))
                  : std::atan2(z1.dot(R2.col(0)), z1.dot(R2.col(2)));
  }
  [[nodiscard]] double rotationAbout(int k) const {
    Eigen::Quaterniond q(Eigen::Matrix3d(R2.transpose() * R1));
    if (q.w() < 0.0) q.coeffs() = -q.coeffs();
    return 2.0 * std::atan2(q.vec()[k], q.w());
  }
};

// How far a slack DOF x is beyond its slack [−slack, slack] (m or rad);
// negative inside it.
double beyond(double x, double slack) { return std::abs(x) - slack; }

// One body hung from the world and one from it, both perturbed, 10 s at
// 60 Hz under gravity, direct solver, default compliance 1e-8: the worst
// violation of the constrained DOFs from 1 s on. The perturbing velocities
// break the constraints' velocity conditions; SPOOK removes that over a few
// damping times τ = 2/60 s (PHYSICS.md §1.2), a transient of ~1e-3 m that is
// over well before 1 s. The loads (≤ 30 N on the upper joint) deflect the
// rows by ≤ 3e-7 m at that compliance.
struct Measured {
  double worst = 0.0;  ///< worst violation from 1 s on (m or rad); < 0: slack DOFs all inside their slack
  double reach = 0.0;  ///< farthest body center from the origin at the end (m)
};

template <class S, class Joint>
Measured worstViolation(const std::function<ref_ptr<Joint>(RigidBodyT<S>*, RigidBodyT<S>*)>& make,
                      const std::function<double(const FramePair<S>&)>& violation, bool postStabilize) {
  ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
  ref_ptr<DirectSolver> solver = new DirectSolver();
  solver->setEnablePostStabilization(postStabilize);
  sim->setSolver(solver);
  auto upper = makeBody<S>(*sim, "upper", S(2), Vec3T<S>(S(0.5), 0, 0), S(0.05));
  auto lower = makeBody<S>(*sim, "lower", S(1), Vec3T<S>(S(0.5), 0, S(-1)), S(0.02));
  ref_ptr<Joint> top = make(upper.get(), nullptr);
  ref_ptr<Joint> bottom = make(lower.get(), upper.get());
  sim->add(top);
  sim->add(bottom);
  upper->setVelocity(S(0.2), S(-0.1), S(0.3));
  upper->setAngularVelocity(S(0.3), S(0.2), S(-0.4));
  lower->setVelocity(S(-0.1), S(0.3), S(0));
  lower->setAngularVelocity(S(0.1), S(0.5), S(0.2));
  double worst = -std::numeric_limits<double>::infinity();
  for (int i = 0; i < 600; ++i) {
    sim->stepForward();
    if (i >= 60) worst = std::max({worst, violation(FramePair<S>(*top)), violation(FramePair<S>(*bottom))});
  }
  return {worst, std::max(double(upper->getPosition().norm()), double(lower->getPosition().norm()))};
}

// The joint at the upper end of each body (0.5 m above its center) with its
// z axis along `axis`.
template <class S, class Joint>
std::function<ref_ptr<Joint>(RigidBodyT<S>*, RigidBodyT<S>*)> jointAbove(const Vec3T<S>& axis) {
  return [axis](RigidBodyT<S>* b1, RigidBodyT<S>* b2) {
    ref_ptr<FrameT<S>> f1, f2;
    ConstraintT<S>::calculateFramesFromWorld(b1->getPosition() + Vec3T<S>(0, 0, S(0.5)), axis, b1, f1, b2, f2);
    return ref_ptr<Joint>(new Joint(b1, f1.get(), b2, f2.get()));
  };
}

// The same for a slack joint with `positional` (m) and `rotational` (rad)
// slack.
template <class S, class Joint>
std::function<ref_ptr<Joint>(RigidBodyT<S>*, RigidBodyT<S>*)> slackJointAbove(const Vec3T<S>& axis, double positional,
                                                                              double rotational) {
  return [=](RigidBodyT<S>* b1, RigidBodyT<S>* b2) {
    ref_ptr<Joint> joint = jointAbove<S, Joint>(axis)(b1, b2);
    joint->setSlackParameters(S(positional), S(rotational));
    return joint;
  };
}

template <class S, class Joint>
Measured checkJoint(const std::string& name, const std::function<ref_ptr<Joint>(RigidBodyT<S>*, RigidBodyT<S>*)>& make,
                    const std::function<double(const FramePair<S>&)>& violation) {
  // The target for every joint: 1e-6. Float stores positions with a
  // spacing of 6e-8·r at r meters, so for bodies that slide or fall far
  // (hundreds of meters in 10 s) its tolerance grows as 1e-6·r.
  const Measured projected = worstViolation<S, Joint>(make, violation, true);
  const Measured plain = worstViolation<S, Joint>(make, violation, false);
  const double tol = pick<S>(1e-6, 1e-6 * std::max(1.0, projected.reach));
  MESSAGE(name << " worst violation " << projected.worst << " (without post-stabilization " << plain.worst
               << "), bodies within " << projected.reach << " m");
  CHECK(projected.worst < tol);
  // SPOOK alone leaves the step's second-order drift, ~h²ω²L, held at
  // ~1e-4..1e-2 m by its stabilization.
  CHECK(plain.worst < 2e-2);
  return projected;
}

// A slack joint, whose violation is how far its DOFs go beyond their slack:
// some DOF must also be held at its end after 1 s, or the check is empty.
template <class S, class Joint>
void checkSlackJoint(const std::string& name, const std::function<ref_ptr<Joint>(RigidBodyT<S>*, RigidBodyT<S>*)>& make,
                     const std::function<double(const FramePair<S>&)>& excess) {
  CHECK(checkJoint<S, Joint>(name, make, excess).worst > -1e-6);
}

}  // namespace

// Axes: tilted so that gravity loads the rotational rows of the hinge-like
// joints; horizontal for the sliding joints (whose bodies would otherwise
// slide hundreds of meters in 10 s, beyond float's 1e-6 m resolution);
// vertical for the plane (the bodies slide in it, gravity on its normal).
TEST_CASE_TEMPLATE("every joint holds its constrained DOFs within 1e-6 when post-stabilized", S, float, double) {
  const Vec3T<S> tilted = Vec3T<S>(1, 0, 1).normalized(), horizontal = Vec3T<S>(1, 1, 0).normalized(), up = Vec3T<S>::UnitZ();
  using F = FramePair<S>;
  SUBCASE("Hinge") {
    checkJoint<S, HingeT<S>>("Hinge", jointAbove<S, HingeT<S>>(tilted),
                             [](const F& f) { return std::max(f.separation(), f.tilt()); });
  }
  SUBCASE("BallJoint") {
    checkJoint<S, BallJointT<S>>("BallJoint", jointAbove<S, BallJointT<S>>(tilted),
                                 [](const F& f) { return f.separation(); });
  }
  SUBCASE("Prismatic") {
    checkJoint<S, PrismaticT<S>>("Prismatic", jointAbove<S, PrismaticT<S>>(horizontal),
                                 [](const F& f) { return std::max(f.offAxis(), f.rotation()); });
  }
  SUBCASE("LockJoint") {
    checkJoint<S, LockJointT<S>>("LockJoint", jointAbove<S, LockJointT<S>>(tilted),
                                 [](const F& f) { return std::max(f.separation(), f.rotation()); });
  }
  SUBCASE("AngularLockJoint") {
    checkJoint<S, AngularLockJointT<S>>("AngularLockJoint", jointAbove<S, AngularLockJointT<S>>(tilted),
                                        [](const F& f) { return f.rotation(); });
  }
  SUBCASE("CylindricalJoint") {
    checkJoint<S, CylindricalJointT<S>>("CylindricalJoint", jointAbove<S, CylindricalJointT<S>>(horizontal),
                                        [](const F& f) { return std::max(f.offAxis(), f.tilt()); });
  }
  SUBCASE("UniversalJoint") {
    checkJoint<S, UniversalJointT<S>>("UniversalJoint", jointAbove<S, UniversalJointT<S>>(tilted),
                                      [](const F& f) { return std::max(f.separation(), f.crossTilt()); });
  }
  SUBCASE("PrismaticUniversalJoint") {
    checkJoint<S, PrismaticUniversalJointT<S>>("PrismaticUniversalJoint",
                                               jointAbove<S, PrismaticUniversalJointT<S>>(horizontal),
                                               [](const F& f) { return std::max(f.offAxis(), f.crossTilt()); });
  }
  SUBCASE("PlaneJoint") {
    checkJoint<S, PlaneJointT<S>>("PlaneJoint", jointAbove<S, PlaneJointT<S>>(up),
                                  [](const F& f) { return f.outOfPlane(); });
  }
  SUBCASE("Dot1Joint") {
    checkJoint<S, Dot1JointT<S>>("Dot1Joint", jointAbove<S, Dot1JointT<S>>(tilted),
                                 [](const F& f) { return f.crossTilt(); });
  }
  SUBCASE("DistanceJoint") {
    // Anchored 0.7 m above the joint point.
    checkJoint<S, DistanceJointT<S>>(
        "DistanceJoint",
        [](RigidBodyT<S>* b1, RigidBodyT<S>* b2) {
          const Vec3T<S> up(0, 0, S(0.5));
          ref_ptr<FrameT<S>> f1 = frameAt<S>(up);
          const Vec3T<S> anchor = b1->getPosition() + up + Vec3T<S>(0, 0, S(0.7));
          if (b2) {
            ref_ptr<FrameT<S>> f2 = frameAt<S>(Vec3T<S>(anchor - b2->getPosition()));
            return ref_ptr<DistanceJointT<S>>(new DistanceJointT<S>(b1, f1.get(), b2, f2.get()));
          }
          return ref_ptr<DistanceJointT<S>>(new DistanceJointT<S>(b1, f1.get(), anchor));
        },
        [](const F& f) { return std::abs(f.separation() - 0.7); });
  }
  SUBCASE("WheelJoint") {
    // The suspension is locked at creation: the wheel's frame stays at the
    // pivot, its axle perpendicular to the steering axis.
    checkJoint<S, WheelJointT<S>>("WheelJoint", jointAbove<S, WheelJointT<S>>(tilted),
                                  [](const F& f) { return std::max(f.separation(), f.axleTilt()); });
  }
  // Slack: 1 cm and 0.02 rad, taken up in the first second, after which
  // gravity holds DOFs at their ends. The sliding joints get 2 mrad: their
  // axes tilt by the rotational slack, the bodies slide apart along them, and
  // the lower one's weight on that growing lever bends the upper joint by
  // compliance × torque (2e-7 rad, 2.7 m apart, at 2 mrad; 1.4e-6 rad, 20 m
  // apart, at 0.02 rad).
  const double cm = 0.01, rad = 0.02, sliding = 0.002;
  SUBCASE("SlackHingeJoint") {
    checkSlackJoint<S, SlackHingeJointT<S>>(
        "SlackHingeJoint", slackJointAbove<S, SlackHingeJointT<S>>(tilted, cm, rad), [=](const F& f) {
          return std::max({beyond(f.along(0), cm), beyond(f.along(1), cm), beyond(f.along(2), cm),
                           beyond(f.tiltAbout(0), rad), beyond(f.tiltAbout(1), rad)});
        });
  }
  SUBCASE("SlackPrismaticJoint") {
    checkSlackJoint<S, SlackPrismaticJointT<S>>(
        "SlackPrismaticJoint", slackJointAbove<S, SlackPrismaticJointT<S>>(horizontal, cm, sliding), [=](const F& f) {
          return std::max({beyond(f.along(0), cm), beyond(f.along(1), cm), beyond(f.rotationAbout(0), sliding),
                           beyond(f.rotationAbout(1), sliding), beyond(f.rotationAbout(2), sliding)});
        });
  }
  SUBCASE("SlackLockJoint") {
    checkSlackJoint<S, SlackLockJointT<S>>(
        "SlackLockJoint", slackJointAbove<S, SlackLockJointT<S>>(tilted, cm, rad), [=](const F& f) {
          return std::max({beyond(f.along(0), cm), beyond(f.along(1), cm), beyond(f.along(2), cm),
                           beyond(f.rotationAbout(0), rad), beyond(f.rotationAbout(1), rad),
                           beyond(f.rotationAbout(2), rad)});
        });
  }
  SUBCASE("SlackCylindricalJoint") {
    checkSlackJoint<S, SlackCylindricalJointT<S>>(
        "SlackCylindricalJoint", slackJointAbove<S, SlackCylindricalJointT<S>>(horizontal, cm, sliding),
        [=](const F& f) {
          return std::max({beyond(f.along(0), cm), beyond(f.along(1), cm), beyond(f.tiltAbout(0), sliding),
                           beyond(f.tiltAbout(1), sliding)});
        });
  }
}

TEST_CASE_TEMPLATE("post-stabilization holds a 90° pendulum to 1e-6 without taking its energy", S, float, double) {
  // A 2 kg bob on a 1 m hinge arm released horizontally, 10 s at 60 Hz: the
  // fastest swing of the catalogue (ω up to 4.4 rad/s, tension 3mg = 59 N,
  // which the default compliance 1e-8 turns into 5.9e-7 m).
  struct Run {
    double worstGap = 0.0, energyChange = 0.0;  // energy relative to m·g·L
  };
  const auto run = [](bool postStabilize) {
    ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
    ref_ptr<DirectSolver> solver = new DirectSolver();
    solver->setEnablePostStabilization(postStabilize);
    sim->setSolver(solver);
    auto bob = makeBody<S>(*sim, "bob", S(2), Vec3T<S>(S(1), 0, 0), S(0.05));
    ref_ptr<HingeT<S>> hinge = new HingeT<S>(bob.get(), frameAt<S>(Vec3T<S>(-1, 0, 0), Vec3T<S>::UnitY()).get());
    sim->add(hinge);
    const auto energy = [&] {
      return double(bob->getKineticEnergy()) + 2.0 * 9.80665 * double(bob->getCmPosition().z());
    };
    const double E0 = energy();
    Run r;
    for (int i = 0; i < 600; ++i) {
      sim->stepForward();
      r.worstGap = std::max(r.worstGap, FramePair<S>(*hinge).separation());
    }
    r.energyChange = (energy() - E0) / (2.0 * 9.80665);
    return r;
  };
  const Run projected = run(true), plain = run(false);
  MESSAGE("90° pendulum: worst gap " << projected.worstGap << " m (without post-stabilization " << plain.worstGap
                                     << "), energy change " << projected.energyChange << " of m·g·L (without "
                                     << plain.energyChange << ")");
  CHECK(projected.worstGap < 1e-6);
  // Symplectic Euler's own energy error at this step is a few percent of
  // m·g·L; post-stabilization must not add to it beyond 1% of m·g·L.
  CHECK(std::abs(projected.energyChange) < std::abs(plain.energyChange) + 0.01);
  CHECK(std::abs(projected.energyChange) < 0.05);
}
