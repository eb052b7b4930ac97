#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include <spook/constraints/joints/wheel_joint.hpp>
#include <spook/constraints/steering/steering.hpp>

#include "joint_scenes.hpp"
#include "tolerance.hpp"

using namespace spook;
using spook::test::kG;
using spook::test::makeBody;
using spook::test::pick;

namespace {

// A wheel of mass `mass` at the origin, axle along world y, steering axis
// along world z, joined to the world at its center, direct solver, 60 Hz.
template <class S>
struct WheelOnWorldScene {
  ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
  ref_ptr<RigidBodyT<S>> wheel;
  ref_ptr<WheelJointT<S>> joint;

  explicit WheelOnWorldScene(S mass = S(10)) {
    sim->setSolver(new DirectSolver());
    wheel = makeBody<S>(*sim, "wheel", mass, Vec3T<S>::Zero(), S(0.2));
    const WheelJointFrameT<S> frame(Vec3T<S>::Zero(), Vec3T<S>::UnitY(), Vec3T<S>::UnitZ());
    joint = new WheelJointT<S>(frame, wheel.get(), nullptr);
    sim->add(joint);
  }
};

// |y₁·z₂|: the cosine between the axle and the steering axis, read from the
// attachment frames.
template <class S>
double wheelAxleTilt(const WheelJointT<S>& joint) {
  const Mat3T<S> R1 = joint.getAttachmentFrame(0)->getMatrix().linear();
  const Mat3T<S> R2 = joint.getAttachmentFrame(1)->getMatrix().linear();
  return std::abs(double(R1.col(1).dot(R2.col(2))));
}

// Distance of frame 1's origin from the steering axis (m).
template <class S>
double wheelOffAxis(const WheelJointT<S>& joint) {
  const TransformT<S> X1 = joint.getAttachmentFrame(0)->getMatrix(), X2 = joint.getAttachmentFrame(1)->getMatrix();
  const Vec3T<S> d = X1.translation() - X2.translation();
  const Vec3T<S> z = X2.linear().col(2);
  return double((d - d.dot(z) * z).norm());
}

// Front axle of a car: a static chassis at the origin (x forward, y left,
// z up) and two wheels of 15 kg hanging on wheel joints whose steering
// pivots are a wheel track kSteeringTrack apart, under gravity, 60 Hz.
constexpr double kSteeringTrack = 1.5;  // m

template <class S>
struct FrontAxleScene {
  ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
  ref_ptr<RigidBodyT<S>> chassis, leftWheel, rightWheel;
  ref_ptr<WheelJointT<S>> left, right;

