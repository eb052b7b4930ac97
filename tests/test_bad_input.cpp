#include <doctest/doctest.h>

#include <initializer_list>
#include <limits>
#include <string>
#include <string_view>

#include <spook/sim/assembly.hpp>
#include <spook/sim/simulation.hpp>

#include "scene_state.hpp"
#include "tolerance.hpp"

// Bad input throws spook::Error naming the object and the offending value,
// and leaves everything exactly as it was (DESIGN.md, "Errors").

namespace {

template <class S>
constexpr S kNaN = std::numeric_limits<S>::quiet_NaN();
template <class S>
constexpr S kInf = std::numeric_limits<S>::infinity();

/// A scene in a non-default state, so that a half-applied call would show.
template <class S>
struct Yard {
  using Body = spook::RigidBodyT<S>;
  using Vec3 = spook::Vec3T<S>;
  spook::ref_ptr<spook::SimulationT<S>> sim = new spook::SimulationT<S>();
  spook::ref_ptr<spook::SimulationT<S>> other = new spook::SimulationT<S>();
  spook::ref_ptr<Body> crate = new Body("crate");    // dynamic
  spook::ref_ptr<Body> hook = new Body("hook");      // kinematic, moving to a target
  spook::ref_ptr<Body> pallet = new Body("pallet");  // static
  spook::ref_ptr<Body> barrel = new Body("barrel");  // in the collection
  spook::ref_ptr<Body> stray = new Body("stray");    // in the other simulation
  spook::ref_ptr<spook::StepEventListenerT<S>> listener = new spook::StepEventListenerT<S>();
  spook::ref_ptr<spook::CollectionT<S>> stack = new spook::CollectionT<S>("stack");

  Yard() {
    crate->getMassProperties()->setMass(S(2));
    crate->getMassProperties()->setInertiaTensor(Vec3(S(1), S(2), S(2.5)));
    crate->getMassProperties()->setMassCoefficients(Vec3(S(0.5), S(0), S(0)));
    crate->setLinearVelocityDamping(S(0.25));
    crate->setAngularVelocityDamping(Vec3(S(0.5), S(0), S(1)));
    crate->setCmLocalTranslate(Vec3(S(0.1), S(0), S(-0.2)));
    crate->setPosition(Vec3(S(1), S(2), S(3)));
    crate->setRotation(spook::toQuat(spook::EulerAnglesT<S>{S(0.1), S(0.2), S(0.3)}));
    crate->setVelocity(S(1), S(0), S(2));
    crate->setAngularVelocity(S(0), S(3), S(0));
    hook->setMotionControl(Body::KINEMATICS);
    hook->moveTo(spook::makeTransform<S>(Vec3(S(0), S(0), S(5))), S(2));
    pallet->setMotionControl(Body::STATIC);
    stack->add(barrel);
    for (Body* b : {crate.get(), hook.get(), pallet.get()}) sim->add(b);
    sim->add(listener);
    sim->add(stack);
    other->add(stray);
    sim->stepForward();
    crate->addForce(S(0), S(4), S(0));
    crate->addTorque(S(1), S(0), S(0));
  }
  spook::test::SceneState<S> capture() const { return spook::test::SceneState<S>::capture(*sim, {}, {stray}); }
};

template <class Call>
std::string messageOf(Call& call) {
  try {
    call();
  } catch (const spook::Error& e) {
    return e.what();
  }
  return "(no spook::Error)";
}

/// `call` must throw spook::Error whose message holds every fragment (the
/// object's name, the value as printed), and leave the yard bit for bit as it was.
template <class S, class Call>
void checkRejected(const Yard<S>& yard, Call call, std::initializer_list<std::string_view> fragments) {
  const auto before = yard.capture();
  CHECK_THROWS_AS(call(), spook::Error);
  const std::string what = messageOf(call);
  for (std::string_view fragment : fragments)
    CHECK_MESSAGE(what.find(fragment) != std::string::npos, "'" << std::string(fragment) << "' not in: " << what);
  CHECK(spook::test::firstDifference(before, yard.capture()) == "");
}

template <class S>
spook::Mat3T<S> matrix(std::initializer_list<S> rowMajor) {
  spook::Mat3T<S> m;
  auto it = rowMajor.begin();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) m(r, c) = *it++;
  return m;
}

template <class S>
class CountedFrame : public spook::FrameT<S> {
 public:
  explicit CountedFrame(int* deletions) : deletions_(deletions) {}

 protected:
  ~CountedFrame() override { ++*deletions_; }

 private:
  int* deletions_;
};

}  // namespace

