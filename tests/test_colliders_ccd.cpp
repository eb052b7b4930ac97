// The libccd bridge (detail::collideByCcd, the fallback of convex pairs
// without an analytic collider), float and double, for the pairs with a
// box, a cylinder or a sphere; test_colliders_ccd_more.cpp has those with
// a hull or a segment. Each pair: intersecting or not agrees with the
// reference in >= 99.9 % of the cases farther than 1e-6 m from touching,
// depth within 1e-4 m and normal within 1e-3 rad (or an equivalent one:
// as small an overlap along it, see checkDifferential), the deepest (and
// only) contact compared, on contacts as a simulation makes them: the
// second shape placed at −5 cm to +10 cm penetration along a random
// direction (10,000 cases per pair and scalar; 100 in builds without
// NDEBUG, see kCcdCases). Deep overlaps, the second shape's center
// anywhere within reach of the first's (500; 60 without NDEBUG), are
// measured and logged, intersecting or not checked, the depth not judged.
//
// The reference for depth and normal is not FCL: FCL 0.7.0's GST_INDEP
// GJK/EPA (its only path for these pairs) reports the EPA result raw, the
// depth negated and the normal in the first shape's frame, and even
// corrected for both it is often not the minimum for deep overlaps (the
// last test case measures it). So depth and normal come from exact
// computations that share nothing with libccd or FCL's EPA: the separating
// axis theorem over the facet normals of the Minkowski difference for
// polytopes (polytopeReference), the closest point on the hull's triangles
// for a hull and a sphere, and a brute-force minimization of the
// projection overlap for curved shapes (overlapMinimum, itself checked
// against closed forms below; searched once per case for both scalars,
// sharedOverlapMinimum). Intersecting or not comes from FCL's GJK
// where FCL has the shapes as primitives, from the exact computation where
// a hull is involved (FCL 0.7.0's GJK misses some box–fcl::Convex overlaps,
// centimeters deep). 1e-4 m is the bridge's bound: libccd's EPA stops at
// 1e-6 m on polytopes but 1e-4..1e-3 m short on curved shapes before the
// polishing.

#include <doctest/doctest.h>

#include <fcl/narrowphase/detail/primitive_shape_algorithm/capsule_capsule.h>

#include <spook/collide/detail/ccd_bridge.hpp>

#include "collide_reference.hpp"

using namespace spook::test;
using spook::BoxT;
using spook::CapsuleT;
using spook::ConvexT;
using spook::CylinderT;
using spook::SphereT;

TEST_CASE_TEMPLATE("libccd bridge, 10,000 poses: cylinder-cylinder penetration is the overlap minimum", S, float,
                   double) {
  using C = CylinderT<double>;
  checkCcd<S, C, C>("ccd cylinder-cylinder", 401, randomCylinder, randomCylinder, 1.8,
                    withFclIntersection<C, C>(sharedOverlapMinimum<C, C>));
}

TEST_CASE_TEMPLATE("libccd bridge, 10,000 poses: box-cylinder penetration is the overlap minimum", S, float, double) {
  checkCcd<S, BoxT<double>, CylinderT<double>>(
      "ccd box-cylinder", 402, randomBox, randomCylinder, 1.8,
      withFclIntersection<BoxT<double>, CylinderT<double>>(sharedOverlapMinimum<BoxT<double>, CylinderT<double>>));
}

TEST_CASE_TEMPLATE("libccd bridge, 10,000 poses: capsule-cylinder penetration is the overlap minimum", S, float,
                   double) {
  checkCcd<S, CapsuleT<double>, CylinderT<double>>("ccd capsule-cylinder", 403, randomCapsule, randomCylinder, 1.8,
                                                   withFclIntersection<CapsuleT<double>, CylinderT<double>>(
                                                       sharedOverlapMinimum<CapsuleT<double>, CylinderT<double>>));
}

// Intersecting or not by the separating axes as well: FCL 0.7.0's GJK
// misses 5 in 2,000 of these box–fcl::Convex overlaps, up to 6.5 cm deep,
// on which the separating axes, polytopePenetration and overlapMinimum all
// agree. The hulls: randomHull, ellipsoid-like and box-shaped.
TEST_CASE_TEMPLATE("libccd bridge, 10,000 poses: box-convex penetration is the separating-axis minimum", S, float,
                   double) {
  checkCcd<S, BoxT<double>, ConvexT<double>>("ccd box-convex", 404, randomBox, randomHull, 1.6,
                                             polytopeReference<BoxT<double>, ConvexT<double>>);
}

TEST_CASE_TEMPLATE("libccd bridge, 10,000 poses: convex-sphere penetration is the closed form on the hull", S, float,
                   double) {
  const auto [shallow, deep] = checkCcd<S, ConvexT<double>, SphereT<double>>("ccd convex-sphere", 405, randomHull,
                                                                             randomSphere, 1.4, convexSphereReference);
  // The sphere's deepest point, not a corner of the hull's face (issue 24:
  // a sphere on a wide convex ground fell through, spun by that lever arm).
  CHECK(shallow.pointsOutside == 0);
  CHECK(deep.pointsOutside == 0);
}

