// Differential tests of the analytic colliders with a sphere against FCL,
// whose closed forms for these pairs are exact (see collide_reference.hpp).
// Each pair: 10,000 random placements (fixed seed, about half of them
// intersecting), in float and in double, judged by checkPair: intersecting
// or not agrees in >= 99.9 % of the cases farther than 1e-6 m from
// touching, depth within 1e-6 m (double) or 1e-4 m (float, justified at
// depthTolerance), normal within 1e-3 rad unless another direction
// separates the shapes as well.

#include <doctest/doctest.h>

#include <spook/collide/colliders/box_sphere.hpp>
#include <spook/collide/colliders/capsule_sphere.hpp>
#include <spook/collide/colliders/cylinder_sphere.hpp>
#include <spook/collide/colliders/line_sphere.hpp>
#include <spook/collide/colliders/plane_sphere.hpp>
#include <spook/collide/colliders/sphere_sphere.hpp>

#include "collide_reference.hpp"

using namespace spook::test;
using spook::BoxT;
using spook::CapsuleT;
using spook::CylinderT;
using spook::LineT;
using spook::PlaneT;
using spook::SphereT;

namespace {

// A sphere whose center is uniformly 0 to `reach` m from the first shape's
// center, in a random direction.
template <class A>
PairCase<A, SphereT<double>> withSphere(RandomPoses& random, A* a, double reach) {
  PairCase<A, SphereT<double>> c;
  c.a = a;
  c.b = new SphereT<double>(random.length(0.1, 0.8));
  c.X_WA = random.pose(1.0);
  c.X_WB = random.poseNear(c.X_WA.translation(), reach + 2.0 * c.b->getRadius());
  return c;
}

template <class S, class A>
void checkAgainstFcl(const char* name, std::uint64_t seed, auto&& sample) {
  checkPair<S, A, SphereT<double>>(name, seed, sample, fclReference<A, SphereT<double>>);
}

}  // namespace

TEST_CASE_TEMPLATE("sphere-sphere contacts agree with FCL's closed form", S, float, double) {
  checkAgainstFcl<S, SphereT<double>>("sphere-sphere", 101, [](RandomPoses& random) {
    return withSphere(random, new SphereT<double>(random.length(0.1, 0.8)), 0.8);
  });
}

TEST_CASE_TEMPLATE("box-sphere contacts agree with FCL's closed form, center inside the box included", S, float,
                   double) {
  checkAgainstFcl<S, BoxT<double>>("box-sphere", 102, [](RandomPoses& random) {
    const Vec3d h(random.length(0.1, 1.0), random.length(0.1, 1.0), random.length(0.1, 1.0));
    return withSphere(random, new BoxT<double>(h), 1.2);
  });
}

TEST_CASE_TEMPLATE("capsule-sphere contacts agree with FCL's closed form", S, float, double) {
  checkAgainstFcl<S, CapsuleT<double>>("capsule-sphere", 103, [](RandomPoses& random) {
    return withSphere(random, new CapsuleT<double>(random.length(0.1, 0.6), random.length(0.1, 2.0)), 1.1);
  });
}

TEST_CASE_TEMPLATE("cylinder-sphere contacts agree with FCL's closed form, center inside included", S, float, double) {
  checkAgainstFcl<S, CylinderT<double>>("cylinder-sphere", 104, [](RandomPoses& random) {
    return withSphere(random, new CylinderT<double>(random.length(0.1, 1.0), random.length(0.1, 2.0)), 1.4);
  });
}

// FCL has no segment: a capsule of radius 0 stands in, with FCL's closed
// form for sphere–capsule.
TEST_CASE_TEMPLATE("line-sphere contacts agree with FCL's closed form for a capsule of radius 0", S, float, double) {
  checkAgainstFcl<S, LineT<double>>("line-sphere", 105, [](RandomPoses& random) {
    const Vec3d offset = random.unit() * random.uniform(0.0, 0.3), along = random.unit() * random.length(0.05, 1.0);
    return withSphere(random, new LineT<double>(offset - along, offset + along), 0.4);
  });
}

// The solid half-space below the plane: FCL's fcl::Halfspace.
TEST_CASE_TEMPLATE("plane-sphere contacts agree with FCL's half-space closed form", S, float, double) {
  checkAgainstFcl<S, PlaneT<double>>("plane-sphere", 106, [](RandomPoses& random) {
    PairCase<PlaneT<double>, SphereT<double>> c;
    c.a = new PlaneT<double>(random.unit(), Vec3d(random.unit() * random.uniform(0.0, 0.5)));
    c.b = new SphereT<double>(random.length(0.1, 0.8));
    c.X_WA = random.pose(1.0);
    const Vec3d n = c.X_WA.linear() * c.a->getNormal(), onPlane = c.X_WA * c.a->getPoint();
    const Vec3d tangent = random.unit().cross(n);
    const double r = c.b->getRadius();
    c.X_WB = random.pose(0.0);
    c.X_WB.translation() = onPlane + random.uniform(-r, 3.0 * r) * n + tangent;
    return c;
  });
}

// The convention collide_reference.hpp relies on: FCL 0.7's contact normal
// points from the first object toward the second (moving the second by the
// depth along it separates them), as spook's, also for a half-space first.
TEST_CASE("FCL's contact normal points from the first object toward the second") {
  const spook::ref_ptr<SphereT<double>> a = new SphereT<double>(1.0), b = new SphereT<double>(1.0);
  Transformd X_WB = Transformd::Identity();
  X_WB.translation() = Vec3d(1.5, 0, 0);
  const Reference spheres = fclReference(*a, Transformd::Identity(), *b, X_WB);
  CHECK(spheres.intersect);
  CHECK(spheres.depth == doctest::Approx(0.5));
  CHECK((spheres.normal - Vec3d::UnitX()).norm() <= 1e-12);

  const spook::ref_ptr<PlaneT<double>> plane = new PlaneT<double>(Vec3d::UnitZ());
  X_WB.translation() = Vec3d(0, 0, 0.5);
  const Reference halfSpace = fclReference(*plane, Transformd::Identity(), *a, X_WB);
  CHECK(halfSpace.depth == doctest::Approx(0.5));
  CHECK((halfSpace.normal - Vec3d::UnitZ()).norm() <= 1e-12);
}
