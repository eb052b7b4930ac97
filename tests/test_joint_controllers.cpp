#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <spook/constraints/joints/cylindrical_joint.hpp>
#include <spook/constraints/secondary/cone_limit.hpp>
#include <spook/constraints/secondary/friction_controller.hpp>
#include <spook/constraints/secondary/twist_range.hpp>

#include "joint_scenes.hpp"
#include "tolerance.hpp"

// Joint friction (seed 001 §12.15.4), the ball joint's cone limit, twist
// range and rotational friction (§12.4.1–12.4.3), all with the direct solver
// so that the bounded rows are solved exactly (an MLCP, PHYSICS.md §2.4).

using namespace spook;
using spook::test::frameAt;
using spook::test::kG;
using spook::test::makeBody;
using spook::test::pick;

namespace {

template <class S>
ref_ptr<SimulationT<S>> directSimulation() {
  ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
  sim->setSolver(new DirectSolver());
  return sim;
}

// A slider of mass m on a horizontal prismatic along world x: its weight is
// carried by the joint, so the normal force is N = m g.
template <class S>
struct Slider {
  static constexpr double kMass = 10.0, kMu = 0.3;
  ref_ptr<SimulationT<S>> sim = directSimulation<S>();
  ref_ptr<RigidBodyT<S>> body = makeBody<S>(*sim, "slider", S(kMass), Vec3T<S>::Zero());
  ref_ptr<PrismaticT<S>> joint = new PrismaticT<S>(body.get(), frameAt<S>(Vec3T<S>::Zero(), Vec3T<S>::UnitX()).get());
  Slider() {
    joint->setName("rail");
    joint->getFrictionController()->setEnable(true);
    joint->getFrictionController()->setFrictionCoefficient(S(kMu));
    sim->add(joint);
    // The friction bound uses the previous step's normal force (seed): one
    // step without a push lets the controller see the load.
    sim->stepForward();
  }
  void push(S force, int steps) {
    for (int i = 0; i < steps; ++i) {
      body->addForce(Vec3T<S>(force, 0, 0));
      sim->stepForward();
    }
  }
};

// A wheel of mass m on a horizontal hinge along world x, its center of mass on
// the axis: the hinge carries the weight, N = m g, and the friction torque is
// bounded by μ N with μ including the axle radius (seed §12.15.4).
template <class S>
struct FrictionWheel {
  static constexpr double kMass = 4.0, kInertia = 0.5, kMu = 0.05;  // μ in m
  ref_ptr<SimulationT<S>> sim = directSimulation<S>();
  ref_ptr<RigidBodyT<S>> body = makeBody<S>(*sim, "wheel", S(kMass), Vec3T<S>::Zero(), S(kInertia));
  ref_ptr<HingeT<S>> joint = new HingeT<S>(body.get(), frameAt<S>(Vec3T<S>::Zero(), Vec3T<S>::UnitX()).get());
  FrictionWheel() {
    joint->getFrictionController()->setEnable(true);
    joint->getFrictionController()->setFrictionCoefficient(S(kMu));
    sim->add(joint);
    sim->stepForward();
  }
  void twist(S torque, int steps) {
    for (int i = 0; i < steps; ++i) {
      body->addTorque(Vec3T<S>(torque, 0, 0));
      sim->stepForward();
    }
  }
};

}  // namespace

TEST_CASE_TEMPLATE("a prismatic with friction sticks below mu N and slides at (F - mu N)/m above", S, float, double) {
  const double N = Slider<S>::kMass * kG, bound = Slider<S>::kMu * N;  // 29.4 N
  SUBCASE("stick: F = 0.68 mu N") {
    Slider<S> s;
    // After the first step: N = m g up to the joint's compliant transient,
    // Σ m = 4ε m/(h²(1 + 4τ/h)) = 1.6e-4 relative.
    CHECK(std::abs(double(s.joint->getFrictionController()->getNormalForce()) - N) < 1e-3 * N);
    const S x0 = s.joint->getAngle();
    s.push(S(20), 60);
    const double moved = std::abs(double(s.joint->getAngle() - x0));
    MESSAGE("stuck slider moved " << moved << " m in 1 s under 20 N (mu N = " << bound << " N)");
    // The row's compliance (1e-8) is a viscosity: it creeps at 1e-8·20 m/s,
    // 2e-7 m in a second.
    CHECK(moved < 1e-6);
    CHECK(std::abs(double(s.joint->getFrictionController()->getCurrentForce()) + 20.0) < pick<S>(1e-6, 1e-3));
  }
  SUBCASE("slide: F = 1.36 mu N") {
    Slider<S> s;
    const double F = 40.0;
    s.push(S(F), 30);
    const double v1 = double(s.joint->getCurrentSpeed());
    s.push(S(F), 60);
    const double v2 = double(s.joint->getCurrentSpeed());
    const double a = (v2 - v1) / 1.0, expected = (F - bound) / Slider<S>::kMass;
    MESSAGE("sliding acceleration " << a << " m/s^2, (F - mu N)/m = " << expected);
    CHECK(std::abs(a / expected - 1.0) < 0.01);
    CHECK(std::abs(double(s.joint->getFrictionController()->getCurrentForce()) + bound) < pick<S>(1e-6, 1e-4) * bound);
  }
}

