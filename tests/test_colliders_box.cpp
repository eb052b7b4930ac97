#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <fcl/fcl.h>

#include <spook/collide/collider.hpp>
#include <spook/collide/colliders/box_box.hpp>
#include <spook/collide/colliders/box_capsule.hpp>
#include <spook/collide/colliders/box_plane.hpp>
#include <spook/collide/shapes/box.hpp>
#include <spook/collide/shapes/capsule.hpp>
#include <spook/collide/shapes/plane.hpp>

#include "tolerance.hpp"
#include "compiled_collide.hpp"

using spook::test::pick;

// Differential tests of the box–box and box–capsule colliders against FCL
// 0.7 (GST_INDEP solver). FCL's box–box is ODE's dBoxBox, exact along the
// 15 separating axes with the same 5 % preference for face axes, so it is
// the reference for depth and normal (but where it keeps a deeper edge axis,
// see checkBoxBoxAgainstFcl). FCL's capsule–box goes through its
// own GJK/EPA, which is not exact (it misses the least overlap by up to
// about 1 m on these poses); there FCL only decides intersect or not, and the
// depth and normal come from an independent exact reference below
// (Minkowski-difference hull and closest points).
//
// Tolerances: 1e-6 m on depths in double (measured ~1e-14); 1e-5 m in
// float, where ε = 1.2e-7 times lengths up to ~3 m times a few dozen
// roundings in rotations and projections gives some 1e-6 (measured below
// 5e-7). Normals within 1e-3 rad in both.

namespace {

using V3 = Eigen::Vector3d;

// ---- FCL adapters ----------------------------------------------------------

template <class S>
fcl::Transform3d toFclTransform(const spook::TransformT<S>& X) {
  fcl::Transform3d Y = fcl::Transform3d::Identity();
  Y.linear() = X.linear().template cast<double>();
  Y.translation() = X.translation().template cast<double>();
  return Y;
}

// fcl::Box takes full side lengths.
template <class S>
std::shared_ptr<fcl::CollisionGeometryd> fclBox(const spook::BoxT<S>& box) {
  const V3 side = 2.0 * box.getHalfExtents().template cast<double>();
  return std::make_shared<fcl::Boxd>(side.x(), side.y(), side.z());
}

// fcl::Capsule(radius, lz) lies along z with lz between the hemisphere
// centers; spook's lies along y. Its pose is composed with a quarter turn
// about x that takes z onto y (the capsule is symmetric, so the sign of the
// turn does not matter).
template <class S>
std::shared_ptr<fcl::CollisionGeometryd> fclCapsule(const spook::CapsuleT<S>& capsule) {
  return std::make_shared<fcl::Capsuled>(double(capsule.getRadius()), double(capsule.getHeight()));
}
template <class S>
fcl::Transform3d toFclCapsule(const spook::TransformT<S>& X) {
  fcl::Transform3d Y = toFclTransform(X);
  Y.linear() = Y.linear() * Eigen::AngleAxisd(-std::numbers::pi / 2, V3::UnitX()).toRotationMatrix();
  return Y;
}

struct FclContacts {
  bool hit = false;
  double depth = 0;        // deepest contact (m)
  V3 normal = V3::Zero();  // of the deepest contact
  std::size_t count = 0;
};

FclContacts fclContacts(const std::shared_ptr<fcl::CollisionGeometryd>& a, const fcl::Transform3d& X_WA,
                       const std::shared_ptr<fcl::CollisionGeometryd>& b, const fcl::Transform3d& X_WB) {
  fcl::CollisionObjectd objectA(a, X_WA), objectB(b, X_WB);
  fcl::CollisionRequestd request(16, true);
  request.gjk_solver_type = fcl::GST_INDEP;
  fcl::CollisionResultd result;
  fcl::collide(&objectA, &objectB, request, result);
  FclContacts out;
  out.count = result.numContacts();
  out.hit = out.count > 0;
  for (std::size_t i = 0; i < out.count; ++i) {
    const fcl::Contactd& c = result.getContact(i);
    if (i == 0 || c.penetration_depth > out.depth) {
      out.depth = c.penetration_depth;
      out.normal = c.normal;
    }
  }
  return out;
}

double fclSeparation(const std::shared_ptr<fcl::CollisionGeometryd>& a, const fcl::Transform3d& X_WA,
                   const std::shared_ptr<fcl::CollisionGeometryd>& b, const fcl::Transform3d& X_WB) {
  fcl::CollisionObjectd objectA(a, X_WA), objectB(b, X_WB);
  fcl::DistanceRequestd request;
  request.gjk_solver_type = fcl::GST_INDEP;
  fcl::DistanceResultd result;
  fcl::distance(&objectA, &objectB, request, result);
  return result.min_distance;
}

// ---- poses ---------------------------------------------------------------

// Three draws in a fixed order (the order in which function arguments are
// evaluated is unspecified, so V3(d(rng), d(rng), d(rng)) would not be).
template <class Distribution>
V3 draw3(std::mt19937& rng, Distribution& distribution) {
  const double x = distribution(rng);
  const double y = distribution(rng);
  const double z = distribution(rng);
  return V3(x, y, z);
}

// A uniformly random rotation (normalized Gaussian quaternion), from the
// test's own seeded engine rather than std::rand.
template <class S>
spook::TransformT<S> randomPose(std::mt19937& rng, const V3& center) {
  std::normal_distribution<double> gauss(0.0, 1.0);
  const double w = gauss(rng);
  const V3 v = draw3(rng, gauss);
  Eigen::Quaterniond q(w, v.x(), v.y(), v.z());
  q.normalize();
  spook::TransformT<S> X = spook::TransformT<S>::Identity();
  X.linear() = q.toRotationMatrix().cast<S>();
  X.translation() = center.cast<S>();
  return X;
}

V3 randomDirection(std::mt19937& rng) {
  std::normal_distribution<double> gauss(0.0, 1.0);
  return draw3(rng, gauss).normalized();
}

template <class S>
std::vector<spook::ContactPointT<S>> contactsOf(const auto& a, const spook::TransformT<S>& X_WA, const auto& b,
                                                const spook::TransformT<S>& X_WB) {
  std::vector<spook::ContactPointT<S>> points;
  spook::ContactSinkT<S> sink(points);
  spook::test::collideCompiled(a, X_WA, b, X_WB, sink);
  return points;
}

template <class S>
const spook::ContactPointT<S>& deepest(const std::vector<spook::ContactPointT<S>>& points) {
  return *std::max_element(points.begin(), points.end(),
                           [](const auto& p, const auto& q) { return p.depth < q.depth; });
}

double angleBetween(const V3& a, const V3& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));  // accurate near 0, unlike acos
}