  FrontAxleScene() {
    sim->setSolver(new DirectSolver());
    chassis = makeBody<S>(*sim, "chassis", S(500), Vec3T<S>::Zero(), S(100));
    chassis->setMotionControl(RigidBodyT<S>::STATIC);
    const S half = S(kSteeringTrack / 2);
    leftWheel = makeBody<S>(*sim, "left wheel", S(15), Vec3T<S>(0, half + S(0.1), 0), S(0.5));
    rightWheel = makeBody<S>(*sim, "right wheel", S(15), Vec3T<S>(0, -half - S(0.1), 0), S(0.5));
    left = new WheelJointT<S>(WheelJointFrameT<S>(Vec3T<S>(0, half, 0), Vec3T<S>::UnitY(), Vec3T<S>::UnitZ()),
                              leftWheel.get(), chassis.get());
    right = new WheelJointT<S>(WheelJointFrameT<S>(Vec3T<S>(0, -half, 0), Vec3T<S>::UnitY(), Vec3T<S>::UnitZ()),
                               rightWheel.get(), chassis.get());
    sim->add(left);
    sim->add(right);
  }
  [[nodiscard]] double angle(const WheelJointT<S>& joint) const {
    return double(joint.getAngle(WheelJointT<S>::STEERING));
  }
};

// Ackermann's rule (seed 001 §12.13): the outer wheel angle for an inner
// one, both > 0, wheel track over wheel base `trackOverBase`.
double ackermannOuterAngle(double inner, double trackOverBase) {
  return std::atan(1.0 / (1.0 / std::tan(inner) + trackOverBase));
}

// Steers the front axle to a few inputs across the mechanism's range and
// returns the worst |measured − mechanism's target| (rad) and the worst
// deviation of the measured outer angle from Ackermann's rule (rad).
template <class S, class Mechanism>
void steerAcrossRange(double trackOverBase, double& worstTracking, double& worstAckermann, double& innerExcess) {
  FrontAxleScene<S> scene;
  ref_ptr<Mechanism> steering = new Mechanism(scene.left.get(), scene.right.get());
  scene.sim->add(steering);
  const double maximum = double(steering->getMaximumSteeringAngle());
  worstTracking = worstAckermann = 0.0;
  innerExcess = std::numeric_limits<double>::infinity();
  for (const double fraction : {0.25, 0.5, 0.75, 0.95, -0.5, -0.95}) {
    steering->setSteeringAngle(S(fraction * maximum));
    scene.sim->stepTo(scene.sim->getTimeStamp() + S(1));
    const auto target = steering->getWheelAngles();
    const double l = scene.angle(*scene.left), r = scene.angle(*scene.right);
    worstTracking = std::max({worstTracking, std::abs(l - double(target.left)), std::abs(r - double(target.right))});
    // Turning left (input > 0) the left wheel is inner.
    const double inner = fraction > 0 ? l : -r, outer = fraction > 0 ? r : -l;
    worstAckermann = std::max(worstAckermann, std::abs(outer - ackermannOuterAngle(inner, trackOverBase)));
    innerExcess = std::min(innerExcess, inner - outer);
  }
}

// Wheel track over wheel base for which a linkage with knuckle arms at
// |φ₀| − π/2 to the car's axis follows Ackermann's rule near straight ahead
// (the arms' lines meet on the rear axle: tan β = W_t/(2 W_b)).
double designTrackOverBase(double phi0) { return 2.0 * std::tan(std::abs(phi0) - std::numbers::pi / 2.0); }
}  // namespace

TEST_CASE_TEMPLATE("wheel joint: a WHEEL motor spins the wheel at the motor speed", S, float, double) {
  WheelOnWorldScene<S> scene;
  Motor1DT<S>* motor = scene.joint->getMotor1D(WheelJointT<S>::WHEEL);
  motor->setSpeed(S(5));
  motor->setEnable(true);
  scene.sim->stepTo(S(1));
  const double speed = double(scene.joint->getCurrentSpeed(WheelJointT<S>::WHEEL));
  const double spin = double(scene.wheel->getAngularVelocity().dot(Vec3T<S>::UnitY()));
  MESSAGE("WHEEL speed after 1 s: " << speed << " rad/s (target 5), body ω·y = " << spin);
  CHECK(speed == doctest::Approx(5.0).epsilon(pick<S>(1e-6, 1e-4)));
  CHECK(spin == doctest::Approx(5.0).epsilon(pick<S>(1e-6, 1e-4)));
  // The motor row reaches its speed in the first step: 1 s at 5 rad/s.
  CHECK(double(scene.joint->getAngle(WheelJointT<S>::WHEEL)) == doctest::Approx(5.0).epsilon(pick<S>(1e-6, 1e-4)));
  CHECK(std::abs(double(scene.joint->getAngle(WheelJointT<S>::STEERING))) < pick<S>(1e-9, 1e-4));
}

