#include <doctest/doctest.h>

#include <string>
#include <type_traits>

#include <spook/collide/shapes/box.hpp>
#include <spook/collide/shapes/composite.hpp>
#include <spook/collide/shapes/sphere.hpp>
#include <spook/dynamics/rigid_body.hpp>
#include <spook/sim/simulation.hpp>

#include "scene_state.hpp"
#include "shape_helpers.hpp"
#include "tolerance.hpp"

using spook::test::at;
using spook::test::relative;

using spook::test::pick;

namespace {

template <class S>
spook::ref_ptr<spook::MaterialT<S>> material(double density) {
  spook::ref_ptr<spook::MaterialT<S>> m = new spook::MaterialT<S>("m");
  m->getBulkMaterial()->setDensity(S(density));
  return m;
}

}  // namespace

// Box of half extents (0.5, 0.25, 0.1) at density 800: m = 800·0.1 = 80 kg,
// I = m/3 (b² + c², a² + c², a² + b²) about its center.
TEST_CASE_TEMPLATE("a body's mass, center and inertia come from its geometry's volume and density", S, float, double) {
  const S tol = pick<S>(1e-12, 1e-6);
  spook::ref_ptr<spook::RigidBodyT<S>> body = new spook::RigidBodyT<S>("crate");
  spook::ref_ptr<spook::GeometryT<S>> g = new spook::GeometryT<S>(new spook::BoxT<S>(spook::Vec3T<S>(S(0.5), S(0.25), S(0.1))));
  g->setMaterial(material<S>(800));
  g->setLocalTransform(at<S>(1, 2, 3));
  body->add(g);
  const auto* mp = body->getMassProperties();
  CHECK(std::abs(mp->getMass() - S(80)) <= tol * S(80));
  CHECK((body->getCmLocalTranslate() - spook::Vec3T<S>(S(1), S(2), S(3))).norm() <= tol);
  const spook::Vec3T<S> expected = spook::Vec3T<S>(S(0.0725), S(0.26), S(0.3125)) * S(80.0 / 3.0);
  CHECK(relative<S>(mp->getInertiaTensor(), spook::Mat3T<S>(expected.asDiagonal())) <= tol);
  CHECK(g->getRigidBody() == body.get());
}

// Two geometries must give the same mass properties as one composite shape
// of the same parts (the composite's parallel-axis transfer is tested
// against closed forms in test_shapes.cpp).
TEST_CASE_TEMPLATE("two offset geometries combine by the parallel-axis theorem", S, float, double) {
  const S tol = pick<S>(1e-12, 1e-5);
  const spook::QuatT<S> turn(Eigen::AngleAxis<S>(S(0.7), spook::Vec3T<S>(S(1), S(2), S(3)).normalized()));
  spook::ref_ptr<spook::BoxT<S>> box = new spook::BoxT<S>(spook::Vec3T<S>(S(0.3), S(0.2), S(0.4)));
  spook::ref_ptr<spook::SphereT<S>> ball = new spook::SphereT<S>(S(0.25));
  spook::ref_ptr<spook::RigidBodyT<S>> body = new spook::RigidBodyT<S>();
  body->add(new spook::GeometryT<S>(box, at<S>(0.5, 0, 0, turn)));
  body->add(new spook::GeometryT<S>(ball, at<S>(-1, 0.5, 0.2)));
  spook::ref_ptr<spook::CompositeT<S>> both = new spook::CompositeT<S>();
  both->add(box, at<S>(0.5, 0, 0, turn));
  both->add(ball, at<S>(-1, 0.5, 0.2));
  const S mass = S(1000) * both->getVolume();
  const spook::Vec3T<S> c = both->getCenterOfVolume();
  const spook::Mat3T<S> aboutCenter =
      both->calculateInertia(mass).matrix() - mass * (c.squaredNorm() * spook::Mat3T<S>::Identity() - c * c.transpose());
  CHECK(std::abs(body->getMassProperties()->getMass() - mass) <= tol * mass);
  CHECK((body->getCmLocalTranslate() - c).norm() <= tol);
  CHECK(relative<S>(body->getMassProperties()->getInertiaTensor(), aboutCenter) <= tol);
}

