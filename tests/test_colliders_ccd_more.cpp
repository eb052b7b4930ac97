// The libccd bridge (detail::collideByCcd) for the convex pairs with a hull
// or a segment, and the hull–plane collider, float and double; see
// test_colliders_ccd.cpp for the pairs with a box, a cylinder or a sphere
// and for what is judged (checkCcd: 10,000 contacts as a simulation makes
// them per pair and scalar, 100 without NDEBUG, plus deep overlaps;
// intersecting or not agrees in >= 99.9 % of the cases farther than 1e-6 m
// from touching, depth within 1e-4 m, normal within 1e-3 rad or
// equivalent). The hulls are randomHull's: half of them 20–40 points on an
// ellipsoid, half box-shaped.
//
// The references, exact except for curved shapes, none of them libccd's or
// FCL's GJK/EPA:
// - hull–hull, hull–segment: the separating axes of the Minkowski
//   difference (face normals, and edge cross products whose arcs cross on
//   the Gauss map, or each hull edge crossed with the segment);
// - capsule–hull: the same axes for the capsule's segment while it meets
//   the hull (depth = radius + the segment's), else radius minus the
//   segment's distance to the hull's triangles;
// - capsule–line: radius minus the distance of the two segments (FCL's
//   closed form for segment closest points);
// - hull–cylinder, cylinder–line: the brute-force overlap minimum
//   (overlapMinimum);
// - line–line: two segments meet only in degenerate cases, so random poses
//   must give no contact, and crossing ones a finite contact or none;
// - hull–plane: FCL's closed form for fcl::Convex against a half-space, the
//   lowest corner's height when apart.
// Test cases at the end check the exact references against each other and
// against overlapMinimum, and the Gauss-map pruning against all edge pairs.

#include <doctest/doctest.h>

#include <spook/collide/collider.hpp>
#include <spook/collide/colliders/mesh.hpp>

#include "collide_reference.hpp"
#include "compiled_collide.hpp"

using namespace spook::test;
using spook::BoxT;
using spook::CapsuleT;
using spook::ConvexT;
using spook::CylinderT;
using spook::LineT;
using spook::PlaneT;

namespace {

// The capsule's segment against the hull: while it meets the hull, the
// separating axes (hull faces, hull edges × the segment) give the capsule's
// depth, its radius plus the segment's; apart, the radius minus the
// segment's distance to the hull, along the line between the closest points.
Reference capsuleConvexReference(const CapsuleT<double>& a, const Transformd& X_WA, const ConvexT<double>& b,
                                 const Transformd& X_WB) {
  const auto [p, q] = worldSegment(a, X_WA);
  Reference reference = axesMinimum(a, X_WA, b, X_WB, segmentAxes(polytopeFeatures(b, X_WB), q - p));
  if (reference.depth < a.getRadius()) {
    const SegmentPoints closest = segmentHullPoints(p, q, b, X_WB);
    reference.depth = a.getRadius() - closest.distance();
    reference.normal = (closest.onSecond - closest.onFirst) / closest.distance();
  }
  reference.intersect = reference.depth >= 0.0;
  reference.signedDistance = -reference.depth;
  return reference;
}

Reference capsuleLineReference(const CapsuleT<double>& a, const Transformd& X_WA, const LineT<double>& b,
                               const Transformd& X_WB) {
  const auto [pa, qa] = worldSegment(a, X_WA);
  const auto [pb, qb] = worldSegment(b, X_WB);
  const SegmentPoints closest = closestSegmentPoints(pa, qa, pb, qb);
  Reference reference;
  reference.depth = a.getRadius() - closest.distance();
  reference.normal = (closest.onSecond - closest.onFirst) / closest.distance();
  reference.intersect = reference.depth >= 0.0;
  reference.signedDistance = -reference.depth;
  return reference;
}

// Two segments: their distance; they intersect only when it is 0 (a flat
// Minkowski difference, depth 0).
Reference lineLineReference(const LineT<double>& a, const Transformd& X_WA, const LineT<double>& b,
                            const Transformd& X_WB) {
  const auto [pa, qa] = worldSegment(a, X_WA);
  const auto [pb, qb] = worldSegment(b, X_WB);
  Reference reference;
  reference.signedDistance = closestSegmentPoints(pa, qa, pb, qb).distance();
  reference.intersect = reference.signedDistance == 0.0;
  return reference;
}

// FCL's Convex–Halfspace closed form (the deepest corner); apart, the
// height of the lowest corner above the plane.
Reference convexPlaneReference(const ConvexT<double>& a, const Transformd& X_WA, const PlaneT<double>& b,
                               const Transformd& X_WB) {
  const FclObject oa = toFcl(a, X_WA), ob = toFcl(b, X_WB);
  Reference reference = fclCollide(*oa, *ob);
  const Vec3d n = X_WB.linear() * b.getNormal(), o = X_WB * b.getPoint();
  double lowest = std::numeric_limits<double>::infinity();
  for (const Vec3d& v : a.getVertices()) lowest = std::min(lowest, n.dot(X_WA * v - o));
  if (!reference.intersect) reference.signedDistance = lowest;
  return reference;
}

// A random plane and a hull whose frame origin is at a height uniform in
// [−0.3, 1.5] m above it: about half of them cut it.
PairCase<ConvexT<double>, PlaneT<double>> hullOnPlane(RandomPoses& random) {
  PairCase<ConvexT<double>, PlaneT<double>> c;
  c.a = randomHull(random);
  c.b = new PlaneT<double>(random.unit(), floatExact(random.unit() * random.uniform(0.0, 0.5)));
  c.X_WB = random.pose(1.0);
  const Vec3d n = c.X_WB.linear() * c.b->getNormal(), point = c.X_WB * c.b->getPoint();
  c.X_WA = random.pose(0.0);
  c.X_WA.translation() = point + random.uniform(-0.3, 1.5) * n + random.unit().cross(n);
  return c;
}

}  // namespace