TEST_CASE_TEMPLATE("wheel joint: the default suspension lock deflects by load times compliance", S, float, double) {
  WheelOnWorldScene<S> scene(S(10));
  Lock1DT<S>* lock = scene.joint->getLock1D(WheelJointT<S>::SUSPENSION);
  REQUIRE(lock->getEnable());
  CHECK(lock->getPosition() == S(0));
  const double compliance = 1e-4;  // m/N
  lock->setCompliance(S(compliance));
  scene.sim->stepTo(S(5));
  const double expected = -10.0 * kG * compliance;
  const double deflection = double(scene.joint->getAngle(WheelJointT<S>::SUSPENSION));
  MESSAGE("suspension deflection " << deflection << " m, load × compliance " << expected << " m");
  CHECK(deflection == doctest::Approx(expected).epsilon(0.01));
  CHECK(double(scene.wheel->getPosition().z()) == doctest::Approx(expected).epsilon(0.01));
}

TEST_CASE_TEMPLATE("wheel joint: an unlocked suspension stops at its Range1D ends", S, float, double) {
  WheelOnWorldScene<S> scene;
  scene.joint->getLock1D(WheelJointT<S>::SUSPENSION)->setEnable(false);
  Range1DT<S>* range = scene.joint->getRange1D(WheelJointT<S>::SUSPENSION);
  range->setEnable(true);
  range->setRange(S(-0.1), S(0.1));
  scene.sim->stepTo(S(2));
  const double low = double(scene.joint->getAngle(WheelJointT<S>::SUSPENSION));

  Motor1DT<S>* lift = scene.joint->getMotor1D(WheelJointT<S>::SUSPENSION);
  lift->setSpeed(S(0.5));
  lift->setForceRange(S(-500), S(500));
  lift->setEnable(true);
  scene.sim->stepTo(S(4));
  const double high = double(scene.joint->getAngle(WheelJointT<S>::SUSPENSION));
  MESSAGE("suspension under gravity " << low << " m, lifted by a 500 N motor " << high << " m (range ±0.1 m)");
  // Range rows have the default compliance 1e-8 m/N: 98 N and 402 N deflect
  // by well under 1e-5 m.
  CHECK(low == doctest::Approx(-0.1).epsilon(pick<S>(1e-4, 1e-3)));
  CHECK(high == doctest::Approx(0.1).epsilon(pick<S>(1e-4, 1e-3)));
}