TEST_CASE_TEMPLATE("a hinge with friction sticks below mu r N and turns at (T - mu r N)/I above", S, float, double) {
  using W = FrictionWheel<S>;
  const double bound = W::kMu * W::kMass * kG;  // 1.96 N·m
  SUBCASE("stick") {
    W w;
    const S angle0 = w.joint->getAngle();
    w.twist(S(1.2), 60);
    const double turned = std::abs(double(w.joint->getAngle() - angle0));
    MESSAGE("stuck wheel turned " << turned << " rad in 1 s under 1.2 N·m (mu r N = " << bound << " N·m)");
    CHECK(turned < 1e-6);  // creep: compliance 1e-8 × 1.2 N·m rad/s
    CHECK(std::abs(double(w.joint->getFrictionController()->getCurrentForce()) + 1.2) < pick<S>(1e-6, 1e-4));
  }
  SUBCASE("slip") {
    W w;
    const double T = 3.0;
    w.twist(S(T), 30);
    const double w1 = double(w.joint->getCurrentSpeed());
    w.twist(S(T), 60);
    const double alpha = double(w.joint->getCurrentSpeed()) - w1, expected = (T - bound) / W::kInertia;
    MESSAGE("slipping angular acceleration " << alpha << " rad/s^2, (T - mu r N)/I = " << expected);
    CHECK(std::abs(alpha / expected - 1.0) < 0.01);
  }
}

TEST_CASE_TEMPLATE("a cylindrical joint has friction on both DOFs: it slides under a push and sticks under a small torque",
                   S, float, double) {
  auto sim = directSimulation<S>();
  const double m = 5.0, I = 0.2, muT = 0.2, muR = 0.02;
  auto body = makeBody<S>(*sim, "sleeve", S(m), Vec3T<S>::Zero(), S(I));
  ref_ptr<CylindricalJointT<S>> joint =
      new CylindricalJointT<S>(body.get(), frameAt<S>(Vec3T<S>::Zero(), Vec3T<S>::UnitX()).get());
  using J = CylindricalJointT<S>;
  joint->getFrictionController(J::FIRST)->setEnable(true);
  joint->getFrictionController(J::FIRST)->setFrictionCoefficient(S(muT));
  joint->getFrictionController(J::SECOND)->setEnable(true);
  joint->getFrictionController(J::SECOND)->setFrictionCoefficient(S(muR));
  sim->add(joint);
  sim->stepForward();
  const double N = m * kG, F = 15.0, T = 0.5;  // μ_t N = 9.81 N < F; μ_r N = 0.98 N·m > T
  const S angle0 = joint->getAngle(J::SECOND);
  double v1 = 0.0;
  for (int i = 0; i < 90; ++i) {
    if (i == 30) v1 = double(joint->getCurrentSpeed(J::FIRST));
    body->addForce(Vec3T<S>(S(F), 0, 0));
    body->addTorque(Vec3T<S>(S(T), 0, 0));
    sim->stepForward();
  }
  const double a = double(joint->getCurrentSpeed(J::FIRST)) - v1, expected = (F - muT * N) / m;
  MESSAGE("sleeve slides at " << a << " m/s^2 (expected " << expected << "), turned "
                              << double(joint->getAngle(J::SECOND) - angle0) << " rad");
  CHECK(std::abs(a / expected - 1.0) < 0.01);
  CHECK(std::abs(double(joint->getAngle(J::SECOND) - angle0)) < 1e-6);
  CHECK(std::abs(double(joint->getFrictionController(J::SECOND)->getCurrentForce()) + T) < pick<S>(1e-6, 1e-4));
}

