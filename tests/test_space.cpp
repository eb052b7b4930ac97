#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <spook/collide/collide_through.hpp>  // ColliderMatrixT, the colliders of a shape list
#include <spook/collide/space.hpp>
#include <spook/sim/simulation.hpp>

#include "shape_helpers.hpp"
#include "tolerance.hpp"

using spook::test::at;

using spook::test::pick;

namespace {


// A flat floor at z = 0 of cells × cells squares of side `cell`, two
// triangles each, centered on the origin.
template <class S>
spook::ref_ptr<spook::TrimeshT<S>> floorMesh(int cells, double cell) {
  std::vector<spook::Vec3T<S>> vertices;
  std::vector<std::array<int, 3>> triangles;
  const double half = 0.5 * cells * cell;
  for (int j = 0; j <= cells; ++j)
    for (int i = 0; i <= cells; ++i) vertices.emplace_back(S(i * cell - half), S(j * cell - half), S(0));
  const auto index = [&](int i, int j) { return i + (cells + 1) * j; };
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i) {
      triangles.push_back({index(i, j), index(i + 1, j), index(i + 1, j + 1)});
      triangles.push_back({index(i, j), index(i + 1, j + 1), index(i, j + 1)});
    }
  return new spook::TrimeshT<S>(vertices, triangles);
}

template <class S>
spook::ref_ptr<spook::RigidBodyT<S>> boxBody(double z) {
  spook::ref_ptr<spook::RigidBodyT<S>> body = new spook::RigidBodyT<S>("box");
  body->add(new spook::GeometryT<S>(new spook::BoxT<S>(spook::Vec3T<S>(S(0.5), S(0.5), S(0.5))), at<S>(0, 0, 0), "box"));
  body->setPosition(S(0.013), S(-0.021), S(z));
  return body;
}

template <class S>
std::size_t enabledPoints(const spook::SpaceT<S>& space) {
  std::size_t n = 0;
  for (const auto& c : space.getGeometryContacts()) n += c.getNumEnabledPoints();
  return n;
}

}  // namespace

// The seeds' table (course slides, "Collider Matrix"): every pair but the
// three between static shapes (Plane–Plane, Plane–HeightField,
// HeightField–HeightField).
TEST_CASE("the full shape list renders the seeds' collider matrix") {
  const std::vector<std::string> names = {"Box",   "Capsule", "Convex",  "Cylinder",  "Line",
                                          "Plane", "Sphere",  "Trimesh", "Composite", "HeightField"};
  std::string expected = "|";
  for (const auto& n : names) expected += " | " + n;
  expected += " |\n|---";
  for (std::size_t i = 0; i < names.size(); ++i) expected += "|---";
  expected += "|\n";
  for (const auto& row : names) {
    expected += "| " + row;
    for (const auto& column : names) {
      const bool hole = (row == "Plane" || row == "HeightField") && (column == "Plane" || column == "HeightField");
      expected += hole ? " | -" : " | X";
    }
    expected += " |\n";
  }
  CHECK(spook::ColliderMatrixT<double, spook::AllShapes>::describe() == expected);
  CHECK(spook::ColliderMatrixT<float, spook::AllShapes>::describe() == expected);
  CHECK(spook::ColliderMatrixT<double, spook::ShapeList<spook::SphereT, spook::PlaneT>>::describe() ==
        "| | Sphere | Plane |\n|---|---|---|\n| Sphere | X | X |\n| Plane | X | - |\n");
}