bool allFinite(const auto& points) {
  return std::all_of(points.begin(), points.end(), [](const auto& p) {
    return p.point.allFinite() && p.normal.allFinite() && std::isfinite(p.depth) &&
           std::abs(p.normal.norm() - 1) < 1e-5;
  });
}

// ---- exact capsule–box reference ---------------------------------------

// Signed distance of a capsule (segment c + t·u, |t| <= h, radius r) from
// the box |x_k| <= e_k, all in the box frame, with the direction from the box
// toward the capsule, by two computations independent of the collider:
//  - segment outside the box: the segment's distance δ to the box by golden-
//    section search of the convex point–box distance along the segment;
//    signed distance δ − r;
//  - segment meeting the box: its penetration is the distance from the
//    origin to the boundary of the Minkowski difference box − segment, the
//    convex hull of the 16 differences of box corners and segment ends,
//    whose facets are found by brute force over all triples of points;
//    signed distance −(penetration + r), direction the facet's normal.
// `ambiguity` is how much worse the best facet of another normal is: near
// 0 the direction is not unique.
struct CapsuleBoxReference {
  double signedDistance = 0;
  V3 normal = V3::UnitZ();
  double ambiguity = 1;
  double segmentDistance = 0;
};

double pointBoxDistance(const V3& x, const V3& e) { return (x.cwiseAbs() - e).cwiseMax(0.0).norm(); }

CapsuleBoxReference exactCapsuleBox(const V3& e, const V3& c, const V3& u, double h, double r) {
  CapsuleBoxReference out;
  std::vector<V3> points;
  for (int corner = 0; corner < 8; ++corner) {
    const V3 b((corner & 1) ? e.x() : -e.x(), (corner & 2) ? e.y() : -e.y(), (corner & 4) ? e.z() : -e.z());
    points.push_back(b - (c + h * u));
    points.push_back(b - (c - h * u));
  }
  double best = std::numeric_limits<double>::infinity(), second = best;
  V3 bestNormal = V3::UnitZ();
  for (std::size_t i = 0; i < points.size(); ++i)
    for (std::size_t j = i + 1; j < points.size(); ++j)
      for (std::size_t k = j + 1; k < points.size(); ++k) {
        V3 n = (points[j] - points[i]).cross(points[k] - points[i]);
        if (n.norm() < 1e-9) continue;
        n.normalize();
        double lo = 0, hi = 0;
        for (const V3& p : points) {
          lo = std::min(lo, n.dot(p - points[i]));
          hi = std::max(hi, n.dot(p - points[i]));
        }
        if (lo < -1e-12 && hi > 1e-12) continue;  // not a supporting plane
        if (hi > 1e-12) n = -n;                   // outward
        const double offset = n.dot(points[i]);   // distance of the origin below the facet
        if (offset < best - 1e-12) {
          if (angleBetween(n, bestNormal) > 1e-3) second = best;
          best = offset;
          bestNormal = n;
        } else if (angleBetween(n, bestNormal) > 1e-3) {
          second = std::min(second, offset);
        }
      }
  if (best >= 0) {  // the origin is inside: the segment meets the box
    out.signedDistance = -(best + r);
    out.normal = bestNormal;
    out.ambiguity = second - best;
    return out;
  }
  // Golden-section search of the convex distance along the segment.
  double lo = -h, hi = h;
  const double golden = (std::sqrt(5.0) - 1) / 2;
  double t1 = hi - golden * (hi - lo), t2 = lo + golden * (hi - lo);
  double f1 = pointBoxDistance(c + t1 * u, e), f2 = pointBoxDistance(c + t2 * u, e);
  for (int iteration = 0; iteration < 200; ++iteration) {
    if (f1 < f2) {
      hi = t2, t2 = t1, f2 = f1;
      t1 = hi - golden * (hi - lo), f1 = pointBoxDistance(c + t1 * u, e);
    } else {
      lo = t1, t1 = t2, f1 = f2;
      t2 = lo + golden * (hi - lo), f2 = pointBoxDistance(c + t2 * u, e);
    }
  }
  double t = 0.5 * (lo + hi);
  for (const double end : {-h, h})
    if (pointBoxDistance(c + end * u, e) < pointBoxDistance(c + t * u, e)) t = end;
  const V3 x = c + t * u;
  const V3 gap = x - x.cwiseMax(-e).cwiseMin(e);
  out.segmentDistance = gap.norm();
  out.signedDistance = out.segmentDistance - r;
  out.normal = gap / gap.norm();
  return out;
}

