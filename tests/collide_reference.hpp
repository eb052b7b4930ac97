#pragma once

// Differential testing of spook's colliders against FCL 0.7 (tests only).
//
// FCL's conventions, checked on two unit spheres at (0,0,0) and (1.5,0,0):
// collide(o1, o2) reports normal (1, 0, 0), depth 0.5, position (0.75, 0, 0):
// the normal points from o1 toward o2 and moving o2 by depth along it
// separates the pair, as spook's ContactPoint; a half-space first and a
// sphere above it give the half-space's outward normal. So FCL's normal is
// compared with spook's without a sign change.
//
// FCL is exact where GJKSolver_indep has a closed form: sphere–sphere,
// sphere–box, sphere–capsule, sphere–cylinder, and every shape against a
// half-space. Other pairs (capsule–capsule, cylinder or box pairs, convex
// meshes) go through FCL's GJK/EPA, good to about 1e-6..1e-3; there the
// tests use an independent exact computation, named at each use.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <limits>
#include <memory>
#include <numbers>
#include <random>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <doctest/doctest.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/halfspace.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>
#include <fcl/narrowphase/distance.h>

#include <spook/collide/collider.hpp>
#include <spook/collide/contact_sink.hpp>
#include <spook/collide/shapes/box.hpp>
#include <spook/collide/shapes/capsule.hpp>
#include <spook/collide/shapes/convex.hpp>
#include <spook/collide/shapes/cylinder.hpp>
#include <spook/collide/shapes/line.hpp>
#include <spook/collide/shapes/plane.hpp>
#include <spook/collide/shapes/sphere.hpp>

namespace spook::test {

using Vec3d = spook::Vec3<double>;
using Transformd = spook::Transform<double>;

// ---------------------------------------------------------------------------
// Random poses and sizes, deterministic for a seed. Lengths are rounded to
// float so that the float and the double runs collide the very same shapes.

class RandomPoses {
 public:
  explicit RandomPoses(std::uint64_t seed) : rng_(seed) {}

  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }
  /// A length representable in float (m).
  double length(double lo, double hi) { return double(float(uniform(lo, hi))); }
  /// A direction, uniform on the unit sphere.
  Vec3d unit() {
    std::normal_distribution<double> g(0.0, 1.0);
    for (;;) {
      const Vec3d v(g(rng_), g(rng_), g(rng_));
      if (v.norm() > 1e-6) return v.normalized();
    }
  }
  /// A rotation, uniform over SO(3) (a normalized Gaussian quaternion).
  Eigen::Matrix3d rotation() {
    std::normal_distribution<double> g(0.0, 1.0);
    for (;;) {
      Eigen::Quaterniond q(g(rng_), g(rng_), g(rng_), g(rng_));
      if (q.norm() > 1e-6) return q.normalized().toRotationMatrix();
    }
  }
  /// A random rotation at a random point of the cube [−spread, spread]³ (m).
  Transformd pose(double spread) {
    Transformd X = Transformd::Identity();
    X.linear() = rotation();
    X.translation() = Vec3d(uniform(-spread, spread), uniform(-spread, spread), uniform(-spread, spread));
    return X;
  }
  /// A random rotation at distance uniform in [0, reach] from `from`, in a random direction.
  Transformd poseNear(const Vec3d& from, double reach) {
    Transformd X = Transformd::Identity();
    X.linear() = rotation();
    X.translation() = from + uniform(0.0, reach) * unit();
    return X;
  }

 private:
  std::mt19937_64 rng_;
};

// ---------------------------------------------------------------------------
// Shapes in another scalar (sizes are float-exact, so nothing changes).