TEST_CASE_TEMPLATE("a box lying on a plane touches it at its four bottom corners", S, float, double) {
  spook::ref_ptr<spook::SpaceT<S>> space = new spook::SpaceT<S>();
  space->add(new spook::GeometryT<S>(new spook::PlaneT<S>(spook::Vec3T<S>::UnitZ())));
  std::vector<spook::ref_ptr<spook::RigidBodyT<S>>> bodies{boxBody<S>(0.49)};
  space->update(bodies);
  REQUIRE(space->getGeometryContacts().size() == 1);
  const auto& points = space->getGeometryContacts()[0].points();
  CHECK(points.size() == 4);
  for (const auto& p : points) {
    CHECK(std::abs(p.depth - S(0.01)) <= pick<S>(1e-12, 1e-6));
    CHECK(std::abs(std::abs(p.normal.z()) - S(1)) <= pick<S>(1e-12, 1e-6));
  }
}

// 100 × 100 cells of 0.1 m: 20,000 triangles, about 200 under the box.
TEST_CASE_TEMPLATE("contact reduction keeps at most four points of a box on a fine mesh at resolution 2", S, float,
                   double) {
  spook::ref_ptr<spook::SpaceT<S>> space = new spook::SpaceT<S>();
  spook::ref_ptr<spook::GeometryT<S>> floor = new spook::GeometryT<S>(floorMesh<S>(100, 0.1));
  REQUIRE(static_cast<const spook::TrimeshT<S>*>(floor->getShape())->getNumTriangles() == 20000);
  space->add(floor);
  std::vector<spook::ref_ptr<spook::RigidBodyT<S>>> bodies{boxBody<S>(0.495)};

  space->setContactReductionMode(spook::ContactReductionMode::REDUCE_NONE);
  space->update(bodies);
  const std::size_t all = enabledPoints(*space);
  space->setContactReductionMode(spook::ContactReductionMode::REDUCE_GEOMETRY);
  space->update(bodies);
  const std::size_t atTwo = enabledPoints(*space);
  space->setContactBinResolution(3);
  space->update(bodies);
  const std::size_t atThree = enabledPoints(*space);
  MESSAGE("box on a 20,000-triangle floor: " << all << " points, " << atTwo << " at resolution 2, " << atThree
                                             << " at resolution 3");
  CHECK(all > 50);
  CHECK(atTwo >= 3);
  CHECK(atTwo <= 4);
  CHECK(atThree > atTwo);
  // The survivors span the contact patch: their bounding square covers most
  // of the box's 1 m × 1 m base.
  S minX = S(1), maxX = S(-1);
  for (const auto& c : space->getGeometryContacts())
    for (const auto& p : c.points())
      if (p.enabled) {
        minX = std::min(minX, p.point.x());
        maxX = std::max(maxX, p.point.x());
      }
  CHECK(maxX - minX >= S(0.7));
}

TEST_CASE_TEMPLATE("filters: pairwise, group ids, group names, same body, disabled, static pairs", S, float, double) {
  spook::ref_ptr<spook::SpaceT<S>> space = new spook::SpaceT<S>();
  spook::ref_ptr<spook::GeometryT<S>> ground = new spook::GeometryT<S>(new spook::PlaneT<S>(spook::Vec3T<S>::UnitZ()));
  space->add(ground);
  auto body = boxBody<S>(0.49);
  std::vector<spook::ref_ptr<spook::RigidBodyT<S>>> bodies{body};
  spook::GeometryT<S>* box = body->getGeometries()[0].get();
  const auto contacts = [&] {
    space->update(bodies);
    return space->getGeometryContacts().size();
  };
  CHECK(contacts() == 1);
  box->setEnableCollisions(ground.get(), false);
  CHECK(contacts() == 0);
  box->setEnableCollisions(ground.get(), true);
  box->addGroup(1);
  ground->addGroup(2);
  space->setEnablePair(2, 1, false);
  CHECK(contacts() == 0);
  space->setEnablePair(1, 2, true);
  box->addGroup("crates");
  ground->addGroup("floor");
  space->setEnablePair("floor", "crates", false);
  CHECK(contacts() == 0);
  space->setEnablePair("crates", "floor", true);
  CHECK(contacts() == 1);
  box->setEnable(false);
  CHECK(contacts() == 0);
  box->setEnable(true);
  body->setMotionControl(spook::RigidBodyT<S>::STATIC);  // static against static
  CHECK(contacts() == 0);
  body->setMotionControl(spook::RigidBodyT<S>::DYNAMICS);
  body->add(new spook::GeometryT<S>(new spook::SphereT<S>(S(0.5))));  // overlaps its sibling box
  CHECK(contacts() == 2);  // both against the ground, never against each other
}