TEST_CASE_TEMPLATE("mass follows geometry and material changes but not material parameter edits", S, float, double) {
  const S tol = pick<S>(1e-12, 1e-6);
  spook::ref_ptr<spook::RigidBodyT<S>> body = new spook::RigidBodyT<S>();
  spook::ref_ptr<spook::GeometryT<S>> g = new spook::GeometryT<S>(new spook::BoxT<S>(spook::Vec3T<S>::Constant(S(0.5))));
  body->add(g);
  CHECK(std::abs(body->getMassProperties()->getMass() - S(1000)) <= tol * S(1000));  // default density, 1 m³
  const auto steel = material<S>(7750);
  g->setMaterial(steel);
  CHECK(std::abs(body->getMassProperties()->getMass() - S(7750)) <= tol * S(7750));
  steel->getBulkMaterial()->setDensity(S(100));  // a parameter edit: no update
  CHECK(std::abs(body->getMassProperties()->getMass() - S(7750)) <= tol * S(7750));
  body->updateMassProperties();
  CHECK(std::abs(body->getMassProperties()->getMass() - S(100)) <= tol * S(100));
  g->add(new spook::SphereT<S>(S(1)), at<S>(3, 0, 0));  // adding a shape updates
  const S sphereVolume = S(4.0 / 3.0 * 3.14159265358979323846);
  CHECK(std::abs(body->getMassProperties()->getMass() - S(100) * (S(1) + sphereVolume)) <= tol * S(600));
  CHECK(body->remove(g.get()));
  CHECK(g->getRigidBody() == nullptr);
  CHECK(body->getGeometries().empty());
}

TEST_CASE_TEMPLATE("a hand-set mass stays and scales the generated inertia", S, float, double) {
  const S tol = pick<S>(1e-12, 1e-6);
  spook::ref_ptr<spook::RigidBodyT<S>> body = new spook::RigidBodyT<S>();
  body->getMassProperties()->setMass(S(2));
  body->add(new spook::GeometryT<S>(new spook::SphereT<S>(S(0.5))));
  CHECK(body->getMassProperties()->getMass() == S(2));
  CHECK(std::abs(body->getMassProperties()->getInertiaTensor()(0, 0) - S(0.2)) <= tol);  // 2/5 m r²
  CHECK(body->getMassProperties()->getAutoGenerateMask() ==
        (spook::MassPropertiesT<S>::CM_OFFSET | spook::MassPropertiesT<S>::INERTIA));
}

TEST_CASE_TEMPLATE("moving the center of mass keeps every body point's velocity", S, float, double) {
  const S tol = pick<S>(1e-12, 1e-5);
  spook::ref_ptr<spook::RigidBodyT<S>> body = new spook::RigidBodyT<S>();
  body->setAngularVelocity(S(0), S(0), S(2));
  body->setVelocity(S(1), S(0), S(0));
  const spook::Vec3T<S> probe(S(0.3), S(-0.4), S(0.1));
  const spook::Vec3T<S> before = body->getVelocityAtPoint(probe);
  body->add(new spook::GeometryT<S>(new spook::SphereT<S>(S(0.5)), at<S>(1, 0, 0)));
  CHECK((body->getCmPosition() - spook::Vec3T<S>(S(1), S(0), S(0))).norm() <= tol);
  CHECK((body->getVelocityAtPoint(probe) - before).norm() <= tol);
}

TEST_CASE_TEMPLATE("bad geometry input throws and leaves body and geometry unchanged", S, float, double) {
  spook::ref_ptr<spook::RigidBodyT<S>> a = new spook::RigidBodyT<S>("a"), b = new spook::RigidBodyT<S>("b");
  spook::ref_ptr<spook::GeometryT<S>> g = new spook::GeometryT<S>(new spook::SphereT<S>(S(1)), at<S>(0, 0, 0), "ball");
  a->add(g);
  const S mass = a->getMassProperties()->getMass();
  CHECK_THROWS_WITH_AS(b->add(g), doctest::Contains("another body, got ball"), spook::Error);
  CHECK_THROWS_WITH_AS(a->add(g), doctest::Contains("already added"), spook::Error);
  CHECK_THROWS_WITH_AS(a->add(nullptr), doctest::Contains("got nullptr"), spook::Error);
  CHECK_THROWS_WITH_AS(g->add(nullptr), doctest::Contains("Geometry 'ball'"), spook::Error);
  CHECK_THROWS_WITH_AS(g->setMaterial(nullptr), doctest::Contains("got nullptr"), spook::Error);
  CHECK_THROWS_WITH_AS(g->setEnableCollisions(g.get(), false), doctest::Contains("itself"), spook::Error);
  CHECK(b->getGeometries().empty());
  CHECK(a->getGeometries().size() == 1);
  CHECK(g->getShapes().size() == 1);
  CHECK(a->getMassProperties()->getMass() == mass);
}

