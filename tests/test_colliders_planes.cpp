// Differential tests of the analytic colliders against a plane (the solid
// half-space below it) with FCL's fcl::Halfspace, whose closed forms for
// boxes, capsules and cylinders are exact; a line is FCL's capsule of
// radius 0. FCL reports only the deepest point; spook may report more
// (every penetrating corner, end or rim point), and its deepest must match.
// Apart, the signed distance is the lowest support point's height above
// the plane. 10,000 random placements per pair (fixed seeds, about half
// intersecting), float and double, judged by checkPair (see
// collide_reference.hpp for the tolerances).

#include <doctest/doctest.h>

#include <spook/collide/colliders/box_plane.hpp>
#include <spook/collide/colliders/capsule_plane.hpp>
#include <spook/collide/colliders/cylinder_plane.hpp>
#include <spook/collide/colliders/line_plane.hpp>

#include "collide_reference.hpp"

using namespace spook::test;
using spook::BoxT;
using spook::CapsuleT;
using spook::CylinderT;
using spook::LineT;
using spook::PlaneT;

namespace {

// FCL's collide; apart, the height of the shape's lowest point (its support
// along −n) above the plane.
template <class A>
Reference planeReference(const A& a, const Transformd& X_WA, const PlaneT<double>& b, const Transformd& X_WB) {
  const FclObject oa = toFcl(a, X_WA), ob = toFcl(b, X_WB);
  Reference reference = fclCollide(*oa, *ob);
  const Vec3d n = X_WB.linear() * b.getNormal();
  const double lowest = n.dot(supportWorld(a, X_WA, -n) - X_WB * b.getPoint());
  if (!reference.intersect) reference.signedDistance = lowest;
  return reference;
}

// A random plane, and the shape's center at a height uniform in
// [−reach/2, 5 reach/2] above it (about half intersect for reach near the
// shape's extent along the normal), shifted along the plane.
template <class A>
PairCase<A, PlaneT<double>> onPlane(RandomPoses& random, A* a, double reach) {
  PairCase<A, PlaneT<double>> c;
  c.a = a;
  c.b = new PlaneT<double>(random.unit(), Vec3d(random.unit() * random.uniform(0.0, 0.5)));
  c.X_WB = random.pose(1.0);
  const Vec3d n = c.X_WB.linear() * c.b->getNormal(), point = c.X_WB * c.b->getPoint();
  c.X_WA = random.pose(0.0);
  c.X_WA.translation() = point + random.uniform(-0.5 * reach, 2.5 * reach) * n + random.unit().cross(n);
  return c;
}

template <class S, class A>
spook::test::Agreement checkPlane(const char* name, std::uint64_t seed, auto&& sample) {
  return checkPair<S, A, PlaneT<double>>(name, seed, sample, planeReference<A>);
}

}  // namespace

TEST_CASE_TEMPLATE("box-plane: the deepest of the penetrating corners agrees with FCL", S, float, double) {
  const auto agreement = checkPlane<S, BoxT<double>>("box-plane", 201, [](RandomPoses& random) {
    const Vec3d h(random.length(0.1, 1.0), random.length(0.1, 1.0), random.length(0.1, 1.0));
    return onPlane(random, new BoxT<double>(h), 0.8 * h.norm());
  });
  CHECK(agreement.maxContacts >= 4);
}

TEST_CASE_TEMPLATE("capsule-plane: the deeper end agrees with FCL", S, float, double) {
  checkPlane<S, CapsuleT<double>>("capsule-plane", 202, [](RandomPoses& random) {
    const double r = random.length(0.1, 0.6), h = random.length(0.1, 2.0);
    return onPlane(random, new CapsuleT<double>(r, h), 0.8 * (r + 0.5 * h));
  });
}

TEST_CASE_TEMPLATE("cylinder-plane: the deepest rim point agrees with FCL", S, float, double) {
  checkPlane<S, CylinderT<double>>("cylinder-plane", 203, [](RandomPoses& random) {
    const double r = random.length(0.1, 1.0), h = random.length(0.1, 2.0);
    return onPlane(random, new CylinderT<double>(r, h), 0.8 * std::hypot(r, 0.5 * h));
  });
}

TEST_CASE_TEMPLATE("line-plane: the deeper endpoint agrees with FCL's capsule of radius 0", S, float, double) {
  checkPlane<S, LineT<double>>("line-plane", 204, [](RandomPoses& random) {
    const Vec3d offset = random.unit() * random.uniform(0.0, 0.3), along = random.unit() * random.length(0.05, 1.0);
    return onPlane(random, new LineT<double>(offset - along, offset + along), 0.5 * along.norm());
  });
}
