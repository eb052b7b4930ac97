// The analytic colliders on the configurations where a formula has no
// unique answer or divides by zero: coincident centers, centers on an axis
// or a face, parallel, coincident and crossing segments, spheres exactly
// touching. Every contact must be finite with a unit normal, and the
// counts and depths are stated.

#include <doctest/doctest.h>

#include <numbers>

#include <spook/collide/colliders/box_sphere.hpp>
#include <spook/collide/colliders/capsule_capsule.hpp>
#include <spook/collide/colliders/capsule_sphere.hpp>
#include <spook/collide/colliders/cylinder_sphere.hpp>
#include <spook/collide/colliders/line_sphere.hpp>
#include <spook/collide/colliders/sphere_sphere.hpp>

#include "collide_cases.hpp"

using spook::test::at;
using spook::test::contacts;
using spook::test::near;
using spook::test::pick;
using spook::test::turned;

TEST_CASE_TEMPLATE("spheres with coincident centers push apart along a fixed axis by the sum of the radii", S, float,
                   double) {
  spook::ref_ptr<spook::SphereT<S>> a = new spook::SphereT<S>(S(0.5)), b = new spook::SphereT<S>(S(0.25));
  const auto points = contacts(*a, at<S>(1, 2, 3), *b, at<S>(1, 2, 3));
  REQUIRE(points.size() == 1);
  CHECK(points[0].depth == doctest::Approx(0.75));
  CHECK(points[0].normal == spook::Vec3T<S>::UnitZ());
}

TEST_CASE_TEMPLATE("spheres exactly touching give one contact of depth 0 at the touching point", S, float, double) {
  spook::ref_ptr<spook::SphereT<S>> a = new spook::SphereT<S>(S(0.5)), b = new spook::SphereT<S>(S(0.25));
  const auto points = contacts(*a, at<S>(0, 0, 0), *b, at<S>(S(0.75), 0, 0));
  REQUIRE(points.size() == 1);
  CHECK(points[0].depth == S(0));
  CHECK(near<S>(points[0].point, spook::Vec3T<S>(S(0.5), 0, 0), pick<S>(1e-15, 1e-7)));
  CHECK(near<S>(points[0].normal, spook::Vec3T<S>::UnitX(), S(0)));
}

TEST_CASE_TEMPLATE("the reversed pair flips the normal: sphere-box pushes from the sphere into the box", S, float,
                   double) {
  spook::ref_ptr<spook::BoxT<S>> box = new spook::BoxT<S>(spook::Vec3T<S>(1, 1, 1));
  spook::ref_ptr<spook::SphereT<S>> sphere = new spook::SphereT<S>(S(0.5));
  const auto forward = contacts(*box, at<S>(0, 0, 0), *sphere, at<S>(0, 0, S(1.25)));
  const auto reversed = contacts(*sphere, at<S>(0, 0, S(1.25)), *box, at<S>(0, 0, 0));
  REQUIRE(forward.size() == 1);
  REQUIRE(reversed.size() == 1);
  CHECK(forward[0].normal == spook::Vec3T<S>::UnitZ());
  CHECK(reversed[0].normal == -spook::Vec3T<S>::UnitZ());
  CHECK(reversed[0].depth == forward[0].depth);
  CHECK(forward[0].depth == doctest::Approx(0.25));
}

TEST_CASE_TEMPLATE("a sphere centered in a box, on a face or on a corner pushes out through a face", S, float, double) {
  spook::ref_ptr<spook::BoxT<S>> box = new spook::BoxT<S>(spook::Vec3T<S>(1, S(0.5), S(0.75)));
  spook::ref_ptr<spook::SphereT<S>> sphere = new spook::SphereT<S>(S(0.25));
  SUBCASE("center at the box center: the nearest face, +y") {
    const auto points = contacts(*box, at<S>(0, 0, 0), *sphere, at<S>(0, 0, 0));
    REQUIRE(points.size() == 1);
    CHECK(points[0].normal == spook::Vec3T<S>::UnitY());
    CHECK(points[0].depth == doctest::Approx(0.75));
  }
  SUBCASE("center on the −z face: depth r") {
    const auto points = contacts(*box, at<S>(0, 0, 0), *sphere, at<S>(S(0.2), S(0.1), S(-0.75)));
    REQUIRE(points.size() == 1);
    CHECK(points[0].normal == -spook::Vec3T<S>::UnitZ());
    CHECK(points[0].depth == doctest::Approx(0.25));
  }
  SUBCASE("center on a corner: depth r along the first axis") {
    const auto points = contacts(*box, at<S>(0, 0, 0), *sphere, at<S>(1, S(0.5), S(0.75)));
    REQUIRE(points.size() == 1);
    CHECK(points[0].normal == spook::Vec3T<S>::UnitX());
    CHECK(points[0].depth == doctest::Approx(0.25));
  }
}

