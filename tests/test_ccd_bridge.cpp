#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <spook/collide/detail/ccd_bridge.hpp>
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
  const int cases = spook::test::sweep(10000, 1000);
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
