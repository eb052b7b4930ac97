// Resting contacts of the analytic colliders with a plane, and of a line
// with a box: shapes exactly touching (depth 0), lying flat, on an edge or
// a corner, and the number of contacts each pose needs to rest without
// rolling. Every contact must be finite with a unit normal.

#include <doctest/doctest.h>

#include <numbers>

#include <spook/collide/colliders/box_line.hpp>
#include <spook/collide/colliders/box_plane.hpp>
#include <spook/collide/colliders/capsule_plane.hpp>
#include <spook/collide/colliders/cylinder_plane.hpp>
#include <spook/collide/colliders/line_plane.hpp>
#include <spook/collide/colliders/plane_sphere.hpp>

#include "collide_cases.hpp"

using spook::test::at;
using spook::test::contacts;
using spook::test::near;
using spook::test::pick;
using spook::test::turned;

TEST_CASE_TEMPLATE("a box exactly touching a plane gives its four bottom corners at depth 0", S, float, double) {
  spook::ref_ptr<spook::BoxT<S>> box = new spook::BoxT<S>(spook::Vec3T<S>(S(0.5), S(0.25), S(0.75)));
  spook::ref_ptr<spook::PlaneT<S>> plane = new spook::PlaneT<S>(spook::Vec3T<S>::UnitZ());
  const auto points = contacts(*box, at<S>(1, 2, S(0.75)), *plane, at<S>(0, 0, 0));
  REQUIRE(points.size() == 4);
  for (const auto& p : points) {
    CHECK(p.depth == S(0));
    CHECK(p.point.z() == S(0));
    CHECK(p.normal == -spook::Vec3T<S>::UnitZ());
  }
}

TEST_CASE_TEMPLATE("a box resting on a plane: four contacts flat, two on an edge, one on a corner", S, float, double) {
  spook::ref_ptr<spook::BoxT<S>> box = new spook::BoxT<S>(spook::Vec3T<S>(S(0.5), S(0.5), S(0.5)));
  spook::ref_ptr<spook::PlaneT<S>> plane = new spook::PlaneT<S>(spook::Vec3T<S>::UnitZ(), spook::Vec3T<S>(0, 0, 1));
  const auto flat = contacts(*box, at<S>(0, 0, S(1.4)), *plane, at<S>(0, 0, 0));
  REQUIRE(flat.size() == 4);
  for (const auto& p : flat) {
    CHECK(p.depth == doctest::Approx(0.1));
    CHECK(std::abs(p.point.z() - S(0.95)) <= pick<S>(1e-12, 1e-6));  // midway between the corner and the plane
  }
  const S edgeHeight = S(0.5) * std::sqrt(S(2)) + S(0.9);
  const auto onEdge = contacts(*box, turned(at<S>(0, 0, edgeHeight), S(std::numbers::pi / 4), spook::Vec3T<S>::UnitX()),
                               *plane, at<S>(0, 0, 0));
  CHECK(onEdge.size() == 2);
  const S cornerHeight = S(0.5) * std::sqrt(S(3)) + S(0.9);
  // The diagonal (1, 1, 1) turned onto z, about (1, 1, 1) × z.
  const spook::TransformT<S> onCorner =
      turned(at<S>(0, 0, cornerHeight), std::acos(S(1) / std::sqrt(S(3))), spook::Vec3T<S>(1, -1, 0));
  const auto corner = contacts(*box, onCorner, *plane, at<S>(0, 0, 0));
  REQUIRE(corner.size() == 1);
  CHECK(corner[0].depth == doctest::Approx(0.1).epsilon(1e-4));
}

TEST_CASE_TEMPLATE("a capsule on a plane: two contacts lying, one tilted, none above", S, float, double) {
  spook::ref_ptr<spook::CapsuleT<S>> capsule = new spook::CapsuleT<S>(S(0.25), S(2));
  spook::ref_ptr<spook::PlaneT<S>> plane = new spook::PlaneT<S>(spook::Vec3T<S>::UnitZ());
  const auto lying = contacts(*capsule, at<S>(0, 0, S(0.2)), *plane, at<S>(0, 0, 0));  // axis along y
  REQUIRE(lying.size() == 2);
  for (const auto& p : lying) CHECK(p.depth == doctest::Approx(0.05));
  const auto tilted =
      contacts(*capsule, turned(at<S>(0, 0, S(0.6)), S(1), spook::Vec3T<S>::UnitX()), *plane, at<S>(0, 0, 0));
  CHECK(tilted.size() == 1);
  CHECK(contacts(*capsule, at<S>(0, 0, S(1.3)), *plane, at<S>(0, 0, 0)).empty());
}