template <Scalar S>
ref_ptr<SphereT<S>> castShape(const SphereT<double>& s) {
  return new SphereT<S>(S(s.getRadius()));
}
template <Scalar S>
ref_ptr<BoxT<S>> castShape(const BoxT<double>& s) {
  return new BoxT<S>(s.getHalfExtents().cast<S>());
}
template <Scalar S>
ref_ptr<CapsuleT<S>> castShape(const CapsuleT<double>& s) {
  return new CapsuleT<S>(S(s.getRadius()), S(s.getHeight()));
}
template <Scalar S>
ref_ptr<CylinderT<S>> castShape(const CylinderT<double>& s) {
  return new CylinderT<S>(S(s.getRadius()), S(s.getHeight()));
}
template <Scalar S>
ref_ptr<PlaneT<S>> castShape(const PlaneT<double>& s) {
  return new PlaneT<S>(s.getNormal().cast<S>(), s.getPoint().cast<S>());
}
template <Scalar S>
ref_ptr<LineT<S>> castShape(const LineT<double>& s) {
  return new LineT<S>(s.getFirstPoint().cast<S>(), s.getSecondPoint().cast<S>());
}
template <Scalar S>
ref_ptr<ConvexT<S>> castShape(const ConvexT<double>& s) {
  std::vector<Vec3<S>> points;
  for (const Vec3d& v : s.getVertices()) points.push_back(v.cast<S>());
  return new ConvexT<S>(points);
}

// ---------------------------------------------------------------------------
// FCL adapters: a spook shape at X_WS (shape → world) as an FCL object.

inline fcl::Transform3d fclPose(const Transformd& X) {
  fcl::Transform3d T = fcl::Transform3d::Identity();
  T.linear() = X.linear();
  T.translation() = X.translation();
  return T;
}
/// Capsules and cylinders have their axis along y in spook and along z in
/// FCL: X_WF = X_WS · R_SF with R_SF = Rx(−90°), which takes FCL's z onto
/// spook's y (it is the inverse of the +90° turn about x taking y to z).
inline fcl::Transform3d fclAxisPose(const Transformd& X) {
  return fclPose(X) * Eigen::AngleAxisd(-std::numbers::pi / 2, Eigen::Vector3d::UnitX());
}

using FclObject = std::unique_ptr<fcl::CollisionObjectd>;

inline FclObject toFcl(const SphereT<double>& s, const Transformd& X) {
  return std::make_unique<fcl::CollisionObjectd>(std::make_shared<fcl::Sphered>(s.getRadius()), fclPose(X));
}
/// fcl::Box takes full side lengths: twice spook's half extents.
inline FclObject toFcl(const BoxT<double>& s, const Transformd& X) {
  const Vec3d side = 2.0 * s.getHalfExtents();
  return std::make_unique<fcl::CollisionObjectd>(std::make_shared<fcl::Boxd>(side.x(), side.y(), side.z()), fclPose(X));
}
/// fcl::Capsule(radius, lz): lz is the cylindrical part, spook's height.
inline FclObject toFcl(const CapsuleT<double>& s, const Transformd& X) {
  return std::make_unique<fcl::CollisionObjectd>(std::make_shared<fcl::Capsuled>(s.getRadius(), s.getHeight()),
                                                 fclAxisPose(X));
}
/// fcl::Cylinder(radius, lz): lz is the full height, as spook's.
inline FclObject toFcl(const CylinderT<double>& s, const Transformd& X) {
  return std::make_unique<fcl::CollisionObjectd>(std::make_shared<fcl::Cylinderd>(s.getRadius(), s.getHeight()),
                                                 fclAxisPose(X));
}
/// fcl::Halfspace(n, d) is the solid n·x <= d, spook's plane with d = n·point.
inline FclObject toFcl(const PlaneT<double>& s, const Transformd& X) {
  return std::make_unique<fcl::CollisionObjectd>(std::make_shared<fcl::Halfspaced>(s.getNormal(), s.getDistance()),
                                                 fclPose(X));
}
/// FCL has no segment; a capsule of radius 0 along it is one, and FCL's
/// closed forms for capsules against spheres and half-spaces hold for it.
inline FclObject toFcl(const LineT<double>& s, const Transformd& X) {
  const Vec3d p = s.getFirstPoint(), q = s.getSecondPoint();
  Transformd X_SL = Transformd::Identity();
  X_SL.translation() = 0.5 * (p + q);
  X_SL.linear() = Eigen::Quaterniond::FromTwoVectors(Vec3d::UnitZ(), q - p).toRotationMatrix();
  return std::make_unique<fcl::CollisionObjectd>(std::make_shared<fcl::Capsuled>(0.0, (q - p).norm()),
                                                 fclPose(X * X_SL));
}
/// fcl::Convex takes the polygon faces as [count, i0, i1, ..., count, ...].
inline FclObject toFcl(const ConvexT<double>& s, const Transformd& X) {
  auto vertices = std::make_shared<std::vector<Vec3d>>(s.getVertices());
  auto faces = std::make_shared<std::vector<int>>();
  for (const auto& face : s.getFaces()) {
    faces->push_back(int(face.vertices.size()));
    for (int v : face.vertices) faces->push_back(v);
  }
  return std::make_unique<fcl::CollisionObjectd>(
      std::make_shared<fcl::Convexd>(vertices, int(s.getFaces().size()), faces), fclPose(X));
}