TEST_CASE_TEMPLATE("the minimum static friction range holds a load without a normal force", S, float, double) {
  auto sim = directSimulation<S>();
  sim->setUniformGravity(Vec3T<S>::Zero());
  auto body = makeBody<S>(*sim, "wheel", S(2), Vec3T<S>::Zero(), S(0.1));
  ref_ptr<HingeT<S>> hinge = new HingeT<S>(body.get(), frameAt<S>(Vec3T<S>::Zero(), Vec3T<S>::UnitX()).get());
  auto* friction = hinge->getFrictionController();
  friction->setEnable(true);
  friction->setFrictionCoefficient(S(0));
  // The range bounds the friction torque itself: it may resist a positive
  // torque up to 2 N·m and a negative one up to 1 N·m.
  friction->setMinimumStaticFrictionForceRange(S(-2), S(1));
  sim->add(hinge);
  for (int i = 0; i < 60; ++i) {
    body->addTorque(Vec3T<S>(S(1.5), 0, 0));  // held: friction −1.5 within [−2, 1]
    sim->stepForward();
  }
  MESSAGE("held by the minimum range: turned " << double(hinge->getAngle()) << " rad");
  CHECK(std::abs(double(hinge->getAngle())) < 1e-6);
  const double w1 = double(hinge->getCurrentSpeed());
  for (int i = 0; i < 60; ++i) {
    body->addTorque(Vec3T<S>(S(-1.5), 0, 0));  // beyond the upper end (1 N·m): turns at −0.5/0.1 rad/s²
    sim->stepForward();
  }
  const double alpha = double(hinge->getCurrentSpeed()) - w1;
  MESSAGE("angular acceleration past the minimum range " << alpha << " rad/s^2 (expected -5)");
  CHECK(std::abs(alpha + 5.0) < 0.05);
}

TEST_CASE_TEMPLATE("the non-linear update follows a linearly growing normal force without the one-step lag", S, float,
                   double) {
  // Extra load k t pressing the slider down: N(t) = m g + k t. With the
  // previous step's N the bound lags by μ k h; extrapolated, it is exact for
  // a linear N. What is left is the joint's own compliant, damped response
  // (N is not exactly linear in the first steps): ~2e-4 N here.
  const double k = 600.0, mu = Slider<S>::kMu, h = 1.0 / 60.0;
  for (bool nonLinear : {false, true}) {
    Slider<S> s;
    s.joint->getFrictionController()->setEnableNonLinearDirectSolveUpdate(nonLinear);
    double worst = 0.0;
    for (int i = 0; i < 60; ++i) {
      const S t = s.sim->getTimeStamp();
      s.body->addForce(Vec3T<S>(S(200), 0, S(-k) * t));
      s.sim->stepForward();
      const auto* f = s.joint->getFrictionController();
      if (i >= 3) worst = std::max(worst, std::abs(-double(f->getCurrentForce()) - mu * double(f->getNormalForce())));
    }
    MESSAGE(std::string(nonLinear ? "non-linear" : "previous-step") << " mode: largest |friction - mu N| " << worst
                                                         << " N (mu k h = " << mu * k * h << " N)");
    if (nonLinear)
      CHECK(worst < 1e-3 * mu * k * h);
    else
      CHECK(std::abs(worst - mu * k * h) < 1e-3 * mu * k * h + pick<S>(1e-9, 1e-3));
  }
}

TEST_CASE_TEMPLATE("ball joint rotational friction holds a small torque and slips under a large one", S, float, double) {
  const double m = 3.0, I = 0.2, mu = 0.03;  // μ N = 0.88 N·m
  const double bound = mu * m * kG;
  for (double T : {0.5, 2.0}) {
    auto sim = directSimulation<S>();
    auto body = makeBody<S>(*sim, "ball", S(m), Vec3T<S>::Zero(), S(I));
    ref_ptr<BallJointT<S>> ball = new BallJointT<S>(body.get(), frameAt<S>(Vec3T<S>::Zero()).get());
    ball->setEnableRotationalFriction(true);
    ball->setRotationalFrictionCoefficient(S(mu));
    CHECK(ball->getRotationalFrictionControllers().size() == 3);
    sim->add(ball);
    sim->stepForward();
    for (int i = 0; i < 60; ++i) {
      body->addTorque(Vec3T<S>(S(T), 0, 0));
      sim->stepForward();
    }
    const double omega = double(body->getAngularVelocity().x());
    const double expected = T < bound ? 0.0 : (T - bound) / I * 1.0;
    MESSAGE("torque " << T << " N·m: omega after 1 s " << omega << " rad/s (expected " << expected << ")");
    CHECK(std::abs(omega - expected) < 0.01 * std::max(1.0, expected));
    CHECK(std::abs(double(ball->getRotationalFrictionControllerU()->getCurrentForce()) + std::min(T, bound)) <
          pick<S>(1e-6, 1e-3));
  }
}