TEST_CASE_TEMPLATE("a mass that is zero, negative or NaN is rejected", S, float, double) {
  Yard<S> y;
  auto* mass = y.crate->getMassProperties();
  checkRejected(y, [&] { mass->setMass(S(0)); }, {"'crate'", "got 0"});
  checkRejected(y, [&] { mass->setMass(S(-1)); }, {"'crate'", "got -1"});
  checkRejected(y, [&] { mass->setMass(kNaN<S>); }, {"'crate'", "got nan"});
}

TEST_CASE_TEMPLATE("a non-finite position is rejected", S, float, double) {
  using Vec3 = spook::Vec3T<S>;
  Yard<S> y;
  checkRejected(y, [&] { y.crate->setPosition(Vec3(kNaN<S>, S(0), S(1))); }, {"'crate'", "got (nan, 0, 1)"});
  checkRejected(y, [&] { y.crate->setPosition(S(0), kInf<S>, S(1)); }, {"'crate'", "got (0, inf, 1)"});
  checkRejected(y, [&] { y.crate->setCmPosition(Vec3(S(0), S(0), -kInf<S>)); }, {"'crate'", "-inf"});
  checkRejected(y, [&] { y.crate->setCmLocalTranslate(Vec3(kNaN<S>, S(0), S(0))); }, {"'crate'", "nan"});
  auto X = spook::makeTransform<S>(Vec3(S(1), kNaN<S>, S(0)));
  checkRejected(y, [&] { y.crate->setTransform(X); }, {"'crate'", "got (1, nan, 0)"});
}

TEST_CASE_TEMPLATE("a NaN or zero rotation quaternion is rejected", S, float, double) {
  using Quat = spook::QuatT<S>;
  Yard<S> y;
  checkRejected(y, [&] { y.crate->setRotation(Quat(kNaN<S>, S(0), S(0), S(1))); }, {"'crate'", "nan"});
  checkRejected(y, [&] { y.crate->setRotation(Quat(S(0), S(0), S(0), S(0))); }, {"'crate'", "got (0, 0, 0, 0)"});
  spook::TransformT<S> X = spook::TransformT<S>::Identity();
  X.linear()(1, 1) = kNaN<S>;
  checkRejected(y, [&] { y.crate->setTransform(X); }, {"'crate'", "nan"});
}

// A finite quaternion whose squared norm overflows (components ~2e154 in
// double, ~3e19 in float) or underflows is still a rotation: it is
// normalized after scaling by its largest component, not stored as zero.
TEST_CASE_TEMPLATE("a finite quaternion too large or too small to square is normalized, not zeroed", S, float, double) {
  using Quat = spook::QuatT<S>;
  const S tol = spook::test::pick<S>(1e-14, 1e-6);
  const Quat q = spook::toQuat(spook::EulerAnglesT<S>{S(0.1), S(0.2), S(0.3)});
  const auto same = [&](const Quat& a) {
    return std::abs(std::abs(a.dot(q)) - S(1)) < tol && std::abs(a.norm() - S(1)) < tol;
  };
  for (const S scale :
       {spook::test::pick<S>(2e154, 3e19), spook::test::pick<S>(1e-170, 1e-25), std::numeric_limits<S>::max() / S(2)}) {
    CAPTURE(scale);
    const Quat scaled(Quat(q.coeffs() * scale));
    Yard<S> y;
    CHECK_NOTHROW(y.crate->setRotation(scaled));
    MESSAGE("setRotation of q * ", scale, " stored ", y.crate->getRotation().coeffs().transpose());
    CHECK(same(y.crate->getRotation()));
    for (int step = 0; step < 10; ++step) CHECK_NOTHROW(y.sim->stepForward());
    CHECK(y.crate->getPosition().allFinite());

    spook::ref_ptr<spook::FrameT<S>> parent = new spook::FrameT<S>(), child = new spook::FrameT<S>();
    child->setParent(parent.get());
    parent->setRotate(spook::toQuat(spook::EulerAnglesT<S>{S(0.5), S(0), S(0)}));
    CHECK_NOTHROW(child->setRotate(scaled));
    CHECK(same(child->getRotate()));
    CHECK_NOTHROW(child->setLocalRotate(scaled));
    CHECK(same(child->getLocalRotate()));
    spook::ref_ptr<spook::AssemblyT<S>> assembly = new spook::AssemblyT<S>("rig");
    CHECK_NOTHROW(assembly->setRotation(scaled));
    CHECK(same(assembly->getRotation()));
    CHECK(std::abs(spook::toEulerAngles<S>(scaled).z - S(0.3)) < tol);
    CHECK((spook::logRotation<S>(scaled) - spook::logRotation<S>(q)).norm() < tol);
  }
  // Zero and non-finite quaternions are still refused, the scene unchanged.
  Yard<S> y;
  checkRejected(y, [&] { y.crate->setRotation(Quat(kInf<S>, S(0), S(0), S(1))); }, {"'crate'", "inf"});
  checkRejected(y, [&] { y.crate->setRotation(Quat(S(0), S(0), S(0), S(0))); }, {"'crate'", "got (0, 0, 0, 0)"});
  spook::ref_ptr<spook::FrameT<S>> frame = new spook::FrameT<S>();
  CHECK_THROWS_AS(frame->setRotate(Quat(S(0), S(0), S(0), S(0))), spook::Error);
  CHECK_THROWS_AS(frame->setLocalRotate(Quat(S(0), kNaN<S>, S(0), S(1))), spook::Error);
  CHECK(frame->getRotate().coeffs() == Quat::Identity().coeffs());
}