// ---------------------------------------------------------------------------
// Reference answers.

/// A reference answer for one placed pair: whether they intersect, the
/// penetration depth (m) and the normal from the first toward the second
/// when they do, and a signed distance (m; −depth when they intersect) that
/// tells which cases are too close to contact to decide.
struct Reference {
  bool intersect = false;
  double depth = 0.0;
  Vec3d normal = Vec3d::UnitZ();
  double signedDistance = 0.0;
};

/// FCL's collide with contacts (num_max_contacts large, GST_INDEP): the
/// deepest contact's depth and normal.
inline Reference fclCollide(const fcl::CollisionObjectd& a, const fcl::CollisionObjectd& b) {
  fcl::CollisionRequestd request(1000, true);
  request.gjk_solver_type = fcl::GST_INDEP;
  fcl::CollisionResultd result;
  fcl::collide(&a, &b, request, result);
  Reference reference;
  reference.intersect = result.isCollision();
  for (std::size_t i = 0; i < result.numContacts(); ++i) {
    const auto& contact = result.getContact(i);
    if (i == 0 || contact.penetration_depth > reference.depth) {
      reference.depth = contact.penetration_depth;
      reference.normal = contact.normal;
    }
  }
  reference.signedDistance = -reference.depth;
  return reference;
}

/// FCL's distance (GST_INDEP) of a non-intersecting pair (m).
inline double fclDistance(const fcl::CollisionObjectd& a, const fcl::CollisionObjectd& b) {
  fcl::DistanceRequestd request;
  request.gjk_solver_type = fcl::GST_INDEP;
  fcl::DistanceResultd result;
  fcl::distance(&a, &b, request, result);
  return result.min_distance;
}

/// FCL's collide, with fcl::distance for the pairs it finds apart.
template <class A, class B>
Reference fclReference(const A& a, const Transformd& X_WA, const B& b, const Transformd& X_WB) {
  const FclObject oa = toFcl(a, X_WA), ob = toFcl(b, X_WB);
  Reference reference = fclCollide(*oa, *ob);
  if (!reference.intersect) reference.signedDistance = fclDistance(*oa, *ob);
  return reference;
}

/// The support point of a convex shape placed at X (world, m).
template <class Shape>
Vec3d supportWorld(const Shape& shape, const Transformd& X, const Vec3d& n) {
  return X * Vec3d(shape.support(X.linear().transpose() * n));
}

/// The overlap of the projections of a and b on the unit direction n (from
/// a toward b): h_a(n) + h_b(−n). The penetration depth is its minimum over
/// n, so a normal n with overlap(n) equal to the depth is as good as any.
template <class A, class B>
double projectionOverlap(const A& a, const Transformd& X_WA, const B& b, const Transformd& X_WB, const Vec3d& n) {
  return n.dot(supportWorld(a, X_WA, n) - supportWorld(b, X_WB, -n));
}