namespace {

// A bob of 1 kg on a massless 1 m rod from a ball joint at the origin,
// starting horizontal along +x; frame 1's z runs along the rod. The cone's
// axis (frame 2's z) is horizontal along +x, so the bob falls out of the
// cone's axis and comes to rest on the cone, its weight pressing it there.
// `frame2` decides which half-angle is met on the way down (−z world).
template <class S>
struct ConePendulum {
  ref_ptr<SimulationT<S>> sim = directSimulation<S>();
  ref_ptr<RigidBodyT<S>> bob = makeBody<S>(*sim, "bob", S(1), Vec3T<S>(1, 0, 0));
  ref_ptr<BallJointT<S>> ball;
  ConePendulum(ref_ptr<FrameT<S>> frame2, S a1, S a2) {
    ball = new BallJointT<S>(bob.get(), frameAt<S>(Vec3T<S>(-1, 0, 0), Vec3T<S>::UnitX()).get(), nullptr, frame2.get());
    ball->setName("shoulder");
    ball->getConeLimit()->setEnable(true);
    ball->getConeLimit()->setLimitAngles(a1, a2);
    sim->add(ball);
  }
};

// World frame at the origin with axes (x, y, z) = the given world axes.
template <class S>
ref_ptr<FrameT<S>> frameWithAxes(const Vec3T<S>& x, const Vec3T<S>& y, const Vec3T<S>& z) {
  Mat3T<S> R;
  R << x, y, z;
  ref_ptr<FrameT<S>> f = new FrameT<S>();
  f->setLocalRotate(QuatT<S>(R));
  return f;
}

}  // namespace

TEST_CASE_TEMPLATE("an elliptic cone limit stops a falling pendulum at a1 in the x-z plane and a2 in the y-z plane", S,
                   float, double) {
  const S a1 = S(0.5), a2 = S(0.8);
  const Vec3T<S> X = Vec3T<S>::UnitX(), Y = Vec3T<S>::UnitY(), Z = Vec3T<S>::UnitZ();
  struct Case {
    const char* plane;
    ref_ptr<FrameT<S>> frame2;
    double limit;
  };
  // x₂ = −z world: the bob falls towards frame 2's x (azimuth 0, limit a1);
  // y₂ = +z world: it falls towards −y₂ (azimuth −π/2, limit a2).
  for (const Case& c : {Case{"x-z", frameWithAxes<S>(-Z, Y, X), double(a1)}, Case{"y-z", frameWithAxes<S>(Y, Z, X), double(a2)}}) {
    ConePendulum<S> p(c.frame2, a1, a2);
    double highest = 0.0;
    for (int i = 0; i < 240; ++i) {
      p.sim->stepForward();
      highest = std::max(highest, double(p.ball->getSwingAngle()));
    }
    const double swing = double(p.ball->getSwingAngle());
    const double drop = std::asin(-double(p.bob->getPosition().z()));  // angle of the rod below horizontal
    MESSAGE(std::string(c.plane) << " plane: at rest " << swing - c.limit << " rad off the limit " << c.limit
                                 << " (rod " << drop - c.limit << " off), overshoot " << highest - c.limit << ", torque " << double(p.ball->getConeLimit()->getCurrentForce())
                    << " N·m");
    // The row is added two steps before the rod reaches the cone, so the
    // impact does not overshoot; at rest the weight's torque m g L cos a
    // deflects the limit by ε m g L cos a = 8.6e-8 rad (a1) and 6.8e-8 rad
    // (a2), and the Spherical rows stretch by ~1e-7 m. Measured: 8.6e-8 and
    // 6.8e-8 rad (double), 6e-8 rad (float, its resolution at 0.5 rad).
    CHECK(std::abs(swing - c.limit) < pick<S>(1e-6, 1e-5));
    CHECK(std::abs(drop - c.limit) < pick<S>(1e-6, 1e-5));
    CHECK(highest < c.limit + pick<S>(1e-6, 1e-5));
    CHECK(std::abs(double(p.bob->getAngularVelocity().norm())) < pick<S>(1e-4, 1e-3));
    // The limit carries the weight's torque about the pivot.
    CHECK(std::abs(std::abs(double(p.ball->getConeLimit()->getCurrentForce())) - kG * std::cos(c.limit)) <
          1e-3 * kG);
  }
}