// Overlap of the projections of box and capsule onto the unit direction n
// (box frame, from the box toward the capsule): h_box(n) + h_capsule(−n).
double capsuleBoxOverlap(const V3& n, const V3& e, const V3& c, const V3& u, double h, double r) {
  return n.cwiseAbs().dot(e) - n.dot(c) + h * std::abs(n.dot(u)) + r;
}

// Two boxes in double, world frame, and their 15 separating-axis
// candidates by brute force, independent of the collider's bookkeeping.
struct SatAxis {
  V3 axis = V3::UnitZ();  // from A toward B
  double overlap = std::numeric_limits<double>::infinity();
  bool edge = false;
};

struct BoxPair {
  V3 eA;
  Eigen::Matrix3d RA;
  V3 pA;
  V3 eB;
  Eigen::Matrix3d RB;
  V3 pB;

  // Overlap of the projections onto the unit direction n (from A toward B).
  [[nodiscard]] double overlap(const V3& n) const {
    return (RA.transpose() * n).cwiseAbs().dot(eA) + (RB.transpose() * n).cwiseAbs().dot(eB) - n.dot(pB - pA);
  }

  // The face axis of least overlap, or the edge axis of least overlap when
  // 1.05 times it is smaller still (the face preference of dBoxBox).
  [[nodiscard]] SatAxis leastOverlap() const {
    SatAxis face, edge;
    auto consider = [&](V3 n, SatAxis& best, bool isEdge) {
      if (n.dot(pB - pA) < 0) n = -n;
      const double o = overlap(n);
      if (o < best.overlap) best = SatAxis{n, o, isEdge};
    };
    for (int i = 0; i < 3; ++i) consider(RA.col(i), face, false);
    for (int j = 0; j < 3; ++j) consider(RB.col(j), face, false);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        const V3 n = RA.col(i).cross(RB.col(j));
        if (n.norm() > 1e-6) consider(n.normalized(), edge, true);
      }
    return 1.05 * edge.overlap < face.overlap ? edge : face;
  }
};

}  // namespace

// FCL 0.7's Contact::normal is documented as "pointing from o1 to o2"; two
// spheres confirm it, and it is also spook's convention.
TEST_CASE("FCL reports the contact normal from the first object toward the second") {
  const fcl::Transform3d X_WA = fcl::Transform3d::Identity();
  fcl::Transform3d X_WB = fcl::Transform3d::Identity();
  X_WB.translation() = V3(1.5, 0, 0);
  const FclContacts contacts =
      fclContacts(std::make_shared<fcl::Sphered>(1.0), X_WA, std::make_shared<fcl::Sphered>(1.0), X_WB);
  REQUIRE(contacts.hit);
  CHECK(contacts.normal.isApprox(V3::UnitX(), 1e-12));
  CHECK(std::abs(contacts.depth - 0.5) < 1e-12);
}

namespace {

// Where the randomized tests draw their shapes and poses, with fixed seeds:
//  - random: half extents in [0.1, 1] m, uniform rotations, B's center at a
//    uniform distance up to `reach` from A's in a uniform direction;
//  - lattice: half extents and radii in multiples of 0.25 m, rotations made
//    of two turns by 0, 45 or 90 degrees about coordinate axes, centers on a
//    1/8 m grid: parallel edges, coplanar faces and exact touching, where
//    ties and degenerate axes live.
class PoseSampler {
 public:
  PoseSampler(bool lattice, unsigned seed) : lattice_(lattice), rng_(seed) {}

  [[nodiscard]] bool lattice() const { return lattice_; }