// A box of half extents 1e200 m (1e30 m in float) has a volume of inf m³;
// a density of 1e300 kg/m³ (1e38 in float) on a box of half extents 100 m
// (10 m) makes m/3·(b² + c²), or already m, overflow. Each change is refused
// before it is made, naming the geometry or body and the offending value.
TEST_CASE_TEMPLATE("a geometry, shape, material or placement whose mass would overflow is refused before it is in place",
                   S, float, double) {
  using V = spook::Vec3T<S>;
  const double hugeSize = pick<S>(1e200, 1e30);
  constexpr bool isDouble = std::is_same_v<S, double>;
  const std::string hugeText = isDouble ? "1e+200" : "1e+30";
  spook::ref_ptr<spook::SimulationT<S>> sim = new spook::SimulationT<S>();
  spook::ref_ptr<spook::RigidBodyT<S>> crate = new spook::RigidBodyT<S>("crate");
  spook::ref_ptr<spook::GeometryT<S>> lid =
      new spook::GeometryT<S>(new spook::BoxT<S>(V(S(100), S(100), S(pick<S>(100, 10)))), at<S>(0, 0, 0), "lid");
  crate->add(lid);
  crate->add(new spook::GeometryT<S>(new spook::BoxT<S>(V::Ones()), at<S>(0, 0, 0), "base"));
  crate->setVelocity(S(1), S(2), S(3));
  crate->setAngularVelocity(S(0.5), S(0), S(0));
  sim->add(crate);
  sim->stepForward();
  const auto before = spook::test::SceneState<S>::capture(*sim);
  const S mass = crate->getMassProperties()->getMass();
  const auto unchanged = [&] {
    CHECK(spook::test::firstDifference(before, spook::test::SceneState<S>::capture(*sim)) == "");
    CHECK(crate->getMassProperties()->getMass() == mass);
    CHECK(crate->getGeometries().size() == 2);
    CHECK(lid->getShapes().size() == 1);
    CHECK(lid->getMaterial() == spook::GeometryT<S>::defaultMaterial());
    CHECK(lid->getLocalTransform().matrix() == at<S>(0, 0, 0).matrix());
  };

  spook::ref_ptr<spook::GeometryT<S>> huge =
      new spook::GeometryT<S>(new spook::BoxT<S>(V::Constant(S(hugeSize))), at<S>(0, 0, 0), "huge");
  // The message of the spook::Error that `f` throws ("" when it throws none).
  const auto thrown = [](const auto& f) -> std::string {
    try {
      f();
    } catch (const spook::Error& e) {
      return e.what();
    }
    return "";
  };
  const auto contains = [](const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
  };

  std::string message = thrown([&] { crate->add(huge); });
  CAPTURE(message);
  CHECK(contains(message, "Geometry 'huge': Box of bounding half extents (" + hugeText));
  CHECK(huge->getRigidBody() == nullptr);
  CHECK(huge->getFrame()->getParent() == nullptr);
  unchanged();

  message = thrown([&] { lid->add(new spook::BoxT<S>(V::Constant(S(hugeSize)))); });
  CHECK(contains(message, "Geometry 'lid': Box of bounding half extents (" + hugeText));
  unchanged();

  const auto dense = material<S>(pick<S>(1e300, 1e38));
  message = thrown([&] { lid->setMaterial(dense); });
  CHECK(contains(message, "Geometry 'lid': Box of bounding half extents (100, 100, "));
  CHECK(contains(message, isDouble ? "density 1e+300" : "density 1e+38"));
  unchanged();

  // Moved 1e200 m (1e30 m) away from the base, the body's parallel-axis
  // terms m·d² (or in float already the moment m·d) overflow.
  message = thrown([&] { lid->setLocalTransform(at<S>(hugeSize, 0, 0)); });
  CHECK(contains(message, "RigidBody 'crate'"));
  CHECK((contains(message, "inf") || contains(message, "must be finite")));
  unchanged();
  message = thrown([&] { lid->setPosition(V(S(hugeSize), S(0), S(0))); });
  CHECK(contains(message, "RigidBody 'crate'"));
  unchanged();

  // A density raised on the material in place is only seen by
  // updateMassProperties, which refuses it the same way.
  spook::ref_ptr<spook::MaterialT<S>> steel = material<S>(7800);
  lid->setMaterial(steel);
  sim->stepForward();
  const auto withSteel = spook::test::SceneState<S>::capture(*sim);
  steel->getBulkMaterial()->setDensity(S(pick<S>(1e300, 1e38)));
  CHECK_THROWS_WITH_AS(crate->updateMassProperties(), doctest::Contains("Geometry 'lid'"), spook::Error);
  CHECK(spook::test::firstDifference(withSteel, spook::test::SceneState<S>::capture(*sim)) == "");

  // Still usable once the density is sane again.
  steel->getBulkMaterial()->setDensity(S(7800));
  crate->add(new spook::GeometryT<S>(new spook::SphereT<S>(S(1))));
  CHECK(crate->getGeometries().size() == 3);
}

