// The libccd bridge (detail::collideByCcd, the fallback of convex pairs
// without an analytic collider), float and double: intersecting or not
// agrees with FCL's GJK (GST_INDEP) in >= 99.9 % of the cases farther than
// 1e-6 m from touching, depth within 1e-4 m and normal within 1e-3 rad of
// an exact reference, on contacts as a simulation makes them: the second
// shape placed at −5 cm to +10 cm penetration along a random direction
// (1,000 cases per pair, see `touching`). Deep overlaps, the second
// shape's center anywhere within reach of the first's, are measured and
// logged, intersecting or not checked, the depth not judged.
//
// The reference for depth and normal is not FCL: FCL 0.7.0's GST_INDEP
// GJK/EPA (its only path for these pairs) reports the EPA result raw, the
// depth negated and the normal in the first shape's frame, and even
// corrected for both it is often not the minimum for deep overlaps (the
// last test case measures it). So depth and normal come from exact
// computations that share nothing with libccd or FCL's EPA: the separating
// axis theorem over all face normals and edge cross products for
// polytopes, the closest point on the hull's triangles for a hull and a
// sphere, and a brute-force minimization of the projection overlap for
// curved shapes (overlapMinimum, itself checked against closed forms
// below). 1e-4 m is the bridge's bound: libccd's EPA stops at 1e-6 m on
// polytopes but 1e-4..1e-3 m short on curved shapes before the polishing.

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

namespace {

const auto ccd = [](const auto& a, const auto& X_WA, const auto& b, const auto& X_WB, auto& sink) {
  spook::detail::collideByCcd(a, X_WA, b, X_WB, sink);
};

constexpr double kCcdDepth = 1e-4;  // m
constexpr int kCcdCases = 1000;

// Contacts as a simulation makes them: the second shape turned at random
// and moved so that its deepest point along −u, for a random direction u,
// sits δ ∈ [−5, 10] cm below the first shape's highest point along u: the
// shapes are apart (the plane between the two points separates them) for
// δ < 0, and overlap by at most δ otherwise.
template <class A, class B>
PairCase<A, B> touching(RandomPoses& random, A* a, B* b) {
  PairCase<A, B> c;
  c.a = a;
  c.b = b;
  c.X_WA = random.pose(1.0);
  c.X_WB = random.pose(0.0);
  const Vec3d u = random.unit();
  const double delta = random.uniform(-0.05, 0.1);
  c.X_WB.translation() = supportWorld(*a, c.X_WA, u) - delta * u - supportWorld(*b, c.X_WB, -u);
  return c;
}

// The second shape anywhere within `reach` of the first one's center:
// mostly deep overlaps.
template <class A, class B>
PairCase<A, B> near(RandomPoses& random, A* a, B* b, double reach) {
  PairCase<A, B> c;
  c.a = a;
  c.b = b;
  c.X_WA = random.pose(1.0);
  c.X_WB = random.poseNear(c.X_WA.translation(), reach);
  return c;
}

CylinderT<double>* randomCylinder(RandomPoses& random) {
  return new CylinderT<double>(random.length(0.1, 0.8), random.length(0.2, 1.6));
}

// The convex hull of 12 random points on an ellipsoid.
ConvexT<double>* randomConvex(RandomPoses& random) {
  const Vec3d axes(random.length(0.2, 0.8), random.length(0.2, 0.8), random.length(0.2, 0.8));
  std::vector<Vec3d> points;
  for (int i = 0; i < 12; ++i) points.push_back(random.unit().cwiseProduct(axes));
  return new ConvexT<double>(points);
}

// Intersecting or not by FCL's GJK; depth, normal and signed distance by `exact`.
template <class A, class B>
auto withFclIntersection(auto exact) {
  return [exact](const A& a, const Transformd& X_WA, const B& b, const Transformd& X_WB) {
    const FclObject oa = toFcl(a, X_WA), ob = toFcl(b, X_WB);
    Reference reference = exact(a, X_WA, b, X_WB);
    reference.intersect = fclCollide(*oa, *ob).intersect;
    return reference;
  };
}

Reference boxConvexReference(const BoxT<double>& a, const Transformd& X_WA, const ConvexT<double>& b,
                             const Transformd& X_WB) {
  std::vector<Vec3d> axes;
  for (int i = 0; i < 3; ++i) axes.push_back(X_WA.linear().col(i));
  for (const auto& face : b.getFaces()) axes.push_back(X_WB.linear() * face.normal);
  const auto& v = b.getVertices();
  for (const auto& t : b.getTriangles())
    for (int k = 0; k < 3; ++k) {
      const Vec3d edge = X_WB.linear() * (v[std::size_t(t[(k + 1) % 3])] - v[std::size_t(t[k])]);
      for (int i = 0; i < 3; ++i) axes.push_back(X_WA.linear().col(i).cross(edge));
    }
  return axesMinimum(a, X_WA, b, X_WB, axes);
}

// Contacts as a simulation makes them, judged; then deep overlaps with
// the same reference, logged.
template <class S, class A, class B>
void checkCcd(const std::string& name, std::uint64_t seed, auto&& makeA, auto&& makeB, double reach, auto&& reference) {
  checkDifferential<S, A, B>(
      name, seed, [&](RandomPoses& random) { return touching(random, makeA(random), makeB(random)); }, ccd, reference,
      kCcdDepth, kCcdCases);
  checkDifferential<S, A, B>(
      name + " (deep)", seed + 1000,
      [&](RandomPoses& random) { return near(random, makeA(random), makeB(random), reach); }, ccd, reference, kCcdDepth,
      kCcdCases / 4, 0.0);
}

auto randomBox(RandomPoses& random) {
  return new BoxT<double>(Vec3d(random.length(0.1, 0.8), random.length(0.1, 0.8), random.length(0.1, 0.8)));
}

}  // namespace