  V3 halfExtents() {
    if (!lattice_) return draw3(rng_, extent_);
    return 0.25 * V3(1 + quarter(), 1 + quarter(), 1 + quarter());
  }
  // A length in [lo, hi] m (a multiple of 0.25 m on the lattice).
  double length(double lo, double hi) {
    if (!lattice_) return lo + (hi - lo) * unit_(rng_);
    return std::max(0.25, std::round((lo + (hi - lo) * unit_(rng_)) * 4) / 4);
  }
  template <class S>
  spook::TransformT<S> first() {
    return pose<S>(lattice_ ? V3::Zero() : V3(0.5 * draw3(rng_, unit_)));
  }
  template <class S>
  spook::TransformT<S> second(const spook::TransformT<S>& X_WA, double reach) {
    const V3 centerA = X_WA.translation().template cast<double>();
    if (lattice_) {
      std::uniform_int_distribution<int> cell(-int(4 * reach), int(4 * reach));  // a cube of side `reach`
      const double x = cell(rng_), y = cell(rng_), z = cell(rng_);
      return pose<S>(centerA + V3(x, y, z) / 8);
    }
    const double separation = reach * unit_(rng_);
    const V3 direction = randomDirection(rng_);
    return pose<S>(centerA + separation * direction);
  }

 private:
  int quarter() { return std::uniform_int_distribution<int>(0, 3)(rng_); }

  template <class S>
  spook::TransformT<S> pose(const V3& center) {
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
    if (lattice_) {
      for (int turn = 0; turn < 2; ++turn) {
        const double angle = std::uniform_int_distribution<int>(0, 2)(rng_) * std::numbers::pi / 4;
        R = R * Eigen::AngleAxisd(angle, V3::Unit(std::uniform_int_distribution<int>(0, 2)(rng_))).toRotationMatrix();
      }
    } else {
      R = randomPose<double>(rng_, V3::Zero()).linear();
    }
    spook::TransformT<S> X = spook::TransformT<S>::Identity();
    X.linear() = R.cast<S>();
    X.translation() = center.cast<S>();
    return X;
  }

