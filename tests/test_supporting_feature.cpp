// supportingFeature of every convex shape: the face, edge or point extreme
// along a direction, worked out by hand, in float and double. Every point
// returned must be on the shape and within the feature angle of the
// support's height along the direction.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include <spook/collide/detail/triangle.hpp>
#include <spook/collide/shapes/box.hpp>
#include <spook/collide/shapes/capsule.hpp>
#include <spook/collide/shapes/convex.hpp>
#include <spook/collide/shapes/cylinder.hpp>
#include <spook/collide/shapes/line.hpp>
#include <spook/collide/shapes/sphere.hpp>

#include "tolerance.hpp"

namespace {

template <class S>
using Vec3 = spook::Vec3T<S>;

template <class S>
bool has(const spook::SupportingFeatureT<S>& f, const Vec3<S>& p) {
  const S tolerance = spook::test::pick<S>(1e-12, 1e-5);
  return std::any_of(f.points.begin(), f.points.begin() + static_cast<std::ptrdiff_t>(f.count),
                     [&](const Vec3<S>& q) { return (q - p).norm() <= tolerance; });
}

/// Every point of the feature is as high along d as the support, to within
/// sin(feature angle) × the feature's extent (it may only be tilted that much).
template <class S, class Shape>
void checkNearSupport(const Shape& shape, const Vec3<S>& d, const spook::SupportingFeatureT<S>& f, S extent) {
  const Vec3<S> u = d.normalized();
  const S top = shape.support(d).dot(u);
  for (std::size_t k = 0; k < f.count; ++k) {
    CHECK(f.points[k].dot(u) <= top + spook::test::pick<S>(1e-12, 1e-5));
    CHECK(f.points[k].dot(u) >= top - S(spook::kSupportingFeatureSin) * extent - spook::test::pick<S>(1e-12, 1e-5));
  }
}

}  // namespace

TEST_CASE_TEMPLATE("a box supports a face within the feature angle, else an edge, else a corner", S, float, double) {
  spook::ref_ptr<spook::BoxT<S>> box = new spook::BoxT<S>(Vec3<S>(1, 2, 3));
  spook::SupportingFeatureT<S> f;
  // Straight down, and 2° off it: the bottom face, its four corners.
  for (const Vec3<S>& d : {Vec3<S>(0, 0, -1), Vec3<S>(S(std::sin(0.035)), 0, -S(std::cos(0.035)))}) {
    box->supportingFeature(d, f);
    REQUIRE(f.count == 4);
    for (const S x : {S(-1), S(1)})
      for (const S y : {S(-2), S(2)}) CHECK(has(f, Vec3<S>(x, y, -3)));
    checkNearSupport<S>(*box, d, f, S(5));
  }
  // 45° between −z and +x, and 2° off that about x: the edge along y at x = 1, z = −3.
  for (const Vec3<S>& d : {Vec3<S>(1, 0, -1), Vec3<S>(1, S(0.05), -1)}) {
    box->supportingFeature(d, f);
    REQUIRE(f.count == 2);
    CHECK(has(f, Vec3<S>(1, -2, -3)));
    CHECK(has(f, Vec3<S>(1, 2, -3)));
  }
  // A general direction: the corner alone.
  box->supportingFeature(Vec3<S>(1, -1, 1), f);
  REQUIRE(f.count == 1);
  CHECK(has(f, Vec3<S>(1, -2, 3)));
}

TEST_CASE_TEMPLATE("a cylinder supports a cap, its side line or a rim point", S, float, double) {
  spook::ref_ptr<spook::CylinderT<S>> cylinder = new spook::CylinderT<S>(S(0.5), S(2));  // axis y
  spook::SupportingFeatureT<S> f;
  // Along −y, and 1° off it: the bottom cap, kCapCorners points on its rim.
  for (const Vec3<S>& d : {Vec3<S>(0, -1, 0), Vec3<S>(S(0.017), -1, 0)}) {
    cylinder->supportingFeature(d, f);
    REQUIRE(f.count == std::size_t(spook::kCapCorners));
    for (std::size_t k = 0; k < f.count; ++k) {
      CHECK(f.points[k].y() == doctest::Approx(-1.0));
      CHECK(std::hypot(f.points[k].x(), f.points[k].z()) == doctest::Approx(0.5).epsilon(1e-6));
    }
    if (d.x() != S(0)) CHECK(has(f, cylinder->support(d)));  // tilted: the deepest rim point is a corner
  }
  // Across the axis toward +x, and 2° off it: the side line at x = 0.5.
  for (const Vec3<S>& d : {Vec3<S>(1, 0, 0), Vec3<S>(1, S(0.035), 0)}) {
    cylinder->supportingFeature(d, f);
    REQUIRE(f.count == 2);
    CHECK(has(f, Vec3<S>(S(0.5), -1, 0)));
    CHECK(has(f, Vec3<S>(S(0.5), 1, 0)));
    checkNearSupport<S>(*cylinder, d, f, S(2));
  }
  // 45° between: the rim point alone.
  cylinder->supportingFeature(Vec3<S>(1, -1, 0), f);
  REQUIRE(f.count == 1);
  CHECK(has(f, Vec3<S>(S(0.5), -1, 0)));
}