/// Exact penetration of two convex polytopes given by their world corners,
/// by brute force. The Minkowski difference M = {a − b} is the hull of all
/// corner differences; the pair intersects when the origin is in M, and
/// the depth is the origin's distance to M's boundary, the smallest offset
/// o = ν·x of M's facets (outward unit ν), reached by moving b along ν. The
/// facets are all planes through three difference points with every point
/// on one side. Apart, −(the smallest offset) is a lower bound of the
/// distance, enough to set aside near-touching cases.
inline Reference polytopePenetration(const std::vector<Vec3d>& cornersA, const std::vector<Vec3d>& cornersB) {
  std::vector<Vec3d> m;
  for (const Vec3d& a : cornersA)
    for (const Vec3d& b : cornersB) m.push_back(a - b);
  double scale = 0.0;
  for (const Vec3d& x : m) scale = std::max(scale, x.norm());
  const double flat = 1e-9 * scale * scale, side = 1e-12 * scale;
  const std::size_t count = m.size();
  Reference reference;
  double smallest = 0.0;
  bool found = false;
  for (std::size_t i = 0; i < count; ++i)
    for (std::size_t j = i + 1; j < count; ++j)
      for (std::size_t k = j + 1; k < count; ++k) {
        Vec3d nu = (m[j] - m[i]).cross(m[k] - m[i]);
        if (nu.norm() <= flat) continue;
        nu.normalize();
        const double offset = nu.dot(m[i]);
        bool below = true, above = true;
        for (const Vec3d& x : m) {
          const double h = nu.dot(x) - offset;
          below = below && h <= side;
          above = above && h >= -side;
        }
        if (!below && !above) continue;
        const double o = below ? offset : -offset;
        if (!found || o < smallest) {
          smallest = o;
          reference.normal = below ? nu : Vec3d(-nu);
          found = true;
        }
      }
  reference.intersect = smallest >= 0.0;
  reference.depth = smallest;
  reference.signedDistance = -smallest;
  return reference;
}

/// Exact penetration (or, apart, minus the distance) of two convex shapes
/// whose Minkowski difference has its facet normals among `axes` (world):
/// min over ±axes of the projection overlap, the separating axis theorem.
/// For polytopes the axes are the face normals of both and the cross
/// products of their edges; extra axes only add upper bounds.
template <class A, class B>
Reference axesMinimum(const A& a, const Transformd& X_WA, const B& b, const Transformd& X_WB,
                      const std::vector<Vec3d>& axes) {
  Reference reference;
  bool first = true;
  for (const Vec3d& axis : axes) {
    if (!(axis.norm() > 1e-9)) continue;
    for (const double sign : {1.0, -1.0}) {
      const Vec3d n = sign * axis.normalized();
      const double f = projectionOverlap(a, X_WA, b, X_WB, n);
      if (first || f < reference.depth) {
        reference.depth = f;
        reference.normal = n;
        first = false;
      }
    }
  }
  reference.intersect = reference.depth >= 0.0;
  reference.signedDistance = -reference.depth;
  return reference;
}