  bool lattice_;
  std::mt19937 rng_;
  std::uniform_real_distribution<double> extent_{0.1, 1.0}, unit_{0.0, 1.0};
};

std::string describe(bool lattice, bool isFloat) {
  return std::string(lattice ? "lattice" : "random") + " poses, " + (isFloat ? "float" : "double");
}

// Box–box against FCL's dBoxBox: intersect or not, the deepest depth, the
// normal of the deepest contact.
template <class S>
void checkBoxBoxAgainstFcl(PoseSampler& sampler) {
  int intersecting = 0, decided = 0, agreed = 0, quirks = 0;
  double worstDepth = 0, worstAngle = 0, worstOverlap = 0;
  const int trials = spook::test::sweep(10000, 800);
  for (int trial = 0; trial < trials; ++trial) {
    const V3 halfA = sampler.halfExtents(), halfB = sampler.halfExtents();
    spook::ref_ptr<spook::BoxT<S>> a = new spook::BoxT<S>(halfA.cast<S>()), b = new spook::BoxT<S>(halfB.cast<S>());
    const spook::TransformT<S> X_WA = sampler.first<S>();
    const spook::TransformT<S> X_WB = sampler.second<S>(X_WA, 1.4 * (halfA.norm() + halfB.norm()));
    const auto points = contactsOf<S>(*a, X_WA, *b, X_WB);
    REQUIRE(allFinite(points));

    const auto shapeA = fclBox(*a), shapeB = fclBox(*b);
    const FclContacts reference = fclContacts(shapeA, toFclTransform(X_WA), shapeB, toFclTransform(X_WB));
    // fcl::distance answers −1 for boxes that touch (on the lattice) although
    // fcl::collide found no contact: that is a signed distance of 0.
    const double signedDistance =
        reference.hit ? -reference.depth : std::max(0.0, fclSeparation(shapeA, toFclTransform(X_WA), shapeB, toFclTransform(X_WB)));
    if (std::abs(signedDistance) > 1e-6) {
      ++decided;
      if (reference.hit == !points.empty()) ++agreed;
    }
    if (!reference.hit || points.empty()) continue;
    ++intersecting;

    // The same geometry in double, for the overlap along a direction.
    const BoxPair pair{a->getHalfExtents().template cast<double>(), X_WA.linear().template cast<double>(),
                       X_WA.translation().template cast<double>(),  b->getHalfExtents().template cast<double>(),
                       X_WB.linear().template cast<double>(),       X_WB.translation().template cast<double>()};
    const SatAxis expected = pair.leastOverlap();
    double depth = reference.depth;
    V3 normal = reference.normal;
    // dBoxBox lets an edge axis replace the best so far, edge axes included,
    // only when 1.05 times its overlap is smaller, so among edge axes it may
    // keep one up to 5 % deeper than the least. spook takes the least edge
    // axis (then weighs it against the faces with the same 1.05): there the
    // exact axis of least overlap is the reference.
    if (expected.edge && reference.depth > expected.overlap + double(pick<S>(1e-7, 1e-6))) {
      ++quirks;
      CHECK(reference.depth <= 1.05 * expected.overlap + 1e-9);
      depth = expected.overlap;
      normal = expected.axis;
    }
    const auto& mine = deepest(points);
    const V3 n = mine.normal.template cast<double>().normalized();
    worstDepth = std::max(worstDepth, std::abs(double(mine.depth) - depth));
    // The overlap along spook's normal is that of the chosen axis, which
    // also holds where two axes tie and the normal is not unique (everywhere
    // on the lattice, so the angle is compared on random poses only).
    worstOverlap = std::max(worstOverlap, std::abs(pair.overlap(n) - expected.overlap));
    if (!sampler.lattice()) worstAngle = std::max(worstAngle, angleBetween(n, normal));
  }
  MESSAGE("box-box vs FCL (" << describe(sampler.lattice(), std::is_same_v<S, float>) << "): " << intersecting
                             << " intersecting, intersect/not agree in " << agreed << " of " << decided << ", "
                             << quirks << " with FCL on a deeper edge axis, worst depth error " << worstDepth
                             << " m, worst normal error " << worstAngle << " rad"
                             << std::string(sampler.lattice() ? " (not compared: axes tie on the lattice)" : "")
                             << ", worst axis-overlap error " << worstOverlap << " m");
  CHECK(intersecting * 10 > trials * 3);
  CHECK(intersecting * 10 < trials * 7);
  CHECK(agreed >= 0.999 * decided);
  CHECK(worstDepth <= double(pick<S>(1e-6, 1e-5)));
  CHECK(worstOverlap <= double(pick<S>(1e-6, 1e-5)));
  CHECK(worstAngle <= 1e-3);
}

// Box–capsule against the exact reference (depth, normal) and FCL
// (intersect or not).
template <class S>
void checkBoxCapsuleAgainstExact(PoseSampler& sampler) {
  int intersecting = 0, decided = 0, agreedFcl = 0, agreedExact = 0, normalsCompared = 0, fclOff = 0;
  double worstDepth = 0, worstAngle = 0, worstOverlap = 0, worstFclDepth = 0;
  const int trials = spook::test::sweep(10000, 800);
  for (int trial = 0; trial < trials; ++trial) {
    const V3 half = sampler.halfExtents();
    const double radius = sampler.length(0.05, 0.5);
    const double height = sampler.length(0.05, 1.55);
    spook::ref_ptr<spook::BoxT<S>> box = new spook::BoxT<S>(half.cast<S>());
    spook::ref_ptr<spook::CapsuleT<S>> capsule = new spook::CapsuleT<S>(S(radius), S(height));
    const spook::TransformT<S> X_WA = sampler.first<S>();
    const spook::TransformT<S> X_WB = sampler.second<S>(X_WA, 1.3 * (half.norm() + 0.5 * height + radius));
    const auto points = contactsOf<S>(*box, X_WA, *capsule, X_WB);
    REQUIRE(allFinite(points));

    // The exact reference, in the box frame, on the geometry as rounded to S.
    const Eigen::Matrix3d R_WA = X_WA.linear().template cast<double>();
    const V3 e = box->getHalfExtents().template cast<double>();
    const V3 c = R_WA.transpose() * (X_WB.translation() - X_WA.translation()).template cast<double>();
    const V3 u = (R_WA.transpose() * X_WB.linear().col(1).template cast<double>()).normalized();
    const double h = 0.5 * double(capsule->getHeight()), r = double(capsule->getRadius());
    const CapsuleBoxReference exact = exactCapsuleBox(e, c, u, h, r);

    const auto shapeA = fclBox(*box), shapeB = fclCapsule(*capsule);
    const FclContacts fcl = fclContacts(shapeA, toFclTransform(X_WA), shapeB, toFclCapsule(X_WB));
    if (std::abs(exact.signedDistance) > 1e-6) {
      ++decided;
      if (fcl.hit == (exact.signedDistance < 0)) ++agreedFcl;
      if (!points.empty() == (exact.signedDistance < 0)) ++agreedExact;
    }
    if (fcl.hit && exact.signedDistance < 0) {
      // FCL 0.7's generic GST_INDEP path stores −epa.depth as the depth
      // (gjk_solver_indep-inl.h, `S depth = -epa.depth;`), so only its
      // magnitude is compared, and only for information: its EPA also
      // overshoots the least overlap (by up to about 1 m here).
      const double fclError = std::abs(std::abs(fcl.depth) + exact.signedDistance);
      worstFclDepth = std::max(worstFclDepth, fclError);
      if (fclError > 1e-3) ++fclOff;
    }
    if (points.empty() || exact.signedDistance >= 0) continue;
    ++intersecting;
    const auto& mine = deepest(points);
    const V3 n = R_WA.transpose() * mine.normal.template cast<double>().normalized();
    worstDepth = std::max(worstDepth, std::abs(double(mine.depth) + exact.signedDistance));
    // Along spook's normal the projections overlap by the depth: the normal
    // is a direction of least overlap (also where that is not unique).
    worstOverlap = std::max(worstOverlap, std::abs(capsuleBoxOverlap(n, e, c, u, h, r) + exact.signedDistance));
    // The direction is unique unless two facets tie, or the segment touches
    // the box (then any direction in the normal cone of the touching feature
    // will do).
    const bool unique = exact.ambiguity > double(pick<S>(1e-9, 1e-4)) &&
                        (exact.segmentDistance == 0 || exact.segmentDistance > double(pick<S>(1e-9, 1e-4)));
    if (unique) {
      ++normalsCompared;
      worstAngle = std::max(worstAngle, angleBetween(n, exact.normal));
    }
  }
  MESSAGE("box-capsule (" << describe(sampler.lattice(), std::is_same_v<S, float>) << "): " << intersecting
                          << " intersecting; intersect/not agree with the exact reference in " << agreedExact
                          << " and with FCL in " << agreedFcl << " of " << decided << "; worst depth error "
                          << worstDepth << " m (FCL's GJK/EPA: " << worstFclDepth << " m, off by more than 1 mm in "
                          << fclOff << "), worst normal error " << worstAngle << " rad over " << normalsCompared
                          << ", worst overlap along the normal " << worstOverlap << " m");
  CHECK(intersecting * 10 > trials * 3);
  CHECK(intersecting * 10 < trials * 7);
  CHECK(agreedExact == decided);
  CHECK(agreedFcl >= 0.999 * decided);
  CHECK(worstDepth <= double(pick<S>(1e-6, 1e-5)));
  CHECK(worstOverlap <= double(pick<S>(1e-6, 1e-5)));
  CHECK(worstAngle <= 1e-3);
}

}  // namespace