// A zero rotation block is the transform form of the zero quaternion;
// Quat(Mat3::Zero()) reads as (1, 0, 0, 0), a half turn about x.
TEST_CASE_TEMPLATE("a transform whose rotation part is zero is rejected", S, float, double) {
  Yard<S> y;
  spook::TransformT<S> X = spook::TransformT<S>::Identity();
  X.linear().setZero();
  checkRejected(y, [&] { y.crate->setTransform(X); }, {"'crate'"});
}

TEST_CASE_TEMPLATE("a non-finite velocity or angular velocity is rejected", S, float, double) {
  Yard<S> y;
  checkRejected(y, [&] { y.crate->setVelocity(S(0), kNaN<S>, S(0)); }, {"'crate'", "got (0, nan, 0)"});
  checkRejected(y, [&] { y.crate->setAngularVelocity(kInf<S>, S(0), S(0)); }, {"'crate'", "got (inf, 0, 0)"});
}

TEST_CASE_TEMPLATE("a non-finite force or torque is rejected", S, float, double) {
  Yard<S> y;
  checkRejected(y, [&] { y.crate->addForce(S(1), S(0), kInf<S>); }, {"'crate'", "got (1, 0, inf)"});
  checkRejected(y, [&] { y.crate->addTorque(kNaN<S>, S(0), S(0)); }, {"'crate'", "got (nan, 0, 0)"});
}

TEST_CASE_TEMPLATE("addForceAtPosition rejects a non-finite force, point or resulting torque", S, float, double) {
  using Vec3 = spook::Vec3T<S>;
  Yard<S> y;
  const S big = std::numeric_limits<S>::max() / S(2);
  checkRejected(y, [&] { y.crate->addForceAtPosition(Vec3(kNaN<S>, S(0), S(0)), Vec3::Zero()); }, {"'crate'", "nan"});
  checkRejected(y, [&] { y.crate->addForceAtPosition(Vec3::UnitX(), Vec3(S(0), kInf<S>, S(0))); }, {"'crate'", "inf"});
  // Finite force and point whose moment r × F overflows.
  checkRejected(y, [&] { y.crate->addForceAtPosition(Vec3(S(0), big, S(0)), Vec3(big, S(0), S(0))); },
                {"'crate'", "torque", "inf"});
}

TEST_CASE_TEMPLATE("an inertia tensor with a negative eigenvalue is rejected", S, float, double) {
  Yard<S> y;
  const spook::Mat3T<S> I = matrix<S>({2, 0, 0, 0, 1, 3, 0, 3, 1});  // eigenvalues 2, 4, -2
  checkRejected(y, [&] { y.crate->getMassProperties()->setInertiaTensor(I); },
                {"'crate'", "positive definite", "got (2, 0, 0, 0, 1, 3, 0, 3, 1)"});
}

TEST_CASE_TEMPLATE("a non-symmetric inertia tensor is rejected", S, float, double) {
  Yard<S> y;
  const spook::Mat3T<S> I = matrix<S>({1, 0.5, 0, 0, 1, 0, 0, 0, 1});
  checkRejected(y, [&] { y.crate->getMassProperties()->setInertiaTensor(I); },
                {"'crate'", "symmetric", "got (1, 0.5, 0, 0, 1, 0, 0, 0, 1)"});
}