TEST_CASE_TEMPLATE("a cylinder on a plane: four rim points standing, two lying, one tilted", S, float, double) {
  spook::ref_ptr<spook::CylinderT<S>> cylinder = new spook::CylinderT<S>(S(0.5), S(1));
  spook::ref_ptr<spook::PlaneT<S>> plane = new spook::PlaneT<S>(spook::Vec3T<S>::UnitZ());
  // Standing on its −y cap (the axis turned onto z), 0.05 m deep.
  const auto standing =
      contacts(*cylinder, turned(at<S>(0, 0, S(0.45)), S(std::numbers::pi / 2), spook::Vec3T<S>::UnitX()), *plane,
               at<S>(0, 0, 0));
  REQUIRE(standing.size() == 4);
  for (std::size_t i = 0; i < 4; ++i) {
    CHECK(standing[i].depth == doctest::Approx(0.05));
    const spook::Vec3T<S> radial(standing[i].point.x(), standing[i].point.y(), 0);
    CHECK(radial.norm() == doctest::Approx(0.5));
    for (std::size_t j = 0; j < i; ++j) {
      const spook::Vec3T<S> other(standing[j].point.x(), standing[j].point.y(), 0);
      const S cosine = radial.dot(other) / (radial.norm() * other.norm());
      CHECK((std::abs(cosine) <= pick<S>(1e-12, 1e-6) || std::abs(cosine + S(1)) <= pick<S>(1e-12, 1e-6)));
    }
  }
  const auto lying = contacts(*cylinder, at<S>(0, 0, S(0.45)), *plane, at<S>(0, 0, 0));  // axis along y
  REQUIRE(lying.size() == 2);
  for (const auto& p : lying) CHECK(p.depth == doctest::Approx(0.05));
  const auto tilted =
      contacts(*cylinder, turned(at<S>(0, 0, S(0.6)), S(0.5), spook::Vec3T<S>::UnitX()), *plane, at<S>(0, 0, 0));
  CHECK(tilted.size() == 1);
}

TEST_CASE_TEMPLATE("a line on a plane or across a box face rests on two points", S, float, double) {
  spook::ref_ptr<spook::LineT<S>> line = new spook::LineT<S>(spook::Vec3T<S>(-2, 0, 0), spook::Vec3T<S>(2, 0, 0));
  spook::ref_ptr<spook::PlaneT<S>> plane = new spook::PlaneT<S>(spook::Vec3T<S>::UnitZ());
  const auto onPlane = contacts(*line, at<S>(0, 0, S(-0.1)), *plane, at<S>(0, 0, 0));
  REQUIRE(onPlane.size() == 2);
  for (const auto& p : onPlane) CHECK(p.depth == doctest::Approx(0.1));
  CHECK(contacts(*line, at<S>(0, 0, 0), *plane, at<S>(0, 0, 0)).size() == 2);  // lying in the plane, depth 0

  spook::ref_ptr<spook::BoxT<S>> box = new spook::BoxT<S>(spook::Vec3T<S>(1, 1, S(0.5)));
  // Across the top face, 0.1 m into it, longer than the box: the inside part's ends.
  const auto across = contacts(*box, at<S>(0, 0, 0), *line, at<S>(0, S(0.2), S(0.4)));
  REQUIRE(across.size() == 2);
  for (const auto& p : across) {
    CHECK(p.depth == doctest::Approx(0.1));
    CHECK(p.normal == spook::Vec3T<S>::UnitZ());
    CHECK(std::abs(std::abs(p.point.x()) - S(1)) <= pick<S>(1e-12, 1e-6));
  }
  // Touching the top face from above: depth 0.
  const auto touching = contacts(*box, at<S>(0, 0, 0), *line, at<S>(0, S(0.2), S(0.5)));
  REQUIRE(!touching.empty());
  CHECK(touching[0].depth == S(0));
  // Through the center along x: every axis but x ties; a finite answer, depth 1.
  const auto through = contacts(*box, at<S>(0, 0, 0), *line, at<S>(0, 0, 0));
  REQUIRE(!through.empty());
  CHECK(through[0].depth == doctest::Approx(0.5));
  // An endpoint exactly on a face, the segment going out: depth 0.
  spook::ref_ptr<spook::LineT<S>> stub = new spook::LineT<S>(spook::Vec3T<S>(0, 0, 0), spook::Vec3T<S>(0, 0, 1));
  const auto onFace = contacts(*box, at<S>(0, 0, 0), *stub, at<S>(S(0.3), S(0.3), S(0.5)));
  REQUIRE(onFace.size() == 1);
  CHECK(onFace[0].depth == S(0));
  CHECK(onFace[0].normal == spook::Vec3T<S>::UnitZ());
  // Along a box edge, outside it: touching, depth 0.
  const auto onEdge = contacts(*box, at<S>(0, 0, 0), *line, at<S>(0, 1, S(0.5)));
  REQUIRE(!onEdge.empty());
  CHECK(onEdge[0].depth == S(0));
}

TEST_CASE_TEMPLATE("a sphere under a plane is still in contact, deeper than its diameter", S, float, double) {
  spook::ref_ptr<spook::PlaneT<S>> plane = new spook::PlaneT<S>(spook::Vec3T<S>::UnitZ());
  spook::ref_ptr<spook::SphereT<S>> sphere = new spook::SphereT<S>(S(0.5));
  const auto points = contacts(*plane, at<S>(0, 0, 0), *sphere, at<S>(0, 0, -2));
  REQUIRE(points.size() == 1);
  CHECK(points[0].depth == doctest::Approx(2.5));
  CHECK(points[0].normal == spook::Vec3T<S>::UnitZ());
}