TEST_CASE_TEMPLATE("box-box contacts agree with FCL's dBoxBox on random poses", S, float, double) {
  PoseSampler sampler(false, 20240611);
  checkBoxBoxAgainstFcl<S>(sampler);
}

TEST_CASE_TEMPLATE("box-box contacts agree with FCL's dBoxBox on lattice poses", S, float, double) {
  PoseSampler sampler(true, 4242);
  checkBoxBoxAgainstFcl<S>(sampler);
}

TEST_CASE_TEMPLATE("box-capsule contacts agree with an exact reference on random poses", S, float, double) {
  PoseSampler sampler(false, 7031);
  checkBoxCapsuleAgainstExact<S>(sampler);
}

TEST_CASE_TEMPLATE("box-capsule contacts agree with an exact reference on lattice poses", S, float, double) {
  PoseSampler sampler(true, 1357);
  checkBoxCapsuleAgainstExact<S>(sampler);
}

// ---- targeted cases --------------------------------------------------------

namespace {

template <class S>
spook::TransformT<S> at(double x, double y, double z, const Eigen::Matrix3d& R = Eigen::Matrix3d::Identity()) {
  spook::TransformT<S> X = spook::TransformT<S>::Identity();
  X.linear() = R.cast<S>();
  X.translation() = spook::Vec3T<S>(S(x), S(y), S(z));
  return X;
}

Eigen::Matrix3d turn(double angle, const V3& axis) { return Eigen::AngleAxisd(angle, axis).toRotationMatrix(); }

}  // namespace

TEST_CASE_TEMPLATE("a box resting flat on a larger box touches it at its 4 bottom corners", S, float, double) {
  const S tol = pick<S>(1e-12, 1e-6);
  spook::ref_ptr<spook::BoxT<S>> floor = new spook::BoxT<S>(spook::Vec3T<S>(2, 2, 0.5));
  spook::ref_ptr<spook::BoxT<S>> block = new spook::BoxT<S>(spook::Vec3T<S>(0.5, 0.3, 0.4));
  const auto points = contactsOf<S>(*floor, at<S>(0, 0, 0), *block, at<S>(0.7, -0.2, 0.5 + 0.4 - 0.01));
  MESSAGE("resting box: " << points.size() << " contacts");
  REQUIRE(points.size() == 4);
  for (const auto& p : points) {
    CHECK(std::abs(p.depth - S(0.01)) <= tol);
    CHECK((p.normal - spook::Vec3T<S>::UnitZ()).norm() <= tol);
    CHECK(std::abs(p.point.z() - S(0.495)) <= tol);  // midway between the two faces
    CHECK(std::abs(std::abs(p.point.x() - S(0.7)) - S(0.5)) <= tol);
    CHECK(std::abs(std::abs(p.point.y() + S(0.2)) - S(0.3)) <= tol);
  }
  // The other order: the same points, the normal from the block toward the floor.
  const auto reversed = contactsOf<S>(*block, at<S>(0.7, -0.2, 0.5 + 0.4 - 0.01), *floor, at<S>(0, 0, 0));
  REQUIRE(reversed.size() == 4);
  for (const auto& p : reversed) CHECK((p.normal + spook::Vec3T<S>::UnitZ()).norm() <= tol);
}

TEST_CASE_TEMPLATE("a box turned 45 degrees on an equal box touches along the octagon of their overlap", S, float,
                   double) {
  const S tol = pick<S>(1e-12, 1e-6);
  spook::ref_ptr<spook::BoxT<S>> lower = new spook::BoxT<S>(spook::Vec3T<S>(1, 1, 0.5));
  spook::ref_ptr<spook::BoxT<S>> upper = new spook::BoxT<S>(spook::Vec3T<S>(1, 1, 0.5));
  const auto points =
      contactsOf<S>(*lower, at<S>(0, 0, 0), *upper, at<S>(0, 0, 1 - 0.02, turn(std::numbers::pi / 4, V3::UnitZ())));
  MESSAGE("box turned 45 degrees: " << points.size() << " contacts");
  CHECK(points.size() >= 4);
  for (const auto& p : points) {
    CHECK(std::abs(p.depth - S(0.02)) <= tol);
    CHECK((p.normal - spook::Vec3T<S>::UnitZ()).norm() <= tol);
    // Every point lies on the boundary of the octagon |x|, |y| <= 1,
    // |x ± y| <= √2.
    const S x = std::abs(p.point.x()), y = std::abs(p.point.y());
    CHECK(std::max({x, y, (x + y) / std::numbers::sqrt2_v<S>}) >= S(1) - tol);
    CHECK(std::max({x, y, (x + y) / std::numbers::sqrt2_v<S>}) <= S(1) + tol);
  }
}