TEST_CASE_TEMPLATE("libccd bridge, 10,000 poses: capsule-convex penetration is exact on the segment", S, float,
                   double) {
  checkCcd<S, CapsuleT<double>, ConvexT<double>>("ccd capsule-convex", 411, randomCapsule, randomHull, 1.6,
                                                 capsuleConvexReference);
}

TEST_CASE_TEMPLATE("libccd bridge, 10,000 poses: capsule-line penetration is the closed form", S, float, double) {
  checkCcd<S, CapsuleT<double>, LineT<double>>("ccd capsule-line", 412, randomCapsule, randomLine, 1.6,
                                               capsuleLineReference);
}

TEST_CASE_TEMPLATE("libccd bridge, 10,000 poses: convex-convex penetration is the separating-axis minimum", S, float,
                   double) {
  checkCcd<S, ConvexT<double>, ConvexT<double>>("ccd convex-convex", 413, randomHull, randomHull, 1.6,
                                                polytopeReference<ConvexT<double>, ConvexT<double>>);
}

// Intersecting or not by the overlap minimum's sign too: FCL's GJK on
// fcl::Convex misses some overlaps (see box-convex in test_colliders_ccd.cpp).
TEST_CASE_TEMPLATE("libccd bridge, 10,000 poses: convex-cylinder penetration is the overlap minimum", S, float,
                   double) {
  checkCcd<S, ConvexT<double>, CylinderT<double>>("ccd convex-cylinder", 414, randomHull, randomCylinder, 1.8,
                                                  sharedOverlapMinimum<ConvexT<double>, CylinderT<double>>);
}

TEST_CASE_TEMPLATE("libccd bridge, 10,000 poses: convex-line penetration is the separating-axis minimum", S, float,
                   double) {
  checkCcd<S, ConvexT<double>, LineT<double>>("ccd convex-line", 415, randomHull, randomLine, 1.4, convexLineReference);
}

TEST_CASE_TEMPLATE("libccd bridge, 10,000 poses: cylinder-line penetration is the overlap minimum", S, float, double) {
  checkCcd<S, CylinderT<double>, LineT<double>>(
      "ccd cylinder-line", 416, randomCylinder, randomLine, 1.6,
      withFclIntersection<CylinderT<double>, LineT<double>>(sharedOverlapMinimum<CylinderT<double>, LineT<double>>));
}