/// The penetration depth of two convex shapes as the minimum over unit n of
/// the projection overlap f(n) = h_a(n) + h_b(−n) (minus the distance when
/// apart), found by brute force: f on 2,000 directions spread evenly over
/// the sphere (a Fibonacci lattice, ~0.08 rad apart), then Nelder–Mead from
/// the best five of them (at least 0.15 rad apart), in coordinates on the tangent plane, restarted
/// with ever smaller simplices until they stop improving. It shares nothing
/// with libccd or FCL; on pairs with closed forms it matches them to ~1e-10.
template <class A, class B>
Reference overlapMinimum(const A& a, const Transformd& X_WA, const B& b, const Transformd& X_WB) {
  const auto f = [&](const Vec3d& n) { return projectionOverlap(a, X_WA, b, X_WB, n); };
  constexpr int kLattice = 2000, kSeeds = 5;
  std::vector<std::pair<double, Vec3d>> samples;
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < kLattice; ++i) {
    const double z = 1.0 - 2.0 * (i + 0.5) / kLattice, rho = std::sqrt(1.0 - z * z), phi = golden * i;
    const Vec3d n(rho * std::cos(phi), rho * std::sin(phi), z);
    samples.emplace_back(f(n), n);
  }
  std::sort(samples.begin(), samples.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<Vec3d> seeds;
  for (const auto& [value, n] : samples) {
    bool distinct = true;
    for (const Vec3d& seed : seeds) distinct = distinct && seed.dot(n) < std::cos(0.15);
    if (distinct) seeds.push_back(n);
    if (int(seeds.size()) == kSeeds) break;
  }
  Reference reference;
  reference.depth = samples.front().first;
  reference.normal = samples.front().second;
  for (const Vec3d& seed : seeds) {
    Vec3d center = seed;
    double best = f(seed);
    int restarts = 0;
    for (double size = 0.1; size > 1e-12 && restarts < 80; ++restarts) {
      // Nelder–Mead on g(u, v) = f(normalize(center + u e1 + v e2)).
      const Vec3d e1 = center.unitOrthogonal(), e2 = center.cross(e1);
      const auto at = [&](const Eigen::Vector2d& x) { return Vec3d((center + x.x() * e1 + x.y() * e2).normalized()); };
      std::array<Eigen::Vector2d, 3> x = {Eigen::Vector2d(0, 0), Eigen::Vector2d(size, 0), Eigen::Vector2d(0, size)};
      std::array<double, 3> g = {best, f(at(x[1])), f(at(x[2]))};
      for (int iteration = 0; iteration < 200; ++iteration) {
        std::array<int, 3> order = {0, 1, 2};
        std::sort(order.begin(), order.end(), [&](int i, int j) { return g[i] < g[j]; });
        const int lo = order[0], mid = order[1], hi = order[2];
        if ((x[hi] - x[lo]).norm() + (x[mid] - x[lo]).norm() < 1e-13) break;
        const Eigen::Vector2d centroid = 0.5 * (x[lo] + x[mid]);
        const Eigen::Vector2d reflected = centroid + (centroid - x[hi]);
        const double gr = f(at(reflected));
        if (gr < g[lo]) {
          const Eigen::Vector2d expanded = centroid + 2.0 * (centroid - x[hi]);
          const double ge = f(at(expanded));
          x[hi] = ge < gr ? expanded : reflected;
          g[hi] = std::min(ge, gr);
        } else if (gr < g[mid]) {
          x[hi] = reflected;
          g[hi] = gr;
        } else {
          const Eigen::Vector2d contracted = centroid + 0.5 * (x[hi] - centroid);
          const double gc = f(at(contracted));
          if (gc < g[hi]) {
            x[hi] = contracted;
            g[hi] = gc;
          } else {
            for (const int i : {mid, hi}) {
              x[i] = x[lo] + 0.5 * (x[i] - x[lo]);
              g[i] = f(at(x[i]));
            }
          }
        }
      }
      const int lo = int(std::min_element(g.begin(), g.end()) - g.begin());
      const bool improved = g[lo] < best - 1e-15;
      center = at(x[lo]);
      best = std::min(best, g[lo]);
      size *= improved ? 0.5 : 0.1;
    }
    if (best < reference.depth) {
      reference.depth = best;
      reference.normal = center;
    }
  }
  reference.intersect = reference.depth >= 0.0;
  reference.signedDistance = -reference.depth;
  return reference;
}