TEST_CASE_TEMPLATE("two boxes crossing edge on edge touch at one point", S, float, double) {
  const S tol = pick<S>(1e-12, 1e-6);
  spook::ref_ptr<spook::BoxT<S>> a = new spook::BoxT<S>(spook::Vec3T<S>(0.5, 0.5, 0.5));
  spook::ref_ptr<spook::BoxT<S>> b = new spook::BoxT<S>(spook::Vec3T<S>(0.5, 0.5, 0.5));
  // A's top edge runs along x at z = √2/2, B's bottom edge along y at z_B − √2/2.
  const double reach = std::numbers::sqrt2;
  const auto points = contactsOf<S>(*a, at<S>(0, 0, 0, turn(std::numbers::pi / 4, V3::UnitX())), *b,
                                    at<S>(0.1, -0.2, reach - 0.01, turn(std::numbers::pi / 4, V3::UnitY())));
  MESSAGE("edge on edge: " << points.size() << " contacts");
  REQUIRE(points.size() == 1);
  CHECK(std::abs(points[0].depth - S(0.01)) <= tol);
  CHECK((points[0].normal - spook::Vec3T<S>::UnitZ()).norm() <= tol);
  CHECK((points[0].point - spook::Vec3T<S>(S(0.1), S(0), S(reach / 2 - 0.005))).norm() <= tol);
}

TEST_CASE_TEMPLATE("coincident and exactly touching boxes give finite contacts", S, float, double) {
  spook::ref_ptr<spook::BoxT<S>> a = new spook::BoxT<S>(spook::Vec3T<S>(0.5, 0.7, 0.9));
  const Eigen::Matrix3d R = turn(0.3, V3(1, 2, 3).normalized());
  const auto coincident = contactsOf<S>(*a, at<S>(1, 2, 3, R), *a, at<S>(1, 2, 3, R));
  MESSAGE("coincident boxes: " << coincident.size() << " contacts");
  CHECK(!coincident.empty());
  CHECK(allFinite(coincident));
  for (const auto& p : coincident) CHECK(std::abs(p.depth - S(1)) <= pick<S>(1e-12, 1e-6));  // 2 × least half extent

  const auto touching = contactsOf<S>(*a, at<S>(0, 0, 0), *a, at<S>(0, 0, 1.8));
  MESSAGE("touching boxes: " << touching.size() << " contacts");
  CHECK(!touching.empty());
  CHECK(allFinite(touching));
  for (const auto& p : touching) CHECK(p.depth <= pick<S>(1e-12, 1e-6));

  // Parallel edges (one box shifted diagonally) and an identical orientation.
  const auto shifted = contactsOf<S>(*a, at<S>(0, 0, 0), *a, at<S>(0.99, 1.39, 1.79));
  CHECK(!shifted.empty());
  CHECK(allFinite(shifted));
}

// A unit cube resting on another settles ~1e-9 m deep under 1 kg: below
// float's resolution of its coordinates (6e-8 m at 1 m), and a tilt of a
// micro-radian lifts two of its corners by more than that. Within the
// touching gap (kTouchingGap of the smaller box's size, 8.7e-6 m here) the
// corners still touch (depth 0), and a 1.05 bias cannot hand the contact to
// an edge axis whose overlap differs from the face's only by round-off:
// losing corners made a float pyramid of bricks rock and collapse.
TEST_CASE_TEMPLATE("a cube tilted by round-off on another keeps its four corners", S, float, double) {
  spook::ref_ptr<spook::BoxT<S>> cube = new spook::BoxT<S>(spook::Vec3T<S>::Constant(S(0.5)));
  for (const double tilt : {0.0, 1e-6, 5e-6})
    for (const double lift : {-1e-9, 0.0, 1e-7, 2e-6}) {
      CAPTURE(tilt);
      CAPTURE(lift);
      const auto points =
          contactsOf<S>(*cube, at<S>(0, 0, 0.5), *cube, at<S>(0.2, 0, 1.5 + lift, turn(tilt, V3(1, 1, 0).normalized())));
      CHECK(points.size() == 4);
      for (const auto& p : points) {
        CHECK((p.normal - spook::Vec3T<S>::UnitZ()).norm() <= pick<S>(1e-5, 1e-5));
        CHECK(p.depth <= S(tilt + std::max(0.0, -lift)) + pick<S>(1e-12, 1e-6));
      }
    }
  // Beyond the gap they are apart.
  CHECK(contactsOf<S>(*cube, at<S>(0, 0, 0.5), *cube, at<S>(0.2, 0, 1.5 + 1e-4)).empty());
}