// Known shortfall of the bridge, measured here: its polishing descent stops
// where the overlap function has a kink (a cylinder's rim, a box's faces),
// up to ~3 mm deeper than the minimum on shallow contacts with a cylinder
// or a box, and libccd's EPA is far off on deep overlaps (~0.4 m). These
// cases state the 1e-4 m / 1e-3 rad target and may fail until the bridge
// meets it; the log shows by how much.

TEST_CASE_TEMPLATE("libccd bridge: cylinder-cylinder penetration is the overlap minimum", S,
                   float, double) {
  using C = CylinderT<double>;
  checkCcd<S, C, C>("ccd cylinder-cylinder", 401, randomCylinder, randomCylinder, 1.8,
                    withFclIntersection<C, C>(overlapMinimum<C, C>));
}

TEST_CASE_TEMPLATE("libccd bridge: box-cylinder penetration is the overlap minimum", S, float,
                   double) {
  checkCcd<S, BoxT<double>, CylinderT<double>>(
      "ccd box-cylinder", 402, randomBox, randomCylinder, 1.8,
      withFclIntersection<BoxT<double>, CylinderT<double>>(overlapMinimum<BoxT<double>, CylinderT<double>>));
}

TEST_CASE_TEMPLATE("libccd bridge: capsule-cylinder penetration is the overlap minimum", S, float,
                   double) {
  const auto capsule = [](RandomPoses& random) {
    return new CapsuleT<double>(random.length(0.1, 0.5), random.length(0.1, 1.5));
  };
  checkCcd<S, CapsuleT<double>, CylinderT<double>>(
      "ccd capsule-cylinder", 403, capsule, randomCylinder, 1.8,
      withFclIntersection<CapsuleT<double>, CylinderT<double>>(overlapMinimum<CapsuleT<double>, CylinderT<double>>));
}

// Intersecting or not by the separating axes as well: FCL 0.7.0's GJK
// misses 5 in 2,000 of these box–fcl::Convex overlaps, up to 6.5 cm deep,
// on which the separating axes, polytopePenetration and overlapMinimum all
// agree.
TEST_CASE_TEMPLATE("libccd bridge: box-convex penetration is the separating-axis minimum", S,
                   float, double) {
  checkCcd<S, BoxT<double>, ConvexT<double>>("ccd box-convex", 404, randomBox, randomConvex, 1.6, boxConvexReference);
}

TEST_CASE_TEMPLATE("libccd bridge: convex-sphere penetration is the closed form on the hull", S, float, double) {
  const auto sphere = [](RandomPoses& random) { return new SphereT<double>(random.length(0.1, 0.8)); };
  checkCcd<S, ConvexT<double>, SphereT<double>>(
      "ccd convex-sphere", 405, randomConvex, sphere, 1.4,
      withFclIntersection<ConvexT<double>, SphereT<double>>(convexSphereReference));
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
  for (int k = 0; k < 300; ++k) {
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
  for (int k = 0; k < 1000; ++k) {
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