TEST_CASE_TEMPLATE("wheel joint: the axle stays perpendicular to the steering axis", S, float, double) {
  // A wheel rolling at ω about its axle while steering at Ω, under gravity,
  // suspension free within ±0.2 m, kicked across every constrained
  // direction. Integrating the rotation drifts the axle out of the plane by
  // h²Ωω/2 per step; the plain SPOOK row (ε → 0) corrects it with a steady
  // lag g = drift · τ/h = τ h Ω ω / 2 (τ the row's damping), so the
  // violation stays bounded, does not grow, and halves with h. The direct
  // solver's post-stabilization (its default) removes the lag.
  const double roll = 10.0, steer = 0.5;
  const auto run = [&](double h, double& worst, double& lastSecond, double& offAxis, bool postStabilize = false) {
    WheelOnWorldScene<S> scene(S(10));
    ref_ptr<DirectSolver> solver = new DirectSolver();
    solver->setEnablePostStabilization(postStabilize);
    scene.sim->setSolver(solver);
    scene.sim->setTimeStep(S(h));
    scene.joint->getLock1D(WheelJointT<S>::SUSPENSION)->setEnable(false);
    scene.joint->getRange1D(WheelJointT<S>::SUSPENSION)->setEnable(true);
    scene.joint->getRange1D(WheelJointT<S>::SUSPENSION)->setRange(S(-0.2), S(0.2));
    scene.wheel->setVelocity(S(0.4), S(-0.3), S(0.2));
    scene.wheel->setAngularVelocity(S(0.3), S(roll), S(steer));
    worst = lastSecond = offAxis = 0.0;
    const int steps = int(std::lround(10.0 / h)), perSecond = int(std::lround(1.0 / h));
    for (int step = 0; step < steps; ++step) {
      scene.sim->stepForward();
      if (step < perSecond) continue;
      const double tilt = wheelAxleTilt(*scene.joint);
      worst = std::max(worst, tilt);
      if (step >= steps - perSecond) lastSecond = std::max(lastSecond, tilt);
      offAxis = std::max(offAxis, wheelOffAxis(*scene.joint));
    }
  };
  double worst60 = 0, last60 = 0, off60 = 0, worst120 = 0, last120 = 0, off120 = 0;
  run(1.0 / 60.0, worst60, last60, off60);
  run(1.0 / 120.0, worst120, last120, off120);
  const double tau = 2.0 / 60.0;  // default row damping (s)
  const double lag60 = tau * (1.0 / 60.0) * steer * roll / 2.0;
  MESSAGE("ω = 10 rad/s, Ω = 0.5 rad/s, from 1 s to 10 s: max |y1·z2| = " << worst60 << " at 60 Hz (last second "
                                                                          << last60 << ", predicted lag " << lag60
                                                                          << "), " << worst120 << " at 120 Hz");
  MESSAGE("max distance of the wheel center from the steering axis: " << off60 << " m at 60 Hz");
  CHECK(worst60 < 1.3 * lag60);
  CHECK(last60 < 1.05 * worst60);
  CHECK(worst60 / worst120 == doctest::Approx(2.0).epsilon(0.15));
  CHECK(off60 < pick<S>(1e-9, 1e-5));

  double worstProjected = 0, lastProjected = 0, offProjected = 0;
  run(1.0 / 60.0, worstProjected, lastProjected, offProjected, true);
  MESSAGE("post-stabilized at 60 Hz: max |y1·z2| = " << worstProjected << ", off the axis " << offProjected << " m");
  CHECK(worstProjected < 1e-6);  // measured 1.0e-8 double, 3.3e-7 float
  CHECK(offProjected < pick<S>(1e-9, 1e-5));
}

TEST_CASE_TEMPLATE("wheel joint: angles measure steering and roll separately", S, float, double) {
  ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
  ref_ptr<RigidBodyT<S>> wheel = makeBody<S>(*sim, "wheel", S(1), Vec3T<S>::Zero());
  const WheelJointFrameT<S> frame(Vec3T<S>::Zero(), Vec3T<S>::UnitY(), Vec3T<S>::UnitZ());
  ref_ptr<WheelJointT<S>> joint = new WheelJointT<S>(frame, wheel.get(), nullptr);
  const double steer = 0.4, roll = 1.1;
  // Steer about z, then roll about the steered axle.
  const QuatT<S> q = QuatT<S>(Eigen::AngleAxis<S>(S(steer), Vec3T<S>::UnitZ())) *
                    QuatT<S>(Eigen::AngleAxis<S>(S(roll), Vec3T<S>::UnitY()));
  wheel->setRotation(q);
  wheel->setPosition(Vec3T<S>(0, 0, S(0.03)));
  CHECK(double(joint->getAngle(WheelJointT<S>::STEERING)) == doctest::Approx(steer).epsilon(pick<S>(1e-12, 1e-5)));
  CHECK(double(joint->getAngle(WheelJointT<S>::WHEEL)) == doctest::Approx(roll).epsilon(pick<S>(1e-12, 1e-5)));
  CHECK(double(joint->getAngle(WheelJointT<S>::SUSPENSION)) == doctest::Approx(0.03).epsilon(pick<S>(1e-12, 1e-5)));
}

TEST_CASE_TEMPLATE("wheel joint: a STEERING motor winds past pi", S, float, double) {
  WheelOnWorldScene<S> scene;
  Motor1DT<S>* motor = scene.joint->getMotor1D(WheelJointT<S>::STEERING);
  motor->setSpeed(S(2));
  motor->setEnable(true);
  scene.sim->stepTo(S(3));
  const double angle = double(scene.joint->getAngle(WheelJointT<S>::STEERING));
  MESSAGE("steering angle after 3 s at 2 rad/s: " << angle << " rad");
  CHECK(angle == doctest::Approx(6.0).epsilon(pick<S>(1e-6, 1e-4)));
  CHECK(wheelAxleTilt(*scene.joint) < pick<S>(1e-8, 1e-4));
}