// Two segments in general position do not meet: placed as the other pairs
// (their projections on a random direction overlapping by up to 10 cm, or
// apart by up to 5 cm), no contact where they are farther than 1e-6 m
// apart. Then crossing ones, exactly in the shape frame (small dyadic
// coordinates, exact in float), at random angles, T-shaped, end to end and
// collinear overlapping, once in a frame that keeps them exact and once
// turned at random (crossing to round-off): a contact, if any, is finite,
// with a unit normal and a depth of at most 1e-4 m (the segments' flat
// Minkowski difference has depth 0).
TEST_CASE_TEMPLATE("libccd bridge, 10,000 poses: line-line contacts only where segments meet, never NaN", S, float,
                   double) {
  const Agreement apart = differential<S, LineT<double>, LineT<double>>(
      417, kCcdCases, [](RandomPoses& random) { return touching(random, randomLine(random), randomLine(random)); },
      collideByBridge, lineLineReference, kCcdDepth, 0.0);
  MESSAGE(describe<S>("ccd line-line", apart));
  CHECK(apart.decided * 100 >= apart.cases * 99);
  CHECK(apart.disagreements * 1000 <= apart.decided);
  CHECK(apart.nonUnit == 0);
  CHECK(apart.maxContacts <= 1);

  RandomPoses random(418);
  const auto dyadic = [&](double lo, double hi) { return std::round(random.uniform(lo, hi) * 64.0) / 64.0; };
  int cases = 0, contacts = 0, bad = 0;
  double deepest = 0.0;
  std::vector<spook::ContactPointT<S>> points;
  for (int k = 0; k < kCcdCases / 10; ++k)
    for (int kind = 0; kind < 4; ++kind)
      for (const bool turned : {false, true}) {
        // a along x through the origin, from −a0 to a1; b by kind.
        const double a0 = dyadic(0.1, 1.0), a1 = dyadic(0.1, 1.0);
        Vec3d direction(dyadic(-2.0, 2.0), dyadic(-2.0, 2.0), 0.0);
        if (direction.y() == 0.0) direction.y() = 0.5;
        Vec3d b0 = -dyadic(0.1, 1.0) * direction, b1 = dyadic(0.1, 1.0) * direction;  // crossing at the origin
        if (kind == 1) b0 = Vec3d(dyadic(-a0, a1), 0.0, 0.0), b1 = b0 + direction;    // T: b starts on a
        if (kind == 2) b0 = Vec3d(a1, 0.0, 0.0), b1 = b0 + direction;                 // end to end
        if (kind == 3) b0 = Vec3d(-dyadic(0.0, 1.0), 0.0, 0.0), b1 = Vec3d(dyadic(0.1, 1.5), 0.0, 0.0);  // collinear
        LineT<double>* a = new LineT<double>(Vec3d(-a0, 0.0, 0.0), Vec3d(a1, 0.0, 0.0));
        LineT<double>* b = new LineT<double>(b0, b1);
        const spook::ref_ptr<LineT<double>> holdA = a, holdB = b;
        Transformd X = Transformd::Identity();
        X.translation() = Vec3d(dyadic(-2.0, 2.0), dyadic(-2.0, 2.0), dyadic(-2.0, 2.0));
        if (turned) X.linear() = random.rotation();
        const spook::TransformT<S> X_W = X.template cast<S>();
        points.clear();
        spook::ContactSinkT<S> sink(points);
        collideByBridge(*castShape<S>(*a), X_W, *castShape<S>(*b), X_W, sink);
        ++cases;
        for (const auto& p : points) {
          ++contacts;
          const bool finite = p.point.allFinite() && p.normal.allFinite() && std::isfinite(double(p.depth));
          if (!(finite && std::abs(double(p.normal.norm()) - 1.0) <= 1e-5 && p.depth >= S(0) &&
                double(p.depth) <= kCcdDepth))
            ++bad;
          if (finite) deepest = std::max(deepest, double(p.depth));
        }
      }
  MESSAGE("ccd line-line <" << std::string(scalarName<S>()) << ">: " << cases
                            << " crossing, T, end-to-end and collinear pairs, " << contacts << " contacts, " << bad
                            << " not finite or with a wrong normal or depth; deepest " << deepest << " m");
  CHECK(bad == 0);
}

// Every hull corner at or below the plane is a contact; the deepest is
// FCL's closed form (depth within 1e-6 m in double, 1e-4 m in float). The
// contacts are counted too: at least the corners deeper than that
// tolerance, at most those not higher than it.
TEST_CASE_TEMPLATE("convex-plane, 10,000 poses: every corner below the plane, the deepest agrees with FCL", S, float,
                   double) {
  int miscounted = 0;
  const auto run = [&](const ConvexT<S>& a, const spook::TransformT<S>& X_WA, const PlaneT<S>& b,
                       const spook::TransformT<S>& X_WB, spook::ContactSinkT<S>& sink) {
    const std::size_t before = sink.size();
    spook::test::collideCompiled(a, X_WA, b, X_WB, sink);
    const std::size_t count = sink.size() - before;
    const Transformd XA = X_WA.template cast<double>(), XB = X_WB.template cast<double>();
    const Vec3d n = XB.linear() * b.getNormal().template cast<double>(), o = XB * b.getPoint().template cast<double>();
    std::size_t below = 0, notAbove = 0;
    for (const auto& v : a.getVertices()) {
      const double height = n.dot(XA * v.template cast<double>() - o);
      below += height < -depthTolerance<S>() ? 1 : 0;
      notAbove += height <= depthTolerance<S>() ? 1 : 0;
    }
    if (!(count >= below && count <= notAbove)) ++miscounted;
  };
  const Agreement agreement = checkDifferential<S, ConvexT<double>, PlaneT<double>>(
      "convex-plane", 419, hullOnPlane, run, convexPlaneReference, depthTolerance<S>());
  MESSAGE("convex-plane <" << std::string(scalarName<S>()) << ">: " << miscounted << " of " << agreement.cases
                           << " with a contact count outside the corners below the plane");
  CHECK(miscounted == 0);
}