TEST_CASE_TEMPLATE("a singular inertia tensor is rejected", S, float, double) {
  Yard<S> y;
  const spook::Mat3T<S> I = matrix<S>({1, 0, 0, 0, 1, 0, 0, 0, 0});
  checkRejected(y, [&] { y.crate->getMassProperties()->setInertiaTensor(I); },
                {"'crate'", "got (1, 0, 0, 0, 1, 0, 0, 0, 0)"});
}

// Rows 1 and 2 are equal (determinant 0), but the eigensolver returns a
// smallest eigenvalue of about +1e-16 instead of 0.
TEST_CASE_TEMPLATE("a singular inertia tensor is rejected when round-off makes its smallest eigenvalue positive", S,
                   float, double) {
  Yard<S> y;
  const spook::Mat3T<S> I = matrix<S>({1, 1, 1, 1, 1, 1, 1, 1, 2});
  checkRejected(y, [&] { y.crate->getMassProperties()->setInertiaTensor(I); },
                {"'crate'", "got (1, 1, 1, 1, 1, 1, 1, 1, 2)"});
}

TEST_CASE_TEMPLATE("principal moments of inertia that are not positive are rejected", S, float, double) {
  using Vec3 = spook::Vec3T<S>;
  Yard<S> y;
  auto* mass = y.crate->getMassProperties();
  checkRejected(y, [&] { mass->setInertiaTensor(Vec3(S(1), S(0), S(1))); }, {"'crate'", "got (1, 0, 1)"});
  checkRejected(y, [&] { mass->setInertiaTensor(Vec3(S(1), S(-2), S(1))); }, {"'crate'", "got (1, -2, 1)"});
  checkRejected(y, [&] { mass->setInertiaTensor(Vec3(kNaN<S>, S(1), S(1))); }, {"'crate'", "got (nan, 1, 1)"});
}

TEST_CASE_TEMPLATE("negative or NaN mass coefficients are rejected", S, float, double) {
  using Vec3 = spook::Vec3T<S>;
  Yard<S> y;
  auto* mass = y.crate->getMassProperties();
  checkRejected(y, [&] { mass->setMassCoefficients(Vec3(S(-1), S(0), S(0))); }, {"'crate'", "got (-1, 0, 0)"});
  checkRejected(y, [&] { mass->setMassCoefficients(Vec3(S(0), kNaN<S>, S(0))); }, {"'crate'", "got (0, nan, 0)"});
}

TEST_CASE_TEMPLATE("negative or NaN velocity damping is rejected", S, float, double) {
  using Vec3 = spook::Vec3T<S>;
  Yard<S> y;
  checkRejected(y, [&] { y.crate->setLinearVelocityDamping(S(-1)); }, {"'crate'", "got (-1, -1, -1)"});
  checkRejected(y, [&] { y.crate->setLinearVelocityDamping(Vec3(S(0), S(0), kNaN<S>)); },
                {"'crate'", "got (0, 0, nan)"});
  checkRejected(y, [&] { y.crate->setAngularVelocityDamping(Vec3(S(0), S(-0.5), S(0))); },
                {"'crate'", "got (0, -0.5, 0)"});
  checkRejected(y, [&] { y.crate->setAngularVelocityDamping(kNaN<S>); }, {"'crate'", "got (nan, nan, nan)"});
}

TEST_CASE_TEMPLATE("a time step that is zero, negative, NaN or infinite is rejected", S, float, double) {
  Yard<S> y;
  checkRejected(y, [&] { y.sim->setTimeStep(S(0)); }, {"Simulation", "time step", "got 0"});
  checkRejected(y, [&] { y.sim->setTimeStep(S(-1)); }, {"Simulation", "time step", "got -1"});
  checkRejected(y, [&] { y.sim->setTimeStep(kNaN<S>); }, {"Simulation", "time step", "got nan"});
  checkRejected(y, [&] { y.sim->setTimeStep(kInf<S>); }, {"Simulation", "time step", "got inf"});
}

TEST_CASE_TEMPLATE("adding a body twice is rejected", S, float, double) {
  Yard<S> y;
  checkRejected(y, [&] { y.sim->add(y.crate); }, {"crate", "already added"});
  checkRejected(y, [&] { y.sim->add(y.barrel); }, {"barrel", "already added"});  // added with its collection
}

TEST_CASE_TEMPLATE("adding a body that belongs to another simulation is rejected", S, float, double) {
  Yard<S> y;
  const auto otherBefore = spook::test::SceneState<S>::capture(*y.other);
  checkRejected(y, [&] { y.sim->add(y.stray); }, {"stray", "another simulation"});
  CHECK(spook::test::firstDifference(otherBefore, spook::test::SceneState<S>::capture(*y.other)) == "");
}