TEST_CASE("wheel joint frame rejects bad axes and points") {
  const Vec3T<double> o = Vec3T<double>::Zero(), y = Vec3T<double>::UnitY(), z = Vec3T<double>::UnitZ();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_AS(WheelJointFrame(o, y, Vec3T<double>(0, 0.01, 1)), Error);
  CHECK_THROWS_AS(WheelJointFrame(o, Vec3T<double>::Zero(), z), Error);
  CHECK_THROWS_AS(WheelJointFrame(o, y, Vec3T<double>(0, 0, nan)), Error);
  CHECK_THROWS_AS(WheelJointFrame(Vec3T<double>(nan, 0, 0), y, z), Error);
  CHECK_NOTHROW(WheelJointFrame(o, Vec3T<double>(3, 0, 0), Vec3T<double>(0, 0, 0.5)));
  try {
    WheelJointFrame(o, y, y);
    FAIL("parallel axes accepted");
  } catch (const Error& e) {
    const std::string what = e.what();
    CHECK(what.find("WheelJointFrame") != std::string::npos);
    CHECK(what.find("perpendicular") != std::string::npos);
  }
}

TEST_CASE("wheel joint rejects bad indices and a missing wheel") {
  ref_ptr<Simulation> sim = new Simulation();
  ref_ptr<RigidBody> wheel = makeBody<double>(*sim, "wheel", 1.0, Vec3T<double>::Zero());
  const WheelJointFrame frame(Vec3T<double>::Zero(), Vec3T<double>::UnitY(), Vec3T<double>::UnitZ());
  CHECK_THROWS_AS(WheelJointRef(new WheelJoint(frame, nullptr, nullptr)), Error);
  WheelJointRef joint = new WheelJoint(frame, wheel.get(), nullptr);
  joint->setName("front left");
  try {
    (void)joint->getLock1D(3);
    FAIL("index 3 accepted");
  } catch (const Error& e) {
    const std::string what = e.what();
    CHECK(what.find("WheelJoint 'front left'") != std::string::npos);
    CHECK(what.find("got 3") != std::string::npos);
  }
  CHECK_THROWS_AS((void)joint->getAngle(-1), Error);
  CHECK(joint->getNumDOF() == WheelJoint::NUM_DOF);
  CHECK(joint->getNumDOF() == 3);
}

TEST_CASE_TEMPLATE("steering: Davis turns the wheels by Ackermann's rule exactly", S, float, double) {
  const double trackOverBase = designTrackOverBase(SteeringParameters::davis().phi0);
  // The mechanism's targets, for the exact rule.
  FrontAxleScene<S> scene;
  ref_ptr<DavisT<S>> davis = new DavisT<S>(scene.left.get(), scene.right.get());
  const double maximum = double(davis->getMaximumSteeringAngle());
  double worstTarget = 0.0;
  for (int i = 1; i <= 20; ++i) {
    davis->setSteeringAngle(S(maximum * i / 21.0));
    const auto a = davis->getWheelAngles();
    worstTarget = std::max(worstTarget, std::abs(double(a.right) - ackermannOuterAngle(double(a.left), trackOverBase)));
  }
  double tracking = 0, ackermann = 0, excess = 0;
  steerAcrossRange<S, DavisT<S>>(trackOverBase, tracking, ackermann, excess);
  MESSAGE("Davis: maximum " << maximum << " rad; targets deviate from Ackermann by " << worstTarget
                            << " rad, simulated wheels by " << ackermann << " rad; tracking error " << tracking
                            << " rad");
  CHECK(maximum == doctest::Approx(std::numbers::pi / 2.0 - (SteeringParameters::davis().phi0 - std::numbers::pi / 2.0))
                       .epsilon(1e-6));
  CHECK(worstTarget < pick<S>(1e-12, 1e-6));
  CHECK(ackermann < pick<S>(1e-6, 1e-4));
  CHECK(tracking < pick<S>(1e-6, 1e-4));
  CHECK(excess > 0.0);
}