TEST_CASE_TEMPLATE("a capsule supports its side line across its axis, else one point; a sphere one point", S, float,
                   double) {
  spook::ref_ptr<spook::CapsuleT<S>> capsule = new spook::CapsuleT<S>(S(0.5), S(2));  // axis y, ends at y = ±1
  spook::SupportingFeatureT<S> f;
  capsule->supportingFeature(Vec3<S>(0, 0, -1), f);
  REQUIRE(f.count == 2);
  CHECK(has(f, Vec3<S>(0, 1, S(-0.5))));
  CHECK(has(f, Vec3<S>(0, -1, S(-0.5))));
  // 2° off: both end spheres' supports, each on the surface.
  const Vec3<S> tilted = Vec3<S>(0, S(0.035), -1).normalized();
  capsule->supportingFeature(tilted, f);
  REQUIRE(f.count == 2);
  CHECK(has(f, Vec3<S>(Vec3<S>(0, 1, 0) + S(0.5) * tilted)));
  CHECK(has(f, Vec3<S>(Vec3<S>(0, -1, 0) + S(0.5) * tilted)));
  checkNearSupport<S>(*capsule, tilted, f, S(2));
  capsule->supportingFeature(Vec3<S>(0, 1, -1), f);
  CHECK(f.count == 1);

  spook::ref_ptr<spook::SphereT<S>> sphere = new spook::SphereT<S>(S(2));
  sphere->supportingFeature(Vec3<S>(0, 0, -3), f);
  REQUIRE(f.count == 1);
  CHECK(has(f, Vec3<S>(0, 0, -2)));
}

TEST_CASE_TEMPLATE("a hull supports the face or edge at its support corner, else that corner", S, float, double) {
  // A hexagonal prism about z, corners at radius 1, z = ±0.5.
  std::vector<Vec3<S>> corners;
  for (int k = 0; k < 6; ++k)
    for (const S z : {S(-0.5), S(0.5)})
      corners.emplace_back(S(std::cos(k * spook::PI / 3)), S(std::sin(k * spook::PI / 3)), z);
  spook::ref_ptr<spook::ConvexT<S>> hull = new spook::ConvexT<S>(corners);
  spook::SupportingFeatureT<S> f;
  // Down, and 2° off: the bottom hexagon.
  for (const Vec3<S>& d : {Vec3<S>(0, 0, -1), Vec3<S>(S(0.03), S(0.02), -1)}) {
    hull->supportingFeature(d, f);
    REQUIRE(f.count == 6);
    for (std::size_t k = 0; k < f.count; ++k) CHECK(f.points[k].z() == doctest::Approx(-0.5));
  }
  // Toward the corner at angle 0 and down by 45°: no face or edge there is
  // within 3° of across it, the corner (1, 0, −0.5) alone.
  hull->supportingFeature(Vec3<S>(1, 0, -1), f);
  REQUIRE(f.count == 1);
  CHECK(has(f, Vec3<S>(1, 0, S(-0.5))));
  // Toward the middle of the side face between angles 0 and 60°, tilted
  // down by 45°: the bottom edge of that face.
  const Vec3<S> across(S(std::cos(spook::PI / 6)), S(std::sin(spook::PI / 6)), 0);
  hull->supportingFeature(Vec3<S>(across + Vec3<S>(0, 0, -1)), f);
  REQUIRE(f.count == 2);
  CHECK(has(f, Vec3<S>(1, 0, S(-0.5))));
  CHECK(has(f, Vec3<S>(S(0.5), S(std::sin(spook::PI / 3)), S(-0.5))));
  // Straight at that side face: its four corners.
  hull->supportingFeature(across, f);
  CHECK(f.count == 4);
}

TEST_CASE_TEMPLATE("a line and a triangle support themselves when across the direction", S, float, double) {
  spook::ref_ptr<spook::LineT<S>> line = new spook::LineT<S>(Vec3<S>(-1, 0, 0), Vec3<S>(1, 0, 0));
  spook::SupportingFeatureT<S> f;
  line->supportingFeature(Vec3<S>(0, 0, -1), f);
  CHECK(f.count == 2);
  line->supportingFeature(Vec3<S>(1, 0, -1), f);
  REQUIRE(f.count == 1);
  CHECK(has(f, Vec3<S>(1, 0, 0)));

  const spook::detail::Triangle<S> t{{Vec3<S>(0, 0, 0), Vec3<S>(1, 0, 0), Vec3<S>(0, 1, 0)}};
  for (const Vec3<S>& d : {Vec3<S>(0, 0, 1), Vec3<S>(0, 0, -1)}) {  // either side of a flat triangle
    t.supportingFeature(d, f);
    CHECK(f.count == 3);
  }
  t.supportingFeature(Vec3<S>(0, -1, -1), f);  // across the edge on y = 0
  REQUIRE(f.count == 2);
  CHECK(has(f, Vec3<S>(0, 0, 0)));
  CHECK(has(f, Vec3<S>(1, 0, 0)));
  t.supportingFeature(Vec3<S>(1, 1, -1), f);  // past the hypotenuse: its two ends
  CHECK(f.count == 2);
  t.supportingFeature(Vec3<S>(-1, -1, 1), f);  // the corner at the origin
  REQUIRE(f.count == 1);
  CHECK(has(f, Vec3<S>(0, 0, 0)));
}
