#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <string>

#include "joint_scenes.hpp"

using namespace spook;
using spook::test::frameAt;
using spook::test::makeBody;

namespace {
// The message of the spook::Error thrown by f, or "" when none was thrown.
template <class F>
std::string errorOf(F&& f) {
  try {
    f();
  } catch (const spook::Error& e) {
    return e.what();
  }
  return "";
}
bool mentions(const std::string& message, const std::string& part) { return message.find(part) != std::string::npos; }
}  // namespace

TEST_CASE("bad constraint input throws spook::Error naming the constraint and the value") {
  SimulationRef sim = new Simulation();
  auto a = makeBody<double>(*sim, "arm", 1.0, Vec3T<double>(0, 0, 0));
  auto b = makeBody<double>(*sim, "boom", 1.0, Vec3T<double>(1, 0, 0));
  RigidBodyRef ground = new RigidBody("ground");
  ground->setMotionControl(RigidBody::STATIC);
  sim->add(ground);

  const std::string self = errorOf([&] { HingeRef h = new Hinge(a.get(), nullptr, a.get()); });
  CHECK(mentions(self, "Hinge"));
  CHECK(mentions(self, "itself"));
  CHECK(mentions(self, "arm"));

  CHECK(mentions(errorOf([&] { HingeRef h = new Hinge(nullptr, nullptr); }), "first body"));
  const std::string statics = errorOf([&] { LockJointRef l = new LockJoint(ground.get()); });
  CHECK(mentions(statics, "LockJoint"));
  CHECK(mentions(statics, "not static"));

  HingeRef hinge = new Hinge(a.get(), nullptr, b.get());
  hinge->setName("elbow");
  const std::string range = errorOf([&] { hinge->getRange1D()->setRange(1.0, -1.0); });
  CHECK(mentions(range, "Range1D"));
  CHECK(mentions(range, "(1, -1)"));
  CHECK(mentions(errorOf([&] { hinge->getMotor1D()->setForceRange(5.0, -5.0); }), "(5, -5)"));
  const std::string compliance = errorOf([&] { hinge->setCompliance(-1e-8); });
  CHECK(mentions(compliance, "compliance"));
  CHECK(mentions(compliance, "-1e-08"));
  CHECK(mentions(errorOf([&] { hinge->setDamping(-0.1, Hinge::ROTATIONAL_1); }), "-0.1"));
  CHECK(mentions(errorOf([&] { hinge->setCompliance(1e-6, 7); }), "elbow"));
  CHECK(mentions(errorOf([&] { hinge->setCompliance(std::numeric_limits<double>::quiet_NaN()); }), "nan"));
  CHECK(mentions(errorOf([&] { hinge->getMotor1D()->setSpeed(std::numeric_limits<double>::infinity()); }), "inf"));
  // The failed calls changed nothing.
  CHECK(hinge->getCompliance(Hinge::ROTATIONAL_1) == 1e-8);
  CHECK(hinge->getDamping(Hinge::ROTATIONAL_1) == 2.0 / 60.0);
  CHECK(std::isinf(hinge->getRange1D()->getRange().upper));

  // A frame fixed to another body.
  FrameRef foreign = new Frame();
  b->addAttachment(foreign, "socket");
  const std::string parent = errorOf([&] { HingeRef h = new Hinge(a.get(), foreign.get()); });
  CHECK(mentions(parent, "parent"));
  CHECK(foreign->getParent() == b->getFrame());
}

TEST_CASE("a failed constraint add leaves the simulation unchanged") {
  SimulationRef sim = new Simulation(), other = new Simulation();
  auto a = makeBody<double>(*sim, "arm", 1.0, Vec3T<double>(0, 0, 0));
  auto stranger = makeBody<double>(*other, "stranger", 1.0, Vec3T<double>(0, 0, 0));
  HingeRef hinge = new Hinge(a.get(), nullptr, stranger.get());
  CHECK(mentions(errorOf([&] { sim->add(hinge); }), "add the bodies first"));
  CHECK(sim->getConstraints().empty());

  HingeRef ok = new Hinge(a.get(), nullptr);
  sim->add(ok);
  CHECK(mentions(errorOf([&] { sim->add(ok); }), "already added"));
  CHECK(sim->getConstraints().size() == 1);
  CHECK(mentions(errorOf([&] { other->add(ok); }), "another simulation"));
  CHECK(other->getConstraints().empty());
  // A body later made static with its only partner the world: refused at add.
  auto c = makeBody<double>(*sim, "c", 1.0, Vec3T<double>(0, 0, 0));
  HingeRef late = new Hinge(c.get(), nullptr);
  c->setMotionControl(RigidBody::STATIC);
  CHECK(mentions(errorOf([&] { sim->add(late); }), "not static"));
  CHECK(sim->getConstraints().size() == 1);
}

TEST_CASE("collections carry constraints in and out of a simulation") {
  SimulationRef sim = new Simulation();
  CollectionRef crane = new Collection("crane");
  RigidBodyRef boom = new RigidBody("boom");
  boom->getMassProperties()->setMass(10.0);
  crane->add(boom);
  HingeRef slew = new Hinge(boom.get(), nullptr);
  crane->add(slew);
  sim->add(crane);
  CHECK(sim->contains(slew.get()));
  sim->stepForward();
  CHECK(sim->getStatistics().solver.numRows == 5);
  sim->remove(crane.get());
  CHECK_FALSE(sim->contains(slew.get()));
  CHECK(sim->getConstraints().empty());
}