// A shape changed after it is in place (resized, a child added to a
// composite, nested composites included) is checked like a new one: the
// body's generated mass follows, and a change whose mass would overflow is
// refused, leaving the shape and the whole scene as they were. A shape let
// go by its geometry (or a geometry by its body) no longer reaches the body.
TEST_CASE_TEMPLATE("a shape changed in place updates its body's mass, or is refused leaving shape and scene unchanged",
                   S, float, double) {
  using V = spook::Vec3T<S>;
  const S tol = pick<S>(1e-12, 1e-6);
  const double hugeSize = pick<S>(1e200, 1e30);
  spook::ref_ptr<spook::SimulationT<S>> sim = new spook::SimulationT<S>();
  spook::ref_ptr<spook::RigidBodyT<S>> body = new spook::RigidBodyT<S>("crane hook");
  spook::ref_ptr<spook::SphereT<S>> ball = new spook::SphereT<S>(S(0.5));
  spook::ref_ptr<spook::CompositeT<S>> outer = new spook::CompositeT<S>(), inner = new spook::CompositeT<S>();
  inner->add(new spook::BoxT<S>(V::Constant(S(0.5))));  // 1 m³
  outer->add(inner, at<S>(-2, 0, 0));
  spook::ref_ptr<spook::GeometryT<S>> hook = new spook::GeometryT<S>(ball, at<S>(0, 0, 0), "hook");
  hook->add(outer);
  body->add(hook);
  sim->add(body);
  const S pi = S(3.14159265358979323846);
  const auto mass = [&] { return body->getMassProperties()->getMass(); };
  CHECK(std::abs(mass() - S(1000) * (S(1) + pi / S(6))) <= tol * mass());

  ball->setRadius(S(1));
  CHECK(std::abs(mass() - S(1000) * (S(1) + S(4) * pi / S(3))) <= tol * mass());
  inner->add(new spook::BoxT<S>(V::Constant(S(0.5))), at<S>(0, 0, 3));
  const S expected = S(1000) * (S(2) + S(4) * pi / S(3));
  CHECK(std::abs(mass() - expected) <= tol * mass());
  // Center of mass: the ball at 0, boxes at (-2, 0, 0) and (-2, 0, 3).
  const V center = S(1000) * (V(S(-2), S(0), S(0)) + V(S(-2), S(0), S(3))) / expected;
  CHECK((body->getCmPosition() - center).norm() <= tol * S(10));

  sim->stepForward();
  const auto before = spook::test::SceneState<S>::capture(*sim);
  const auto unchanged = [&] {
    CHECK(spook::test::firstDifference(before, spook::test::SceneState<S>::capture(*sim)) == "");
    CHECK(mass() == before.bodyStates.front().mass);
    CHECK(ball->getRadius() == S(1));
    CHECK(inner->getChildren().size() == 2);
    CHECK(outer->getChildren().size() == 1);
  };
  CHECK_THROWS_WITH_AS(ball->setRadius(S(hugeSize)), doctest::Contains("Geometry 'hook'"), spook::Error);
  unchanged();
  CHECK_THROWS_WITH_AS(inner->add(new spook::BoxT<S>(V::Constant(S(hugeSize)))), doctest::Contains("Geometry 'hook'"),
                       spook::Error);
  unchanged();
  CHECK_THROWS_WITH_AS(inner->add(new spook::BoxT<S>(V::Constant(S(1))), at<S>(hugeSize, 0, 0)),
                       doctest::Contains("Geometry 'hook': Composite"), spook::Error);
  unchanged();

  // Let go: removed from its geometry, the ball changes alone; so does the
  // composite of a geometry removed from the body.
  CHECK(hook->remove(ball.get()));
  const S withoutBall = mass();
  ball->setRadius(S(hugeSize));
  CHECK(mass() == withoutBall);
  CHECK(body->remove(hook.get()));
  const S empty = mass();
  inner->add(new spook::BoxT<S>(V::Constant(S(hugeSize))));
  CHECK(mass() == empty);
  hook = nullptr;  // the composites outlive the geometry that held them
  inner->add(new spook::SphereT<S>(S(1)));
  CHECK(inner->getChildren().size() == 4);
}

TEST_CASE_TEMPLATE("pairwise collision disabling is symmetric and forgets dead partners", S, float, double) {
  spook::ref_ptr<spook::GeometryT<S>> a = new spook::GeometryT<S>(), b = new spook::GeometryT<S>();
  a->setEnableCollisions(b.get(), false);
  CHECK_FALSE(a->getEnableCollisions(b.get()));
  CHECK_FALSE(b->getEnableCollisions(a.get()));
  b->setEnableCollisions(a.get(), true);
  CHECK(a->getEnableCollisions(b.get()));
  a->addGroup(7);
  a->addGroup("wheels");
  CHECK(a->hasGroup(7));
  CHECK(a->hasGroup(std::string("wheels")));
  CHECK_FALSE(a->hasGroup(8));
}
