// Differential tests of the colliders built on segment distances, where
// FCL's collide goes through its GJK/EPA (not exact), so the references are
// independent exact computations:
// - capsule–capsule: FCL's own closed form for segment closest points,
//   fcl::detail::closestPtSegmentSegment (used by its capsule distance,
//   not by its collide), depth r_a + r_b − |c_b − c_a|;
// - box–line: the Minkowski difference of the box corners and the segment
//   endpoints, its facets found by brute force over all point triples
//   (polytopePenetration), which assumes nothing about which axes matter.
// 10,000 random placements per pair (fixed seeds, about half intersecting),
// float and double, judged by checkPair (see collide_reference.hpp).

#include <doctest/doctest.h>

#include <fcl/narrowphase/detail/primitive_shape_algorithm/capsule_capsule.h>

#include <spook/collide/colliders/box_line.hpp>
#include <spook/collide/colliders/capsule_capsule.hpp>

#include "collide_reference.hpp"

using namespace spook::test;
using spook::BoxT;
using spook::CapsuleT;
using spook::LineT;

namespace {

Reference capsuleCapsuleReference(const CapsuleT<double>& a, const Transformd& X_WA, const CapsuleT<double>& b,
                                  const Transformd& X_WB) {
  const Vec3d halfA = X_WA.linear().col(1) * (0.5 * a.getHeight()),
              halfB = X_WB.linear().col(1) * (0.5 * b.getHeight());
  double s = 0, t = 0;
  Vec3d onA, onB;
  fcl::detail::closestPtSegmentSegment<double>(X_WA.translation() - halfA, X_WA.translation() + halfA,
                                               X_WB.translation() - halfB, X_WB.translation() + halfB, &s, &t, &onA,
                                               &onB);
  Reference reference;
  const double distance = (onB - onA).norm();
  reference.depth = a.getRadius() + b.getRadius() - distance;
  reference.intersect = reference.depth >= 0.0;
  reference.normal = (onB - onA) / distance;
  reference.signedDistance = -reference.depth;
  return reference;
}

Reference boxLineReference(const BoxT<double>& a, const Transformd& X_WA, const LineT<double>& b,
                           const Transformd& X_WB) {
  return polytopePenetration(boxCorners(a, X_WA), {X_WB * b.getFirstPoint(), X_WB * b.getSecondPoint()});
}

}  // namespace

TEST_CASE_TEMPLATE("capsule-capsule contacts agree with the closed-form segment distance", S, float, double) {
  checkPair<S, CapsuleT<double>, CapsuleT<double>>(
      "capsule-capsule", 301,
      [](RandomPoses& random) {
        PairCase<CapsuleT<double>, CapsuleT<double>> c;
        c.a = new CapsuleT<double>(random.length(0.1, 0.6), random.length(0.1, 2.0));
        c.b = new CapsuleT<double>(random.length(0.1, 0.6), random.length(0.1, 2.0));
        c.X_WA = random.pose(1.0);
        c.X_WB = random.poseNear(c.X_WA.translation(), 2.0 * (c.a->getRadius() + c.b->getRadius()) +
                                                           0.5 * (c.a->getHeight() + c.b->getHeight()));
        return c;
      },
      capsuleCapsuleReference);
}

TEST_CASE_TEMPLATE("box-line penetration is the exact minimal translation of the Minkowski difference", S, float,
                   double) {
  checkPair<S, BoxT<double>, LineT<double>>(
      "box-line", 302,
      [](RandomPoses& random) {
        PairCase<BoxT<double>, LineT<double>> c;
        const Vec3d h(random.length(0.1, 1.0), random.length(0.1, 1.0), random.length(0.1, 1.0));
        c.a = new BoxT<double>(h);
        const Vec3d offset = random.unit() * random.uniform(0.0, 0.3), along = random.unit() * random.length(0.05, 1.0);
        c.b = new LineT<double>(offset - along, offset + along);
        c.X_WA = random.pose(1.0);
        c.X_WB = random.poseNear(c.X_WA.translation(), 1.1 * h.norm() + 0.5 * along.norm());
        return c;
      },
      boxLineReference);
}