/// Exact penetration of a convex hull (world corners and outward faces from
/// its triangles) and a sphere: a center c outside the hull at distance d
/// from it (the nearest of the triangles, Ericson's closest point on a
/// triangle) gives depth r − d along (c − q)/d; a center inside pushes out
/// through the nearest face plane, depth r + (offset − n·c).
inline Reference convexSphereReference(const ConvexT<double>& a, const Transformd& X_WA, const SphereT<double>& b,
                                       const Transformd& X_WB) {
  const Vec3d c = X_WA.inverse(Eigen::Isometry) * X_WB.translation();
  const auto& v = a.getVertices();
  const double r = b.getRadius();
  bool inside = true;
  double nearestFace = 1e300;
  Vec3d faceNormal = Vec3d::UnitZ();
  for (const auto& face : a.getFaces()) {
    const double gap = face.offset - face.normal.dot(c);
    inside = inside && gap >= 0.0;
    if (gap < nearestFace) {
      nearestFace = gap;
      faceNormal = face.normal;
    }
  }
  Reference reference;
  if (inside) {
    reference.depth = r + nearestFace;
    reference.normal = X_WA.linear() * faceNormal;
  } else {
    double nearest = 1e300;
    Vec3d q = Vec3d::Zero();
    for (const auto& t : a.getTriangles()) {
      // Ericson, Real-Time Collision Detection, §5.1.5.
      const Vec3d &p0 = v[std::size_t(t[0])], &p1 = v[std::size_t(t[1])], &p2 = v[std::size_t(t[2])];
      const Vec3d ab = p1 - p0, ac = p2 - p0, ap = c - p0;
      const double d1 = ab.dot(ap), d2 = ac.dot(ap);
      Vec3d x;
      if (d1 <= 0 && d2 <= 0) {
        x = p0;
      } else {
        const Vec3d bp = c - p1;
        const double d3 = ab.dot(bp), d4 = ac.dot(bp);
        const Vec3d cp = c - p2;
        const double d5 = ab.dot(cp), d6 = ac.dot(cp);
        const double vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
        if (d3 >= 0 && d4 <= d3) {
          x = p1;
        } else if (vc <= 0 && d1 >= 0 && d3 <= 0) {
          x = p0 + d1 / (d1 - d3) * ab;
        } else if (d6 >= 0 && d5 <= d6) {
          x = p2;
        } else if (vb <= 0 && d2 >= 0 && d6 <= 0) {
          x = p0 + d2 / (d2 - d6) * ac;
        } else if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
          x = p1 + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (p2 - p1);
        } else {
          const double denominator = 1.0 / (va + vb + vc);
          x = p0 + ab * (vb * denominator) + ac * (vc * denominator);
        }
      }
      if ((c - x).norm() < nearest) {
        nearest = (c - x).norm();
        q = x;
      }
    }
    reference.depth = r - nearest;
    reference.normal = X_WA.linear() * ((c - q) / nearest);
  }
  reference.intersect = reference.depth >= 0.0;
  reference.signedDistance = -reference.depth;
  return reference;
}

/// World corners of a box placed at X.
inline std::vector<Vec3d> boxCorners(const BoxT<double>& box, const Transformd& X) {
  std::vector<Vec3d> corners;
  for (int c = 0; c < 8; ++c)
    corners.push_back(X * Vec3d(box.getHalfExtents().cwiseProduct(
                              Vec3d((c & 1) ? 1.0 : -1.0, (c & 2) ? 1.0 : -1.0, (c & 4) ? 1.0 : -1.0))));
  return corners;
}

// ---------------------------------------------------------------------------
// The differential harness.

/// A random case: two shapes (double, float-exact sizes) and their poses.
template <class A, class B>
struct PairCase {
  ref_ptr<A> a;
  ref_ptr<B> b;
  Transformd X_WA = Transformd::Identity();
  Transformd X_WB = Transformd::Identity();
};

