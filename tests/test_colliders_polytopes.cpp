// The separating-axis colliders of polytopes (colliders/polytopes.hpp:
// box–hull, hull–hull, hull–segment; and boxes, hulls and segments against
// mesh triangles in colliders/mesh.hpp), float and double.
//
// Differential: 10,000 contacts as a simulation makes them per pair and
// scalar (100 without NDEBUG, kCcdCases), against the test's own
// separating-axis references (polytopeReference, convexLineReference, each
// checked against the brute-force overlap minimum in
// test_colliders_ccd_more.cpp): intersecting or not agrees in >= 99.9 % of
// the cases farther than 1e-6 m from touching, the deepest contact's depth
// within depthTolerance (1e-6 m double, 1e-4 m float), normal within
// 1e-3 rad or equivalent. Then the manifolds: resting faces give their
// clipped overlap polygon, every corner at its own depth.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <spook/collide/colliders.hpp>

#include "collide_reference.hpp"
#include "compiled_collide.hpp"

using namespace spook::test;
using spook::BoxT;
using spook::ConvexT;
using spook::LineT;
using spook::TrimeshT;

namespace {

template <class S, class A, class B>
void checkPolytopes(const std::string& name, std::uint64_t seed, auto&& makeA, auto&& makeB, auto&& reference) {
  const auto run = [](const auto& a, const auto& X_WA, const auto& b, const auto& X_WB, auto& sink) {
    spook::test::collideCompiled(a, X_WA, b, X_WB, sink);
  };
  checkDifferential<S, A, B>(
      name, seed, [&](RandomPoses& random) { return touching(random, makeA(random), makeB(random)); }, run, reference,
      depthTolerance<S>(), kCcdCases);
}

/// Corners of an axis-aligned cube of half side h as a hull.
template <class S>
spook::ref_ptr<ConvexT<S>> cubeHull(S h) {
  std::vector<spook::Vec3T<S>> corners;
  for (int c = 0; c < 8; ++c)
    corners.emplace_back((c & 1) ? h : -h, (c & 2) ? h : -h, (c & 4) ? h : -h);
  return new ConvexT<S>(corners);
}

template <class S>
spook::TransformT<S> at(const spook::Vec3T<S>& p, S angleAboutZ = S(0)) {
  return spook::makeTransform<S>(p, spook::QuatT<S>(Eigen::AngleAxis<S>(angleAboutZ, spook::Vec3T<S>::UnitZ())));
}

template <class S>
std::vector<spook::ContactPointT<S>> contacts(const auto& a, const spook::TransformT<S>& X_WA, const auto& b,
                                              const spook::TransformT<S>& X_WB) {
  std::vector<spook::ContactPointT<S>> points;
  spook::ContactSinkT<S> sink(points);
  spook::test::collideCompiled(a, X_WA, b, X_WB, sink);
  return points;
}

template <class S>
constexpr S tight() {
  return std::is_same_v<S, double> ? S(1e-12) : S(1e-5);
}

}  // namespace

TEST_CASE_TEMPLATE("polytopes, 10,000 poses: box-convex is the separating-axis minimum", S, float, double) {
  checkPolytopes<S, BoxT<double>, ConvexT<double>>("box-convex", 501, randomBox, randomHull,
                                                   polytopeReference<BoxT<double>, ConvexT<double>>);
}

TEST_CASE_TEMPLATE("polytopes, 10,000 poses: convex-convex is the separating-axis minimum", S, float, double) {
  checkPolytopes<S, ConvexT<double>, ConvexT<double>>("convex-convex", 502, randomHull, randomHull,
                                                      polytopeReference<ConvexT<double>, ConvexT<double>>);
}

TEST_CASE_TEMPLATE("polytopes, 10,000 poses: convex-line is the separating-axis minimum", S, float, double) {
  checkPolytopes<S, ConvexT<double>, LineT<double>>("convex-line", 503, randomHull, randomLine, convexLineReference);
}

TEST_CASE_TEMPLATE("a cube hull resting on a box touches it at its 4 bottom corners", S, float, double) {
  const auto hull = cubeHull<S>(S(0.5));
  const spook::ref_ptr<BoxT<S>> floor = new BoxT<S>(spook::Vec3T<S>(2, 2, 0.5));
  const auto points = contacts<S>(*floor, at<S>(spook::Vec3T<S>(0, 0, -0.5)), *hull,
                                  at<S>(spook::Vec3T<S>(S(0.3), S(-0.2), S(0.49))));
  REQUIRE(points.size() == 4);
  for (const auto& p : points) {
    CHECK(std::abs(p.depth - S(0.01)) <= tight<S>());
    CHECK((p.normal - spook::Vec3T<S>::UnitZ()).norm() <= tight<S>());
    CHECK(std::abs(std::abs(p.point.x() - S(0.3)) - S(0.5)) <= tight<S>());
    CHECK(std::abs(std::abs(p.point.y() + S(0.2)) - S(0.5)) <= tight<S>());
    CHECK(std::abs(p.point.z() + S(0.005)) <= tight<S>());  // midway between the surfaces
  }
}