TEST_CASE_TEMPLATE("steering: linkages turn the inner wheel more, close to Ackermann's rule", S, float, double) {
  struct Row {
    const char* name;
    double tracking, ackermann, excess;
  };
  Row rows[3] = {};
  steerAcrossRange<S, AckermannT<S>>(designTrackOverBase(SteeringParameters::ackermann().phi0), rows[0].tracking,
                                     rows[0].ackermann, rows[0].excess);
  steerAcrossRange<S, BellCrankT<S>>(designTrackOverBase(SteeringParameters::bellCrank().phi0), rows[1].tracking,
                                     rows[1].ackermann, rows[1].excess);
  steerAcrossRange<S, RackPinionT<S>>(designTrackOverBase(SteeringParameters::rackPinion().phi0), rows[2].tracking,
                                      rows[2].ackermann, rows[2].excess);
  rows[0].name = "Ackermann";
  rows[1].name = "BellCrank";
  rows[2].name = "RackPinion";
  for (const Row& row : rows) {
    MESSAGE(std::string(row.name) << ": worst deviation from Ackermann's rule "
                                  << row.ackermann * 180.0 / std::numbers::pi
                                  << " deg up to 95% of the maximum, tracking error " << row.tracking
                                  << " rad, smallest inner − outer " << row.excess << " rad");
    CHECK(row.tracking < pick<S>(1e-6, 1e-4));
    CHECK(row.ackermann < 5.0 * std::numbers::pi / 180.0);
    CHECK(row.excess > 0.0);
  }
}

TEST_CASE("steering: small inputs turn both wheels by gear times the input") {
  FrontAxleScene<double> scene;
  SteeringParameters geared = SteeringParameters::rackPinion();
  geared.gear = 0.5;
  for (const SteeringParameters& p : {SteeringParameters::rackPinion(), geared}) {
    RackPinionRef rack = new RackPinion(scene.left.get(), scene.right.get(), p);
    rack->setSteeringAngle(1e-4);
    CHECK(rack->getWheelAngles().left / 1e-4 == doctest::Approx(p.gear).epsilon(1e-3));
    CHECK(rack->getWheelAngles().right / 1e-4 == doctest::Approx(p.gear).epsilon(1e-3));
  }
  AckermannRef ackermann = new Ackermann(scene.left.get(), scene.right.get());
  ackermann->setSteeringAngle(0.2);
  CHECK(ackermann->getWheelAngles().left == doctest::Approx(0.2).epsilon(1e-12));
}

TEST_CASE("steering: maximum angles are finite, positive, and where the linkage stops working") {
  FrontAxleScene<double> scene;
  const SteeringRef mechanisms[] = {
      new Ackermann(scene.left.get(), scene.right.get()), new BellCrank(scene.left.get(), scene.right.get()),
      new RackPinion(scene.left.get(), scene.right.get()), new Davis(scene.left.get(), scene.right.get())};
  for (const SteeringRef& m : mechanisms) {
    const double maximum = m->getMaximumSteeringAngle();
    m->setSteeringAngle(maximum);
    const auto atMax = m->getWheelAngles();
    m->setSteeringAngle(-maximum);
    const auto atMin = m->getWheelAngles();
    MESSAGE(std::string(m->getKind()) << ": maximum steering angle " << maximum << " rad; wheels (" << atMax.left
                                      << ", " << atMax.right << ") and (" << atMin.left << ", " << atMin.right
                                      << ") rad");
    CHECK(std::isfinite(maximum));
    CHECK(maximum > 0.1);
    CHECK(maximum < std::numbers::pi / 2.0);
    m->setSteeringAngle(maximum * 1.01);  // clamped
    CHECK(m->getSteeringAngle() == maximum);
  }
}