/// What a differential run measured.
struct Agreement {
  int cases = 0;
  int intersecting = 0;       // by the reference
  int decided = 0;            // cases with |signed distance| > 1e-6
  int disagreements = 0;      // decided cases where spook and the reference differ on intersecting
  int compared = 0;           // cases both find intersecting
  int equivalentNormals = 0;  // normals off by more than kAngle that separate as well (ties, flat minima)
  int wrongNormals = 0;       // normals off by more than kAngle that do not
  int nonUnit = 0;            // contacts whose normal is not unit length, or whose depth is negative
  int maxContacts = 0;
  int deep = 0;                        // compared cases deeper than the comparison limit, measured apart
  double worstDeepDepth = 0.0;         // m, over those
  double worstDepth = 0.0;             // m
  double worstAngle = 0.0;             // rad, over all compared cases
  double worstStrictAngle = 0.0;       // rad, over cases whose reference minimum is not flat or tied
  double worstEquivalentExcess = 0.0;  // m, overlap along spook's normal above the reference depth, at most

  static constexpr double kDecided = 1e-6;  // m
  static constexpr double kAngle = 1e-3;    // rad
};

template <class S>
const char* scalarName() {
  return std::is_same_v<S, float> ? "float" : "double";
}

/// Runs `count` random cases of the pair (A, B) through spook's collider in
/// scalar S (shapes and poses rounded to S) and through `reference` (in
/// double, on the rounded poses). `overlap(a, X_WA, b, X_WB, n)`, when
/// given, is the projection overlap along n; a spook normal more than
/// kAngle off the reference's still counts as equivalent when its overlap
/// exceeds the reference depth by at most `depthTolerance` (two faces at
/// the same distance, or a minimum too flat for S to place). Cases deeper
/// than `compareUpTo` (m) are measured apart and not judged.
template <class S, class A, class B, class Sample, class Run, class Ref>
Agreement differential(
    std::uint64_t seed, int count, Sample&& sample, Run&& run, Ref&& reference, double depthTolerance,
    double compareUpTo,
    const std::function<double(const A&, const Transformd&, const B&, const Transformd&, const Vec3d&)>& overlap = {}) {
  RandomPoses random(seed);
  Agreement agreement;
  std::vector<ContactPointT<S>> points;
  for (int k = 0; k < count; ++k) {
    const PairCase<A, B> c = sample(random);
    const Transform<S> X_WA = c.X_WA.template cast<S>(), X_WB = c.X_WB.template cast<S>();
    const Transformd XA = X_WA.template cast<double>(), XB = X_WB.template cast<double>();
    points.clear();
    ContactSinkT<S> sink(points);
    run(*castShape<S>(*c.a), X_WA, *castShape<S>(*c.b), X_WB, sink);
    const Reference ref = reference(*c.a, XA, *c.b, XB);

    ++agreement.cases;
    agreement.intersecting += ref.intersect ? 1 : 0;
    agreement.maxContacts = std::max(agreement.maxContacts, int(points.size()));
    const bool found = !points.empty();
    if (std::abs(ref.signedDistance) > Agreement::kDecided) {
      ++agreement.decided;
      if (found != ref.intersect) ++agreement.disagreements;
    }
    double depth = -1.0;
    Vec3d normal = Vec3d::Zero();
    for (const auto& p : points) {
      const Vec3d n = p.normal.template cast<double>();
      if (!(std::abs(n.norm() - 1.0) <= 1e-5 && p.depth >= S(0) && p.point.allFinite())) ++agreement.nonUnit;
      if (double(p.depth) > depth) {
        depth = double(p.depth);
        normal = n.normalized();
      }
    }
    if (!(found && ref.intersect)) continue;
    if (ref.depth > compareUpTo) {
      ++agreement.deep;
      agreement.worstDeepDepth = std::max(agreement.worstDeepDepth, std::abs(depth - ref.depth));
      continue;
    }
    ++agreement.compared;
    agreement.worstDepth = std::max(agreement.worstDepth, std::abs(depth - ref.depth));
    const double angle = std::atan2(normal.cross(ref.normal).norm(), normal.dot(ref.normal));
    agreement.worstAngle = std::max(agreement.worstAngle, angle);
    if (angle <= Agreement::kAngle) {
      agreement.worstStrictAngle = std::max(agreement.worstStrictAngle, angle);
      continue;
    }
    const double excess = overlap ? overlap(*c.a, XA, *c.b, XB, normal) - ref.depth : 1e300;
    if (excess <= depthTolerance) {
      ++agreement.equivalentNormals;
      agreement.worstEquivalentExcess = std::max(agreement.worstEquivalentExcess, excess);
    } else {
      ++agreement.wrongNormals;
      agreement.worstStrictAngle = std::max(agreement.worstStrictAngle, angle);
    }
  }
  return agreement;
}