TEST_CASE_TEMPLATE("a pendulum swinging inside its cone moves exactly as without the limit", S, float, double) {
  // Cone axis straight down, half-angles 0.6 and 0.9 rad; released at 0.4 rad
  // in the x-z plane, the rod never comes within two steps of the cone, so no
  // row is added and the run is the unlimited one, bit for bit.
  const double theta0 = 0.4;
  const Vec3T<S> rod(S(std::sin(theta0)), 0, S(-std::cos(theta0)));
  auto run = [&](bool limited, double& widest) {
    auto sim = directSimulation<S>();
    auto bob = makeBody<S>(*sim, "bob", S(1), rod);
    ref_ptr<BallJointT<S>> ball =
        new BallJointT<S>(bob.get(), frameAt<S>(-rod, rod).get(), nullptr, frameAt<S>(Vec3T<S>::Zero(), -Vec3T<S>::UnitZ()).get());
    ball->getConeLimit()->setEnable(limited);
    ball->getConeLimit()->setLimitAngles(S(0.6), S(0.9));
    sim->add(ball);
    widest = 0.0;
    std::vector<Vec3T<S>> path;
    for (int i = 0; i < 180; ++i) {
      sim->stepForward();
      widest = std::max(widest, double(ball->getSwingAngle()));
      path.push_back(bob->getPosition());
    }
    return path;
  };
  double widestFree = 0.0, widestLimited = 0.0;
  const auto free = run(false, widestFree);
  const auto limited = run(true, widestLimited);
  double diff = 0.0;
  for (std::size_t i = 0; i < free.size(); ++i) diff = std::max(diff, double((free[i] - limited[i]).norm()));
  MESSAGE("largest swing " << widestLimited << " rad, largest difference from the unlimited run " << diff << " m");
  CHECK(diff == 0.0);
  CHECK(widestLimited > theta0 - 0.01);
  CHECK(widestLimited < 0.6);
}

TEST_CASE_TEMPLATE("the twist range controller stops a body spun about its z axis at the upper limit", S, float, double) {
  auto sim = directSimulation<S>();
  auto body = makeBody<S>(*sim, "top", S(2), Vec3T<S>::Zero(), S(0.1));
  ref_ptr<BallJointT<S>> ball = new BallJointT<S>(body.get(), frameAt<S>(Vec3T<S>::Zero()).get());
  auto* twist = ball->getTwistRangeController();
  twist->setEnable(true);
  twist->setRange(S(-0.3), S(0.6));
  sim->add(ball);
  const double T = 0.5;
  double highest = 0.0;
  for (int i = 0; i < 180; ++i) {
    body->addTorque(Vec3T<S>(0, 0, S(T)));
    sim->stepForward();
    highest = std::max(highest, double(ball->getTwistAngle()));
  }
  const double angle = double(ball->getTwistAngle());
  MESSAGE("twist at rest " << angle - 0.6 << " rad off the upper limit 0.6, overshoot " << highest - 0.6
                            << ", controller torque "
                           << double(twist->getCurrentForce()) << " N·m");
  // No overshoot (the row starts two steps before the limit); at rest the
  // deflection is ε T = 5e-9 rad (measured 5e-9 in double, 2.4e-8 in float).
  CHECK(std::abs(angle - 0.6) < pick<S>(1e-7, 1e-6));
  CHECK(highest < 0.6 + pick<S>(1e-7, 1e-6));
  CHECK(std::abs(double(twist->getCurrentForce()) + T) < pick<S>(1e-6, 1e-4));
  // At rest the controller's last measurement (start of the step) is the same angle.
  CHECK(std::abs(double(twist->getAngle()) - angle) < pick<S>(1e-9, 1e-6));
}