// The brute-force overlap minimum against closed forms: FCL's for
// box–sphere and cylinder–sphere, the segment distance for capsule–capsule.
TEST_CASE("the brute-force overlap minimum reproduces closed-form penetrations") {
  RandomPoses random(406);
  double worstDepth = 0, worstAngle = 0;
  const auto compare = [&](const Reference& exact, const Reference& brute) {
    if (!(exact.depth > 1e-6 && brute.intersect)) return;
    worstDepth = std::max(worstDepth, std::abs(exact.depth - brute.depth));
    worstAngle =
        std::max(worstAngle, std::atan2(exact.normal.cross(brute.normal).norm(), exact.normal.dot(brute.normal)));
  };
  for (int k = 0; k < spook::test::sweep(300, 100); ++k) {
    const Vec3d h(random.length(0.1, 1.0), random.length(0.1, 1.0), random.length(0.1, 1.0));
    const auto box = near(random, new BoxT<double>(h), new SphereT<double>(random.length(0.1, 0.8)), 1.2);
    compare(fclReference(*box.a, box.X_WA, *box.b, box.X_WB), overlapMinimum(*box.a, box.X_WA, *box.b, box.X_WB));
    const auto cylinder = near(random, randomCylinder(random), new SphereT<double>(random.length(0.1, 0.8)), 1.2);
    compare(fclReference(*cylinder.a, cylinder.X_WA, *cylinder.b, cylinder.X_WB),
            overlapMinimum(*cylinder.a, cylinder.X_WA, *cylinder.b, cylinder.X_WB));
    const auto capsules = near(random, new CapsuleT<double>(random.length(0.1, 0.5), random.length(0.1, 1.5)),
                               new CapsuleT<double>(random.length(0.1, 0.5), random.length(0.1, 1.5)), 1.5);
    const Vec3d halfA = capsules.X_WA.linear().col(1) * (0.5 * capsules.a->getHeight());
    const Vec3d halfB = capsules.X_WB.linear().col(1) * (0.5 * capsules.b->getHeight());
    double s = 0, t = 0;
    Vec3d onA, onB;
    fcl::detail::closestPtSegmentSegment<double>(
        capsules.X_WA.translation() - halfA, capsules.X_WA.translation() + halfA, capsules.X_WB.translation() - halfB,
        capsules.X_WB.translation() + halfB, &s, &t, &onA, &onB);
    Reference exact;
    exact.depth = capsules.a->getRadius() + capsules.b->getRadius() - (onB - onA).norm();
    exact.normal = (onB - onA).normalized();
    compare(exact, overlapMinimum(*capsules.a, capsules.X_WA, *capsules.b, capsules.X_WB));
  }
  MESSAGE("overlap minimum vs closed forms: worst depth error " << worstDepth << " m, worst normal error " << worstAngle
                                                                << " rad");
  CHECK(worstDepth <= 1e-9);
  CHECK(worstAngle <= 1e-4);
}

// Why FCL's GJK/EPA is not the depth reference above: in FCL 0.7.0 the
// GST_INDEP path for pairs without a closed form returns −(EPA depth) and
// the EPA normal in the first shape's frame. Taking both back, its depth is
// still far above the overlap minimum on deep overlaps. Measured and
// logged, only warned about: this documents FCL, not spook.
TEST_CASE("FCL 0.7's GST_INDEP GJK/EPA reports negated depths for cylinders") {
  RandomPoses random(407);
  int negative = 0, intersecting = 0;
  double worstExcess = 0;
  for (int k = 0; k < spook::test::sweep(1000, 300); ++k) {
    const auto c = near(random, randomCylinder(random), randomCylinder(random), 1.8);
    const FclObject oa = toFcl(*c.a, c.X_WA), ob = toFcl(*c.b, c.X_WB);
    fcl::CollisionRequestd request(1, true);
    request.gjk_solver_type = fcl::GST_INDEP;
    fcl::CollisionResultd result;
    fcl::collide(oa.get(), ob.get(), request, result);
    if (result.numContacts() == 0) continue;
    ++intersecting;
    const auto& contact = result.getContact(0);
    negative += contact.penetration_depth < 0 ? 1 : 0;
    const Reference exact = overlapMinimum(*c.a, c.X_WA, *c.b, c.X_WB);
    worstExcess = std::max(worstExcess, -contact.penetration_depth - exact.depth);
  }
  MESSAGE("FCL GST_INDEP cylinder-cylinder: "
          << negative << " of " << intersecting
          << " contacts with negative depth; |depth| above the overlap minimum by up "
             "to "
          << worstExcess << " m");
  WARN(negative * 10 >= intersecting * 9);  // a warning only: a fixed FCL should not fail spook's tests
}