/// One line for the log.
template <class S>
std::string describe(const std::string& pair, const Agreement& a) {
  char deepText[128] = "";
  if (a.deep > 0)
    std::snprintf(deepText, sizeof deepText, "; %d deeper cases apart, worst depth error %.3g m", a.deep,
                  a.worstDeepDepth);
  char buffer[640];
  std::snprintf(buffer, sizeof buffer,
                "%s <%s>: %d cases, %d intersecting, %d/%d decided cases disagree; worst depth error %.3g m; "
                "worst normal error %.3g rad (%.3g rad outside %d equivalent normals, those within %.3g m); "
                "up to %d contacts%s",
                pair.c_str(), scalarName<S>(), a.cases, a.intersecting, a.disagreements, a.decided, a.worstDepth,
                a.worstAngle, a.worstStrictAngle, a.equivalentNormals, a.worstEquivalentExcess, a.maxContacts,
                deepText);
  return buffer;
}

/// Depth tolerance of the differential tests: 1e-6 m in double; 1e-4 m in
/// float, whose ulp is 2.4e-7 m at the ~3 m the cases reach from the
/// origin, so that the few dozen roundings of a contact (a change of frame,
/// a clamp, a norm) stay far inside it while a wrong feature (centimeters
/// off) does not.
template <class S>
constexpr double depthTolerance() {
  return std::is_same_v<S, double> ? 1e-6 : 1e-4;
}

/// Runs `count` cases of `sample` through `run` and `reference`, logs the
/// result, and checks: intersecting or not agrees in >= 99.9 % of the
/// decided cases, depth within `tolerance`, normal within kAngle unless
/// equivalent (judged by the projection overlap when both shapes have a
/// support function; a plane's normal is unique anyway), every contact
/// finite with a unit normal, and at least a fifth of the cases compared
/// (deeper than `compareUpTo` or not).
template <class S, class A, class B>
Agreement checkDifferential(const std::string& name, std::uint64_t seed, auto&& sample, auto&& run, auto&& reference,
                            double tolerance, int count = 10000,
                            double compareUpTo = std::numeric_limits<double>::infinity()) {
  std::function<double(const A&, const Transformd&, const B&, const Transformd&, const Vec3d&)> overlap;
  if constexpr (ConvexShape<A> && ConvexShape<B>) overlap = projectionOverlap<A, B>;
  const Agreement agreement =
      differential<S, A, B>(seed, count, sample, run, reference, tolerance, compareUpTo, overlap);
  MESSAGE(describe<S>(name, agreement));
  CHECK(agreement.disagreements * 1000 <= agreement.decided);
  CHECK(agreement.worstDepth <= tolerance);
  CHECK(agreement.wrongNormals == 0);
  CHECK(agreement.nonUnit == 0);
  CHECK((agreement.compared + agreement.deep) * 5 >= agreement.cases);
  return agreement;
}

/// checkDifferential of spook::collide (which picks the collider of the
/// pair in ShapeType order) over 10,000 cases, depth within depthTolerance<S>().
template <class S, class A, class B>
Agreement checkPair(const std::string& name, std::uint64_t seed, auto&& sample, auto&& reference) {
  const auto run = [](const auto& a, const auto& X_WA, const auto& b, const auto& X_WB, auto& sink) {
    spook::collide(a, X_WA, b, X_WB, sink);
  };
  return checkDifferential<S, A, B>(name, seed, sample, run, reference, depthTolerance<S>());
}

}  // namespace spook::test
