#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <type_traits>
#include <vector>

#include <spook/collide/detail/ccd_bridge.hpp>
#include <spook/collide/shapes/box.hpp>
#include <spook/collide/shapes/cylinder.hpp>
#include <spook/collide/shapes/line.hpp>
#include <spook/collide/shapes/sphere.hpp>

#include "tolerance.hpp"

using spook::test::pick;

// Two spheres overlap by r_a + r_b − |c_b − c_a| along (c_b − c_a)/|c_b − c_a|:
// an exact reference for the libccd path, whose EPA alone stops 1e-4 to
// 1e-3 short on curved shapes (the polishing step closes the gap).
TEST_CASE_TEMPLATE("libccd bridge finds the exact overlap of two spheres", S, float, double) {
  spook::ref_ptr<spook::SphereT<S>> a = new spook::SphereT<S>(S(1)), b = new spook::SphereT<S>(S(0.5));
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  double worstDepth = 0, worstAngle = 0;
  int compared = 0, missed = 0;
  const int cases = spook::test::sweep(10000, 300);
  for (int k = 0; k < cases; ++k) {
    spook::TransformT<S> X_WA = spook::TransformT<S>::Identity(), X_WB = spook::TransformT<S>::Identity();
    X_WA.translation() = spook::Vec3T<S>(S(u(rng)), S(u(rng)), S(u(rng)));
    X_WB.translation() = spook::Vec3T<S>(S(u(rng)), S(u(rng)), S(u(rng)));
    X_WA.linear() = spook::QuatT<S>::UnitRandom().toRotationMatrix();
    X_WB.linear() = spook::QuatT<S>::UnitRandom().toRotationMatrix();
    const spook::Vec3 d = (X_WB.translation() - X_WA.translation()).template cast<double>();
    const double depth = 1.5 - d.norm();
    if (std::abs(depth) <= 1e-6 || d.norm() < 1e-3) continue;
    std::vector<spook::ContactPointT<S>> points;
    spook::ContactSinkT<S> sink(points);
    spook::detail::collideByCcd<S>(*a, X_WA, *b, X_WB, sink);
    if ((depth > 0) != !points.empty()) {
      ++missed;
      continue;
    }
    if (points.empty()) continue;
    ++compared;
    worstDepth = std::max(worstDepth, std::abs(double(points[0].depth) - depth));
    const double cosine = std::clamp(points[0].normal.template cast<double>().dot(d.normalized()), -1.0, 1.0);
    worstAngle = std::max(worstAngle, std::acos(cosine));
  }
  MESSAGE("spheres through libccd: " << compared << " overlaps, worst depth error " << worstDepth
                                     << " m, worst normal error " << worstAngle << " rad");
  CHECK(compared * 10 > cases * 3);
  CHECK(missed * 1000 <= cases);  // 99.9 %
  CHECK(worstDepth <= double(pick<S>(1e-9, 2e-5)));
  CHECK(worstAngle <= 1e-3);
}

// A small shape resting on a large one overlaps it by micrometres: libccd's
// GJK alone called 0.7 % of such overlaps (1e-9..1e-4 m on boxes of
// 0.5..500 m) apart, each a step of free fall through a resting contact.
// Every one must be found, its depth within 1e-10 of the box's size; a gap
// within the touching gap (1e-5 of the smaller shape's size, 3.5e-6 m
// here) touches along the whole side line (two contacts of depth 0), and a
// wider one must give nothing.
TEST_CASE("libccd bridge finds every shallow overlap of a cylinder resting on a large box, and no gap") {
  spook::ref_ptr<spook::Cylinder> cylinder = new spook::Cylinder(0.2, 0.4);  // lying: axis along y
  const double touching = spook::detail::kTouchingGap * cylinder->getBoundingBox().halfExtents().norm();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int missed = 0, phantom = 0, untouched = 0, cases = 0;
  double worstDepth = 0;
  for (const double half : {0.5, 5.0, 25.0, 50.0, 500.0})
    for (int k = 0; k < spook::test::sweep(1000, 100); ++k) {
      const double overlap = std::pow(10.0, -9.0 + 2.5 * (u(rng) + 1.0));  // 1e-9 .. 1e-4 m
      const bool apart = k % 4 == 0, near = k % 4 == 1;  // a gap wider than the touching gap, or within it
      spook::ref_ptr<spook::Box> box = new spook::Box(spook::Vec3(half, half, 0.5));
      spook::Transform X_A = spook::Transform::Identity(), X_B = spook::Transform::Identity();
      X_A.translation() = spook::Vec3(0.9 * half * u(rng), 0.9 * half * u(rng), -0.5);
      const double gap = apart ? std::max(overlap, 2.0 * touching) : near ? 0.45 * touching * (u(rng) + 1.0) : -overlap;
      X_B.translation() = spook::Vec3(0.07 * u(rng), 0.11 * u(rng), 0.2 + gap);
      // A side line hanging over the box's rim touches the rim with the
      // round side: its true gap is wider (1.6e-4 m 8 mm beyond the rim).
      if (near && std::abs(X_B.translation().x() - X_A.translation().x()) > half) continue;
      std::vector<spook::ContactPointT<double>> points;
      spook::ContactSinkT<double> sink(points);
      spook::detail::collideByCcd<double>(*box, X_A, *cylinder, X_B, sink);
      ++cases;
      if (apart) {
        phantom += points.empty() ? 0 : 1;
        continue;
      }
      if (points.size() != 2) {  // the two ends of the side line
        ++(near ? untouched : missed);
        continue;
      }
      for (const auto& p : points) worstDepth = std::max(worstDepth, std::abs(p.depth - std::max(-gap, 0.0)) / half);
    }
  MESSAGE(cases << " cases: " << missed << " overlaps missed, " << untouched << " touching gaps missed, " << phantom
                << " wider gaps touching, worst depth error " << worstDepth << " of the box's half size");
  CHECK(missed == 0);
  CHECK(untouched == 0);
  CHECK(phantom == 0);
  CHECK(worstDepth <= 1e-10);
}