TEST_CASE_TEMPLATE("a sphere centered on a capsule's or a line's axis pushes out perpendicular to it", S, float,
                   double) {
  spook::ref_ptr<spook::CapsuleT<S>> capsule = new spook::CapsuleT<S>(S(0.5), S(2));
  spook::ref_ptr<spook::LineT<S>> line = new spook::LineT<S>(spook::Vec3T<S>(0, -1, 0), spook::Vec3T<S>(0, 1, 0));
  spook::ref_ptr<spook::SphereT<S>> sphere = new spook::SphereT<S>(S(0.25));
  const auto X = turned(at<S>(1, 1, 1), S(0.3), spook::Vec3T<S>(1, 2, 3));
  const spook::Vec3T<S> axis = X.linear().col(1);
  for (const S along : {S(0), S(0.5), S(1)}) {
    const auto onAxis = at<S>(1, 1, 1);
    spook::TransformT<S> X_WB = onAxis;
    X_WB.translation() += along * axis;
    const auto fromCapsule = contacts(*capsule, X, *sphere, X_WB);
    REQUIRE(fromCapsule.size() == 1);
    CHECK(fromCapsule[0].depth == doctest::Approx(0.75));
    CHECK(std::abs(fromCapsule[0].normal.dot(axis)) <= pick<S>(1e-12, 1e-6));
    const auto fromLine = contacts(*line, X, *sphere, X_WB);
    REQUIRE(fromLine.size() == 1);
    CHECK(fromLine[0].depth == doctest::Approx(0.25));
    CHECK(std::abs(fromLine[0].normal.dot(axis)) <= pick<S>(1e-12, 1e-6));
  }
}

TEST_CASE_TEMPLATE("a sphere centered in a cylinder pushes out through the nearer of cap and barrel", S, float,
                   double) {
  spook::ref_ptr<spook::SphereT<S>> sphere = new spook::SphereT<S>(S(0.25));
  SUBCASE("long cylinder, center on the axis: the barrel, along the cylinder's x") {
    spook::ref_ptr<spook::CylinderT<S>> cylinder = new spook::CylinderT<S>(S(0.5), S(4));
    const auto points = contacts(*cylinder, at<S>(0, 0, 0), *sphere, at<S>(0, 0, 0));
    REQUIRE(points.size() == 1);
    CHECK(points[0].normal == spook::Vec3T<S>::UnitX());
    CHECK(points[0].depth == doctest::Approx(0.75));
  }
  SUBCASE("flat cylinder: the cap") {
    spook::ref_ptr<spook::CylinderT<S>> cylinder = new spook::CylinderT<S>(S(2), S(0.5));
    const auto points = contacts(*cylinder, at<S>(0, 0, 0), *sphere, at<S>(0, 0, 0));
    REQUIRE(points.size() == 1);
    CHECK(points[0].normal == spook::Vec3T<S>::UnitY());
    CHECK(points[0].depth == doctest::Approx(0.5));
  }
}

TEST_CASE_TEMPLATE("parallel capsules side by side touch at both ends of their common stretch", S, float, double) {
  spook::ref_ptr<spook::CapsuleT<S>> a = new spook::CapsuleT<S>(S(0.5), S(2)), b = new spook::CapsuleT<S>(S(0.5), S(1));
  // b's axis covers y ∈ [0, 1] of a's [−1, 1], 0.9 m beside it: 0.1 m deep.
  const auto points = contacts(*a, at<S>(0, 0, 0), *b, at<S>(S(0.9), S(0.5), 0));
  REQUIRE(points.size() == 2);
  for (const auto& p : points) {
    CHECK(p.depth == doctest::Approx(0.1));
    CHECK(near<S>(p.normal, spook::Vec3T<S>::UnitX(), pick<S>(1e-12, 1e-6)));
    CHECK(std::abs(p.point.x() - S(0.45)) <= pick<S>(1e-12, 1e-6));
  }
  CHECK(std::abs(points[0].point.y() - points[1].point.y()) == doctest::Approx(1.0));

  SUBCASE("antiparallel: the same") {
    const auto flipped = contacts(*a, at<S>(0, 0, 0), *b,
                                  turned(at<S>(S(0.9), S(0.5), 0), S(std::numbers::pi), spook::Vec3T<S>::UnitZ()));
    CHECK(flipped.size() == 2);
  }
  SUBCASE("coincident axes: finite contacts, depth r_a + r_b") {
    const auto same = contacts(*a, at<S>(0, 0, 0), *b, at<S>(0, S(0.25), 0));
    REQUIRE(!same.empty());
    CHECK(same[0].depth == doctest::Approx(1.0));
  }
  SUBCASE("crossing axes: the normal is their common perpendicular") {
    const auto crossing =
        contacts(*a, at<S>(0, 0, 0), *b, turned(at<S>(0, 0, 0), S(std::numbers::pi / 2), spook::Vec3T<S>::UnitX()));
    REQUIRE(crossing.size() == 1);
    CHECK(std::abs(crossing[0].normal.x()) == doctest::Approx(1.0));
    CHECK(crossing[0].depth == doctest::Approx(1.0));
  }
}