TEST_CASE_TEMPLATE("adding a listener twice is rejected", S, float, double) {
  Yard<S> y;
  checkRejected(y, [&] { y.sim->add(y.listener); }, {"StepEventListener", "already added"});
}

TEST_CASE_TEMPLATE("removing a body, listener or collection that was never added is rejected", S, float, double) {
  Yard<S> y;
  spook::ref_ptr<spook::RigidBodyT<S>> loose = new spook::RigidBodyT<S>("loose");
  spook::ref_ptr<spook::StepEventListenerT<S>> idle = new spook::StepEventListenerT<S>();
  spook::ref_ptr<spook::CollectionT<S>> spare = new spook::CollectionT<S>("spare");
  checkRejected(y, [&] { y.sim->remove(loose); }, {"loose", "never added"});
  checkRejected(y, [&] { y.sim->remove(y.stray); }, {"stray", "never added"});  // in the other simulation
  checkRejected(y, [&] { y.sim->remove(idle); }, {"StepEventListener", "never added"});
  checkRejected(y, [&] { y.sim->remove(spare); }, {"spare", "never added"});
}

TEST_CASE_TEMPLATE("stepTo a time in the past or NaN is rejected", S, float, double) {
  Yard<S> y;
  checkRejected(y, [&] { y.sim->stepTo(S(-1)); }, {"Simulation", "past", "got -1"});
  checkRejected(y, [&] { y.sim->stepTo(kNaN<S>); }, {"Simulation", "got nan"});
}

TEST_CASE_TEMPLATE("moveTo on a body that is not kinematic is rejected", S, float, double) {
  Yard<S> y;
  const auto target = spook::makeTransform<S>(spook::Vec3T<S>(S(0), S(0), S(1)));
  checkRejected(y, [&] { y.crate->moveTo(target, S(1)); }, {"'crate'", "KINEMATICS"});
  checkRejected(y, [&] { y.pallet->moveTo(target, S(1)); }, {"'pallet'", "KINEMATICS"});
}

TEST_CASE_TEMPLATE("moveTo with a duration that is not positive and finite is rejected", S, float, double) {
  Yard<S> y;
  const auto target = spook::makeTransform<S>(spook::Vec3T<S>(S(0), S(0), S(1)));
  checkRejected(y, [&] { y.hook->moveTo(target, S(0)); }, {"'hook'", "got 0"});
  checkRejected(y, [&] { y.hook->moveTo(target, S(-1)); }, {"'hook'", "got -1"});
  checkRejected(y, [&] { y.hook->moveTo(target, kNaN<S>); }, {"'hook'", "got nan"});
}

TEST_CASE_TEMPLATE("a duplicate attachment name is rejected and the first attachment kept", S, float, double) {
  Yard<S> y;
  spook::ref_ptr<spook::FrameT<S>> first = new spook::FrameT<S>(), second = new spook::FrameT<S>();
  y.crate->addAttachment(first, "lug");
  checkRejected(y, [&] { y.crate->addAttachment(second, "lug"); }, {"'crate'", "got lug"});
  CHECK(y.crate->getAttachment("lug") == first.get());
  CHECK(second->getParent() == nullptr);
}

// AGX style hands a fresh object straight to the API: `addAttachment(new Frame(), "lug")`.
TEST_CASE_TEMPLATE("a rejected attachment passed as a raw new is deleted, not leaked", S, float, double) {
  int deletions = 0;
  {
    Yard<S> y;
    y.crate->addAttachment(new CountedFrame<S>(&deletions), "lug");
    CHECK_THROWS_AS(y.crate->addAttachment(new CountedFrame<S>(&deletions), "lug"), spook::Error);
  }
  CHECK(deletions == 2);
}

TEST_CASE_TEMPLATE("a frame cannot become its own ancestor", S, float, double) {
  Yard<S> y;
  spook::ref_ptr<spook::FrameT<S>> lug = new spook::FrameT<S>(), shackle = new spook::FrameT<S>();
  y.crate->addAttachment(lug, "lug");
  shackle->setParent(lug);
  checkRejected(y, [&] { lug->setParent(lug); }, {"Frame", "cycle"});
  checkRejected(y, [&] { lug->setParent(shackle); }, {"Frame", "cycle"});
  checkRejected(y, [&] { y.crate->getFrame()->setParent(shackle); }, {"Frame", "cycle"});
  CHECK(lug->getParent() == y.crate->getFrame());
  CHECK(shackle->getParent() == lug.get());
  CHECK(y.crate->getFrame()->getParent() == nullptr);
}