// Fuzz finding (tests/fuzz/corpus/finding_line_length_overflow): a segment
// whose finite endpoints lie more than DBL_MAX m apart (each coordinate's
// difference finite) has an infinite size; libccd's
// EPA dereferenced a null face on it. The bridge gives no contact for a
// shape whose size is not finite (in libccd's double), and a finite long
// segment still collides.
TEST_CASE_TEMPLATE("libccd bridge skips a segment whose length overflows, and collides a long finite one", S, float,
                   double) {
  using Vec3 = spook::Vec3T<S>;
  const S far = S(0.8) * std::numeric_limits<S>::max();
  spook::ref_ptr<spook::CylinderT<S>> cylinder = new spook::CylinderT<S>(S(0.5), S(1));
  spook::ref_ptr<spook::LineT<S>> overflowing = new spook::LineT<S>(Vec3(S(0), S(0.1), S(0)), Vec3(far, far, S(0)));
  spook::ref_ptr<spook::LineT<S>> long_ = new spook::LineT<S>(Vec3(S(-1e6), S(0.1), S(0)), Vec3(S(1e6), S(0.1), S(0)));
  REQUIRE_FALSE(std::isfinite((overflowing->getBoundingBox().max - overflowing->getBoundingBox().min).norm()));
  const auto X = spook::TransformT<S>::Identity();
  std::vector<spook::ContactPointT<S>> points;
  spook::ContactSinkT<S> sink(points);
  spook::detail::collideByCcd<S>(*cylinder, X, *overflowing, X, sink);
  // libccd works in double: a float segment's size is finite there.
  if constexpr (std::is_same_v<S, double>) CHECK(points.empty());
  for (const auto& point : points) CHECK((point.point.allFinite() && point.normal.allFinite()));
  points.clear();
  spook::detail::collideByCcd<S>(*cylinder, X, *long_, X, sink);
  REQUIRE(points.size() >= 1);
  for (const auto& point : points) CHECK(std::isfinite(double(point.depth)));
}

// Fuzz finding (tests/fuzz/corpus/finding_epa-endless): a small tilted
// cylinder sunk into a flat cylinder of radius 1e100 (a finite shape the
// API accepts). libccd's EPA, whose tolerance is absolute (1e-6), never
// converged on supports of that size and ran for minutes; the bridge caps
// its support calls (kCcdSupportBudget), and the polishing still finds the
// exact overlap: the small cylinder's lowest rim point below the top face,
// along the disk's axis.
TEST_CASE("libccd bridge ends on a cylinder of radius 1e100 and finds the overlap on its face") {
  using Transform = spook::TransformT<double>;
  // The poses and sizes of the finding, bit for bit.
  const double poseA[12] = {0x0p+0, 0x0p+0, 0x1p+0, 0x1.d8f7f6d0eec7cp-2, 0x1p+0, 0x0p+0,
                            0x0p+0, 0x1.d8f7f6d0eec7cp-2, 0x0p+0, 0x1p+0, 0x0p+0, 0x1.d8f7f6d0eec7cp-2};
  const double poseB[12] = {-0x1.3b472155b2bd9p-2, 0x1.81be0406e221dp-3, 0x1.dd7cc1b9c1e85p-1, -0x1.380e738cd28f4p-1,
                            -0x1.ba01066863cb2p-1, -0x1.de8ad63c12438p-2, -0x1.86667364eb764p-3, -0x1.85a815ac76157p+0,
                            0x1.9984d5ac4577cp-2,  -0x1.ba4270895f33p-1,  0x1.39d75ab1c4c54p-2,  0x1.f9cda1bbb19b2p+0};
  Transform X_WA = Transform::Identity(), X_WB = Transform::Identity();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 4; ++j) {
      X_WA.matrix()(i, j) = poseA[4 * i + j];
      X_WB.matrix()(i, j) = poseB[4 * i + j];
    }
  }
  spook::ref_ptr<spook::CylinderT<double>> disk = new spook::CylinderT<double>(0x1.249ad2594c37dp+332, 0x1.779ea6afdef03p+0);
  spook::ref_ptr<spook::CylinderT<double>> small = new spook::CylinderT<double>(0x1.78ff4fab822e7p-1, 0x1.779ea6afdef03p+0);
  const spook::Vec3 axis = X_WA.linear().col(1);  // the cylinder's axis is its local y
  const double top = axis.dot(X_WA.translation()) + disk->getHeight() / 2;
  const double lowest = axis.dot(X_WB * small->support(X_WB.linear().transpose() * -axis));
  std::vector<spook::ContactPointT<double>> points;
  spook::ContactSinkT<double> sink(points);
  spook::detail::collideByCcd(*disk, X_WA, *small, X_WB, sink);
  REQUIRE(points.size() >= 1);
  for (const auto& point : points) {
    CHECK(point.normal.dot(axis) == doctest::Approx(1.0).epsilon(1e-12));
    CHECK(point.depth == doctest::Approx(top - lowest).epsilon(1e-9));
  }
}