TEST_CASE_TEMPLATE("a pair is an impact once, then a contact, then a separation", S, float, double) {
  spook::ref_ptr<spook::SpaceT<S>> space = new spook::SpaceT<S>();
  space->add(new spook::GeometryT<S>(new spook::PlaneT<S>(spook::Vec3T<S>::UnitZ())));
  auto body = boxBody<S>(0.49);
  std::vector<spook::ref_ptr<spook::RigidBodyT<S>>> bodies{body};
  space->update(bodies);
  REQUIRE(space->getGeometryContacts().size() == 1);
  CHECK(space->getGeometryContacts()[0].isImpact());
  space->update(bodies);
  REQUIRE(space->getGeometryContacts().size() == 1);
  CHECK_FALSE(space->getGeometryContacts()[0].isImpact());
  CHECK(space->getSeparations().empty());
  body->setPosition(S(0), S(0), S(2));
  space->update(bodies);
  CHECK(space->getGeometryContacts().empty());
  REQUIRE(space->getSeparations().size() == 1);
  CHECK(space->getSeparations()[0].second.get() == body->getGeometries()[0].get());
}

TEST_CASE_TEMPLATE("a space refuses shapes outside its list and keeps what it had", S, float, double) {
  spook::ref_ptr<spook::SpaceT<S>> space = new spook::SpaceT<S>(spook::ShapeList<spook::SphereT, spook::PlaneT>{});
  spook::ref_ptr<spook::GeometryT<S>> ball = new spook::GeometryT<S>(new spook::SphereT<S>(S(1)));
  space->add(ball);
  spook::ref_ptr<spook::GeometryT<S>> crate = new spook::GeometryT<S>(
      new spook::BoxT<S>(spook::Vec3T<S>::Ones()), spook::TransformT<S>::Identity(), "crate");
  CHECK_THROWS_WITH_AS(space->add(crate), doctest::Contains("Geometry 'crate': shape type not in this space's shape list, got Box"),
                       spook::Error);
  CHECK_THROWS_WITH_AS(space->add(ball), doctest::Contains("already in this space"), spook::Error);
  CHECK_THROWS_WITH_AS(space->setContactBinResolution(4), doctest::Contains("got 4"), spook::Error);
  CHECK(space->getGeometries().size() == 1);
  CHECK(space->getContactBinResolution() == 2);
}

// Eight points of a flat patch, 2 × 4 cells of `cell` m, at `origin`, with
// depths that differ so that ties do not decide.
namespace {

template <class S>
std::vector<spook::ContactPointT<S>> reductionPatch(const spook::Vec3T<S>& origin, S cell) {
  std::vector<spook::ContactPointT<S>> points;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 4; ++i) {
      spook::ContactPointT<S> p;
      p.point = origin + cell * spook::Vec3T<S>(S(i), S(j), S(0));
      p.depth = S(0.001) * S(1 + i + 4 * j);
      points.push_back(p);
    }
  return points;
}

template <class S>
std::vector<bool> reducedFlags(std::vector<spook::ContactPointT<S>>& points) {
  std::vector<spook::ContactPointT<S>*> pointers;
  for (auto& p : points) pointers.push_back(&p);
  spook::detail::reduceContacts<S>(pointers, 2);
  std::vector<bool> enabled;
  for (const auto& p : points) enabled.push_back(p.enabled);
  return enabled;
}

}  // namespace