TEST_CASE_TEMPLATE("a cube tilted by round-off on a plane keeps its four corners", S, float, double) {
  spook::ref_ptr<spook::BoxT<S>> cube = new spook::BoxT<S>(spook::Vec3T<S>::Constant(S(0.5)));
  spook::ref_ptr<spook::PlaneT<S>> ground = new spook::PlaneT<S>(spook::Vec3T<S>::UnitZ());
  for (const double tilt : {0.0, 1e-6, 5e-6})
    for (const double lift : {-1e-9, 0.0, 1e-7, 2e-6}) {
      CAPTURE(tilt);
      CAPTURE(lift);
      const auto points =
          contactsOf<S>(*cube, at<S>(3, -2, 0.5 + lift, turn(tilt, V3(1, 1, 0).normalized())), *ground, at<S>(0, 0, 0));
      CHECK(points.size() == 4);
      for (const auto& p : points) CHECK(p.depth <= S(tilt + std::max(0.0, -lift)) + pick<S>(1e-12, 1e-6));
    }
  CHECK(contactsOf<S>(*cube, at<S>(3, -2, 0.5 + 1e-4), *ground, at<S>(0, 0, 0)).empty());
}

TEST_CASE_TEMPLATE("a capsule lying flat on a box touches it at both ends", S, float, double) {
  const S tol = pick<S>(1e-12, 1e-6);
  spook::ref_ptr<spook::BoxT<S>> box = new spook::BoxT<S>(spook::Vec3T<S>(1, 1, 0.5));
  spook::ref_ptr<spook::CapsuleT<S>> capsule = new spook::CapsuleT<S>(S(0.1), S(1));
  const Eigen::Matrix3d alongX = turn(-std::numbers::pi / 2, V3::UnitZ());  // capsule axis y → x
  const auto points = contactsOf<S>(*box, at<S>(0, 0, 0), *capsule, at<S>(0.2, 0.3, 0.5 + 0.1 - 0.01, alongX));
  MESSAGE("capsule lying on a box: " << points.size() << " contacts");
  REQUIRE(points.size() == 2);
  for (const auto& p : points) {
    CHECK(std::abs(p.depth - S(0.01)) <= tol);
    CHECK((p.normal - spook::Vec3T<S>::UnitZ()).norm() <= tol);
    CHECK(std::abs(std::abs(p.point.x() - S(0.2)) - S(0.5)) <= tol);
    CHECK(std::abs(p.point.z() - S(0.495)) <= tol);
  }

  // Overhanging the edge: the segment is clipped at the face's side.
  const auto overhanging = contactsOf<S>(*box, at<S>(0, 0, 0), *capsule, at<S>(0.8, 0, 0.5 + 0.1 - 0.01, alongX));
  REQUIRE(overhanging.size() == 2);
  const S xMax = std::max(overhanging[0].point.x(), overhanging[1].point.x());
  const S xMin = std::min(overhanging[0].point.x(), overhanging[1].point.x());
  CHECK(std::abs(xMax - S(1)) <= tol);
  CHECK(std::abs(xMin - S(0.3)) <= tol);

  // Tilted so that only the lower end is within the radius: one contact.
  const auto tilted =
      contactsOf<S>(*box, at<S>(0, 0, 0), *capsule,
                    at<S>(0, 0, 0.5 + 0.1 - 0.01 + 0.5 * std::sin(0.3), turn(0.3, V3::UnitY()) * alongX));
  REQUIRE(tilted.size() == 1);
  CHECK(std::abs(tilted[0].depth - S(0.01)) <= pick<S>(1e-12, 1e-6));

  // Standing upright on the face, and sunk into it: one contact each.
  const Eigen::Matrix3d upright = turn(std::numbers::pi / 2, V3::UnitX());  // capsule axis y → z
  const auto standing = contactsOf<S>(*box, at<S>(0, 0, 0), *capsule, at<S>(0.1, 0.1, 0.5 + 0.6 - 0.01, upright));
  REQUIRE(standing.size() == 1);
  CHECK(std::abs(standing[0].depth - S(0.01)) <= tol);
  const auto sunk = contactsOf<S>(*box, at<S>(0, 0, 0), *capsule, at<S>(0.1, 0.1, 0.5 + 0.6 - 0.3, upright));
  REQUIRE(sunk.size() == 1);
  CHECK(std::abs(sunk[0].depth - S(0.3)) <= tol);
  CHECK((sunk[0].normal - spook::Vec3T<S>::UnitZ()).norm() <= tol);

  // Reversed order: the normal points from the capsule toward the box.
  const auto reversed = contactsOf<S>(*capsule, at<S>(0.2, 0.3, 0.5 + 0.1 - 0.01, alongX), *box, at<S>(0, 0, 0));
  REQUIRE(reversed.size() == 2);
  for (const auto& p : reversed) CHECK((p.normal + spook::Vec3T<S>::UnitZ()).norm() <= tol);
}
