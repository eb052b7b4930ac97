#include <doctest/doctest.h>

#include <string>
#include <vector>

#include <spook/collide/space.hpp>

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