TEST_CASE_TEMPLATE("a cube hull turned 45 degrees on an equal one touches along their octagon", S, float, double) {
  const auto hull = cubeHull<S>(S(0.5));
  const auto points =
      contacts<S>(*hull, at<S>(spook::Vec3T<S>::Zero()), *hull,
                  at<S>(spook::Vec3T<S>(0, 0, S(0.99)), S(std::numbers::pi / 4)));
  REQUIRE(points.size() == 8);
  const S apothem = S(0.5);  // the octagon's corners lie on the squares' sides
  for (const auto& p : points) {
    CHECK(std::abs(p.depth - S(0.01)) <= tight<S>());
    CHECK(std::max(std::abs(p.point.x()), std::abs(p.point.y())) <= apothem + tight<S>());
    const S turnedX = (p.point.x() + p.point.y()) / std::sqrt(S(2)), turnedY = (p.point.y() - p.point.x()) / std::sqrt(S(2));
    CHECK(std::max(std::abs(turnedX), std::abs(turnedY)) <= apothem + tight<S>());
  }
}

TEST_CASE_TEMPLATE("a hull edge across a box edge touches at one point", S, float, double) {
  const auto hull = cubeHull<S>(S(0.5));
  const spook::ref_ptr<BoxT<S>> box = new BoxT<S>(spook::Vec3T<S>::Constant(S(0.5)));
  // Each turned 45 degrees so that an edge leads: the box's top edge along
  // x, the hull's bottom edge along y, overlapping by 1 cm.
  const spook::TransformT<S> X_WA =
      spook::makeTransform<S>(spook::Vec3T<S>::Zero(), spook::QuatT<S>(Eigen::AngleAxis<S>(S(std::numbers::pi / 4),
                                                                                            spook::Vec3T<S>::UnitX())));
  const S reach = S(0.5) * std::sqrt(S(2));
  const spook::TransformT<S> X_WB = spook::makeTransform<S>(
      spook::Vec3T<S>(0, 0, 2 * reach - S(0.01)),
      spook::QuatT<S>(Eigen::AngleAxis<S>(S(std::numbers::pi / 4), spook::Vec3T<S>::UnitY())));
  const auto points = contacts<S>(*box, X_WA, *hull, X_WB);
  REQUIRE(points.size() == 1);
  CHECK(std::abs(points[0].depth - S(0.01)) <= tight<S>());
  CHECK((points[0].normal - spook::Vec3T<S>::UnitZ()).norm() <= tight<S>());
  CHECK((points[0].point - spook::Vec3T<S>(0, 0, reach - S(0.005))).norm() <= tight<S>());
}

TEST_CASE_TEMPLATE("a segment lying on a hull face rests on its two ends", S, float, double) {
  const auto hull = cubeHull<S>(S(0.5));
  const spook::ref_ptr<LineT<S>> rod = new LineT<S>(spook::Vec3T<S>(-0.3, 0, 0), spook::Vec3T<S>(0.3, 0.1, 0));
  const auto points = contacts<S>(*hull, at<S>(spook::Vec3T<S>::Zero()), *rod, at<S>(spook::Vec3T<S>(0, 0, S(0.49))));
  REQUIRE(points.size() == 2);
  for (const auto& p : points) {
    CHECK(std::abs(p.depth - S(0.01)) <= tight<S>());
    CHECK((p.normal - spook::Vec3T<S>::UnitZ()).norm() <= tight<S>());
  }
}

// Two triangles make a 4 m square floor; each clips the box's bottom face
// to its half, so that the contacts are the four corners and the points
// where the diagonal crosses the face, all 1 cm deep.
TEST_CASE_TEMPLATE("a box resting on a two-triangle Trimesh touches it with its whole bottom face", S, float, double) {
  const std::vector<spook::Vec3T<S>> corners{{-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0}};
  const spook::ref_ptr<TrimeshT<S>> floor = new TrimeshT<S>(corners, std::vector<std::array<int, 3>>{{0, 1, 2}, {0, 2, 3}});
  const spook::ref_ptr<BoxT<S>> box = new BoxT<S>(spook::Vec3T<S>(0.5, 0.3, 0.2));
  const auto points = contacts<S>(*box, at<S>(spook::Vec3T<S>(S(0.1), 0, S(0.19)), S(0.3)), *floor,
                                  at<S>(spook::Vec3T<S>::Zero()));
  REQUIRE(points.size() >= 4);
  int bottomCorners = 0;
  for (const auto& p : points) {
    CHECK(std::abs(p.depth - S(0.01)) <= tight<S>());
    CHECK((p.normal + spook::Vec3T<S>::UnitZ()).norm() <= tight<S>());  // from the box into the floor
    const spook::Vec3T<S> local = at<S>(spook::Vec3T<S>(S(0.1), 0, 0), S(0.3)).inverse() * p.point;
    CHECK(std::abs(local.x()) <= S(0.5) + tight<S>());
    CHECK(std::abs(local.y()) <= S(0.3) + tight<S>());
    if (std::abs(std::abs(local.x()) - S(0.5)) <= tight<S>() && std::abs(std::abs(local.y()) - S(0.3)) <= tight<S>())
      ++bottomCorners;
  }
  CHECK(bottomCorners >= 4);
}