// The exact references against each other and against the brute-force
// overlap minimum, on shallow and deep cases alike: on intersecting
// polytopes the Gauss-map pruning keeps the minimum over all face normals
// and edge cross products (apart, both are only lower bounds of the
// distance, the pruned one the smaller), and the
// capsule–hull, hull–segment and hull–hull references agree with
// overlapMinimum (itself checked against closed forms in
// test_colliders_ccd.cpp).
TEST_CASE("the separating-axis references agree with all edge pairs and with the overlap minimum") {
  RandomPoses random(420);
  double worstPruning = 0.0, worstCapsule = 0.0, worstLine = 0.0, worstHulls = 0.0;
  int cases = 0;
  const auto gap = [](const Reference& x, const Reference& y) { return std::abs(x.depth - y.depth); };
  for (int k = 0; k < spook::test::sweep(200, 30); ++k)
    for (const bool deep : {false, true}) {
      const auto pick = [&](auto* a, auto* b) { return deep ? near(random, a, b, 1.6) : touching(random, a, b); };
      const auto hulls = pick(randomHull(random), randomHull(random));
      const PolytopeFeatures fa = polytopeFeatures(*hulls.a, hulls.X_WA), fb = polytopeFeatures(*hulls.b, hulls.X_WB);
      const Reference pruned = axesMinimum(*hulls.a, hulls.X_WA, *hulls.b, hulls.X_WB, minkowskiAxes(fa, fb));
      const Reference all = axesMinimum(*hulls.a, hulls.X_WA, *hulls.b, hulls.X_WB, minkowskiAxes(fa, fb, false));
      if (all.intersect) worstPruning = std::max(worstPruning, gap(pruned, all));
      const auto boxHull = pick(randomBox(random), randomHull(random));
      const PolytopeFeatures fbox = polytopeFeatures(*boxHull.a, boxHull.X_WA),
                             fhull = polytopeFeatures(*boxHull.b, boxHull.X_WB);
      const Reference allBox =
          axesMinimum(*boxHull.a, boxHull.X_WA, *boxHull.b, boxHull.X_WB, minkowskiAxes(fbox, fhull, false));
      if (allBox.intersect)
        worstPruning = std::max(
            worstPruning,
            gap(axesMinimum(*boxHull.a, boxHull.X_WA, *boxHull.b, boxHull.X_WB, minkowskiAxes(fbox, fhull)), allBox));
      if (pruned.intersect)
        worstHulls = std::max(worstHulls, gap(pruned, overlapMinimum(*hulls.a, hulls.X_WA, *hulls.b, hulls.X_WB)));
      const auto capsule = pick(randomCapsule(random), randomHull(random));
      worstCapsule =
          std::max(worstCapsule, gap(capsuleConvexReference(*capsule.a, capsule.X_WA, *capsule.b, capsule.X_WB),
                                     overlapMinimum(*capsule.a, capsule.X_WA, *capsule.b, capsule.X_WB)));
      const auto line = pick(randomHull(random), randomLine(random));
      const Reference exactLine = convexLineReference(*line.a, line.X_WA, *line.b, line.X_WB);
      if (exactLine.intersect)
        worstLine = std::max(worstLine, gap(exactLine, overlapMinimum(*line.a, line.X_WA, *line.b, line.X_WB)));
      ++cases;
    }
  MESSAGE("separating axes on " << cases << " cases: pruned vs all edge pairs " << worstPruning
                                << " m; vs the overlap minimum: hull-hull " << worstHulls << " m, capsule-hull "
                                << worstCapsule << " m, hull-line " << worstLine << " m");
  CHECK(worstPruning == 0.0);
  CHECK(worstHulls <= 1e-8);
  CHECK(worstCapsule <= 1e-8);
  CHECK(worstLine <= 1e-8);
}