// The reduction only looks at arms relative to the patch's centroid and size,
// so the same patch kept near the largest finite coordinate, where the sum of
// its eight points overflows, keeps the same points (1.5·2^1023 m in double,
// 1.5·2^127 m in float, cells of 2^1015 or 2^119 m, so that every coordinate,
// the centroid and the arms are exact). Before, the centroid was inf, the
// arms NaN and their bins a NaN cast to int (undefined behaviour).
TEST_CASE_TEMPLATE("contact reduction near the largest finite coordinate keeps the points it keeps near the origin", S,
                   float, double) {
  using V = spook::Vec3T<S>;
  constexpr int top = std::numeric_limits<S>::max_exponent - 1;  // 1023 or 127
  const S far = std::ldexp(S(1.5), top), cell = std::ldexp(S(1), top - 8);
  auto nearOrigin = reductionPatch<S>(V::Zero(), S(1));
  auto nearMax = reductionPatch<S>(V(far, far, S(0)), cell);
  REQUIRE(nearMax[7].point.x() == far + S(3) * cell);  // representable: the patch is not collapsed
  const std::vector<bool> expected = reducedFlags<S>(nearOrigin);
  CHECK(std::count(expected.begin(), expected.end(), true) == 4);
  CHECK(reducedFlags<S>(nearMax) == expected);

  // A non-finite point handed to the reduction is disabled and left out; the rest reduce as before.
  auto withNan = reductionPatch<S>(V::Zero(), S(1));
  spook::ContactPointT<S> bad;
  bad.point = V(std::numeric_limits<S>::quiet_NaN(), S(0), S(0));
  withNan.push_back(bad);
  bad.point = V::Zero();
  bad.normal = V(S(0), S(0), std::numeric_limits<S>::infinity());
  withNan.push_back(bad);
  std::vector<bool> withNanExpected = expected;
  withNanExpected.push_back(false);
  withNanExpected.push_back(false);
  CHECK(reducedFlags<S>(withNan) == withNanExpected);
}

// A line fixed in a body from its origin to 1 m above, reaching out to
// x = 1.5·max: that endpoint is at x = inf and 1/10 of it below a plane
// tilted toward −x, so the line–plane collider reports a point at infinity,
// which the space drops and counts, and the simulation's statistics too.
TEST_CASE_TEMPLATE("a non-finite contact point is dropped before reduction and counted in the statistics", S, float,
                   double) {
  using V = spook::Vec3T<S>;
  const S max = std::numeric_limits<S>::max();
  spook::ref_ptr<spook::SimulationT<S>> sim = new spook::SimulationT<S>();
  sim->add(new spook::GeometryT<S>(new spook::PlaneT<S>(V(S(-0.1), S(0), S(1)), V(S(0.5) * max, S(0), S(0)))));
  spook::ref_ptr<spook::RigidBodyT<S>> rod = new spook::RigidBodyT<S>("rod");
  rod->add(new spook::GeometryT<S>(new spook::LineT<S>(V(S(0), S(0), S(1)), V(max, S(0), S(1)))));
  rod->setPosition(S(0.5) * max, S(0), S(0));
  sim->add(rod);
  spook::SpaceT<S>& space = *sim->getSpace();
  space.update(sim->getRigidBodies());
  CHECK(space.getNumDroppedContactPoints() == 1);
  CHECK(space.getGeometryContacts().empty());

  CHECK(sim->getStatistics().numDroppedContactPoints == 0);
  sim->stepForward();
  CHECK(sim->getStatistics().numDroppedContactPoints == 1);
  CHECK(rod->getPosition().allFinite());
  // Lifted clear of the plane (which rises to 0.05·max at x = max), nothing is dropped any more.
  rod->setPosition(S(0), S(0), S(0.1) * max);
  sim->stepForward();
  CHECK(sim->getStatistics().numDroppedContactPoints == 0);
  CHECK(sim->getStatistics().frozenBodies.empty());
}