// Requests beyond the linkage's reach are clamped to ±getMaximumSteeringAngle()
// (as AGX does): the mechanism holds the wheels where the clamped input puts
// them, in the simulation too. Only a non-finite request is refused.
template <class S, class Mechanism>
void steerBeyondReach() {
  FrontAxleScene<S> scene;
  ref_ptr<Mechanism> steering = new Mechanism(scene.left.get(), scene.right.get());
  scene.sim->add(steering);
  const S maximum = steering->getMaximumSteeringAngle();
  steering->setSteeringAngle(maximum);
  const auto atMax = steering->getWheelAngles();
  steering->setSteeringAngle(-maximum);
  const auto atMin = steering->getWheelAngles();
  for (const S request : {S(1), S(2) * maximum, S(1e6), -S(2) * maximum, -S(1e30)}) {
    CAPTURE(request);
    const S expected = std::clamp(request, -maximum, maximum);
    CHECK_NOTHROW(steering->setSteeringAngle(request));
    MESSAGE(std::string(steering->getKind()) << ": asked " << request << " rad, holds " << steering->getSteeringAngle()
                                << " rad (reach +-" << maximum << " rad)");
    CHECK(steering->getSteeringAngle() == expected);
    CHECK(steering->getRequestedSteeringAngle() == request);
    if (std::abs(request) > maximum) {
      const auto& wheels = request > S(0) ? atMax : atMin;
      // Float evaluates the linkage at the clamped angle along another path
      // than at the maximum itself: 1.5e-4 rad apart at Ackermann's reach.
      CHECK(std::abs(double(steering->getWheelAngles().left - wheels.left)) <= pick<S>(1e-12, 1e-3));
      CHECK(std::abs(double(steering->getWheelAngles().right - wheels.right)) <= pick<S>(1e-12, 1e-3));
    }
  }
  // Held by the simulation at the clamped angles.
  steering->setSteeringAngle(S(3) * maximum);
  scene.sim->stepTo(S(1));
  CHECK(std::abs(scene.angle(*scene.left) - double(atMax.left)) < 1e-3);
  CHECK(std::abs(scene.angle(*scene.right) - double(atMax.right)) < 1e-3);
  // Non-finite input throws and changes nothing.
  for (const S bad : {std::numeric_limits<S>::quiet_NaN(), std::numeric_limits<S>::infinity()}) {
    CHECK_THROWS_AS(steering->setSteeringAngle(bad), Error);
    CHECK(steering->getSteeringAngle() == maximum);
    CHECK(std::abs(double(steering->getWheelAngles().left - atMax.left)) <= pick<S>(1e-12, 1e-3));
  }
}

TEST_CASE_TEMPLATE("steering: every mechanism clamps requests beyond its reach and reports the angle it holds", S,
                   float, double) {
  steerBeyondReach<S, AckermannT<S>>();
  steerBeyondReach<S, BellCrankT<S>>();
  steerBeyondReach<S, RackPinionT<S>>();
  steerBeyondReach<S, DavisT<S>>();
}

TEST_CASE("steering: added to a simulation it keeps the wheels steered") {
  FrontAxleScene<double> scene;
  AckermannRef steering = new Ackermann(scene.left.get(), scene.right.get());
  scene.sim->add(steering);
  steering->setSteeringAngle(0.3);
  scene.left->getLock1D(WheelJoint::STEERING)->setEnable(false);
  scene.sim->stepTo(1.0);
  CHECK(scene.left->getLock1D(WheelJoint::STEERING)->getEnable());
  CHECK(scene.angle(*scene.left) == doctest::Approx(0.3).epsilon(1e-6));
  scene.sim->remove(steering.get());
  CHECK(steering->getSimulation() == nullptr);
}