TEST_CASE_TEMPLATE("bad controller input names the joint and the value and changes nothing", S, float, double) {
  auto sim = directSimulation<S>();
  auto body = makeBody<S>(*sim, "b", S(1), Vec3T<S>::Zero());
  ref_ptr<HingeT<S>> hinge = new HingeT<S>(body.get(), frameAt<S>(Vec3T<S>::Zero()).get());
  hinge->setName("door");
  auto* friction = hinge->getFrictionController();
  friction->setFrictionCoefficient(S(0.2));
  const auto message = [](auto&& call) {
    try {
      call();
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  std::string m = message([&] { friction->setFrictionCoefficient(S(-0.1)); });
  CHECK(m.find("FrictionController of Hinge 'door'") != std::string::npos);
  CHECK(m.find("-0.1") != std::string::npos);
  m = message([&] { friction->setFrictionCoefficient(std::numeric_limits<S>::quiet_NaN()); });
  CHECK(m.find("nan") != std::string::npos);
  CHECK(friction->getFrictionCoefficient() == S(0.2));
  m = message([&] { friction->setMinimumStaticFrictionForceRange(S(1), S(2)); });
  CHECK(m.find("(1, 2)") != std::string::npos);
  CHECK(friction->getMinimumStaticFrictionForceRange().upper == S(0));

  ref_ptr<CylindricalJointT<S>> cylinder = new CylindricalJointT<S>(body.get(), frameAt<S>(Vec3T<S>::Zero()).get());
  m = message([&] { cylinder->getFrictionController(CylindricalJointT<S>::SECOND)->setFrictionCoefficient(S(-2)); });
  CHECK(m.find("FrictionController of CylindricalJoint") != std::string::npos);
  CHECK_THROWS_AS((void)cylinder->getFrictionController(2), Error);

  ref_ptr<BallJointT<S>> ball = new BallJointT<S>(body.get(), frameAt<S>(Vec3T<S>::Zero()).get());
  ball->setName("shoulder");
  auto* cone = ball->getConeLimit();
  cone->setLimitAngles(S(0.3), S(0.4));
  for (const std::pair<S, S>& angles : {std::pair<S, S>(std::numbers::pi_v<S> / 2, S(0.4)), std::pair<S, S>(S(0.3), S(0)),
                                       std::pair<S, S>(S(-0.1), S(0.4)), std::pair<S, S>(S(0.3), S(2)),
                                       std::pair<S, S>(std::numeric_limits<S>::quiet_NaN(), S(0.4))}) {
    const S a1 = angles.first, a2 = angles.second;  // not a structured binding: clang 14 cannot capture one
    m = message([&] { cone->setLimitAngles(a1, a2); });
    CAPTURE(m);
    CHECK(m.find("ConeLimit of BallJoint 'shoulder'") != std::string::npos);
    CHECK(m.find("got (") != std::string::npos);
    CHECK(cone->getLimitAngle(0) == S(0.3));
    CHECK(cone->getLimitAngle(1) == S(0.4));
  }
  m = message([&] { cone->setLimitAngles(S(0.3), S(2)); });
  CHECK(m.find("(0.3, 2)") != std::string::npos);

  auto* twist = ball->getTwistRangeController();
  twist->setRange(S(-0.5), S(0.5));
  m = message([&] { twist->setRange(S(0.7), S(0.2)); });
  CHECK(m.find("TwistRangeController of BallJoint 'shoulder'") != std::string::npos);
  CHECK(m.find("(0.7, 0.2)") != std::string::npos);
  CHECK_THROWS_AS(twist->setRange(std::numeric_limits<S>::quiet_NaN(), S(0.2)), Error);
  CHECK_THROWS_AS(twist->setRange(S(-4), S(0.2)), Error);
  CHECK(twist->getRange().lower == S(-0.5));
  CHECK(twist->getRange().upper == S(0.5));

  ball->getRotationalFrictionControllerV()->setFrictionCoefficient(S(0.1));
  CHECK_THROWS_AS(ball->setRotationalFrictionCoefficient(S(-1)), Error);
  CHECK(ball->getRotationalFrictionControllerU()->getFrictionCoefficient() == S(0.4167));
  CHECK(ball->getRotationalFrictionControllerV()->getFrictionCoefficient() == S(0.1));
  CHECK(!ball->getConeLimit()->getEnable());
  CHECK(!ball->getTwistRangeController()->getEnable());
  CHECK(!ball->getRotationalFrictionControllerN()->getEnable());
  CHECK(!hinge->getFrictionController()->getEnable());
}