TEST_CASE("steering: bad input throws and leaves the mechanism unchanged") {
  FrontAxleScene<double> scene;
  // A wheel joint on another chassis.
  ref_ptr<RigidBody> trailer = makeBody<double>(*scene.sim, "trailer", 100.0, Vec3T<double>(-3, 0, 0), 10.0);
  ref_ptr<RigidBody> trailerWheel = makeBody<double>(*scene.sim, "trailer wheel", 10.0, Vec3T<double>(-3, 1, 0));
  WheelJointRef other =
      new WheelJoint(WheelJointFrame(Vec3T<double>(-3, 0.9, 0), Vec3T<double>::UnitY(), Vec3T<double>::UnitZ()),
                     trailerWheel.get(), trailer.get());
  CHECK_THROWS_AS(AckermannRef(new Ackermann(nullptr, scene.right.get())), Error);
  CHECK_THROWS_AS(DavisRef(new Davis(nullptr, nullptr)), Error);
  CHECK_THROWS_AS(AckermannRef(new Ackermann(scene.left.get(), scene.left.get())), Error);
  CHECK_THROWS_AS(BellCrankRef(new BellCrank(scene.left.get(), other.get())), Error);

  const double nan = std::numeric_limits<double>::quiet_NaN();
  SteeringParameters p = SteeringParameters::ackermann();
  p.l = nan;
  CHECK_THROWS_AS(AckermannRef(new Ackermann(scene.left.get(), scene.right.get(), p)), Error);
  p = SteeringParameters::ackermann();
  p.side = 2;
  CHECK_THROWS_AS(AckermannRef(new Ackermann(scene.left.get(), scene.right.get(), p)), Error);
  p = SteeringParameters::rackPinion();
  p.lr = 1.5;
  CHECK_THROWS_AS(RackPinionRef(new RackPinion(scene.left.get(), scene.right.get(), p)), Error);
  p = SteeringParameters::bellCrank();
  p.lc = 0.0;
  CHECK_THROWS_AS(BellCrankRef(new BellCrank(scene.left.get(), scene.right.get(), p)), Error);
  p = SteeringParameters::davis();
  p.phi0 = -1.0;
  CHECK_THROWS_AS(DavisRef(new Davis(scene.left.get(), scene.right.get(), p)), Error);
  p = SteeringParameters::davis();
  p.gear = 0.0;
  CHECK_THROWS_AS(DavisRef(new Davis(scene.left.get(), scene.right.get(), p)), Error);
  // Straight ahead with the tie rod along the knuckle arm: a dead centre.
  p = SteeringParameters::ackermann();
  p.phi0 = 0.0;
  CHECK_THROWS_AS(AckermannRef(new Ackermann(scene.left.get(), scene.right.get(), p)), Error);

  AckermannRef steering = new Ackermann(scene.left.get(), scene.right.get());
  steering->setName("front");
  steering->setSteeringAngle(0.2);
  const auto before = steering->getWheelAngles();
  const double lockBefore = scene.right->getLock1D(WheelJoint::STEERING)->getPosition();
  try {
    steering->setSteeringAngle(nan);
    FAIL("a NaN steering angle accepted");
  } catch (const Error& e) {
    const std::string what = e.what();
    MESSAGE(what);
    CHECK(what.find("Ackermann 'front'") != std::string::npos);
    CHECK(what.find("nan") != std::string::npos);
  }
  CHECK_THROWS_AS(steering->setSteeringAngle(std::numeric_limits<double>::infinity()), Error);
  CHECK(steering->getSteeringAngle() == 0.2);
  CHECK(steering->getWheelAngles().left == before.left);
  CHECK(steering->getWheelAngles().right == before.right);
  CHECK(scene.right->getLock1D(WheelJoint::STEERING)->getPosition() == lockBefore);
}
