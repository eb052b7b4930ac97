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
#include <cstring>
#include <functional>
#include <limits>
#include <map>
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
#include <fcl/narrowphase/detail/primitive_shape_algorithm/capsule_capsule.h>
#include <fcl/narrowphase/distance.h>

#include <spook/collide/collider.hpp>
#include <spook/collide/contact_sink.hpp>
#include <spook/collide/detail/ccd_bridge.hpp>
#include <spook/collide/shapes/box.hpp>
#include <spook/collide/shapes/capsule.hpp>
#include <spook/collide/shapes/convex.hpp>
#include <spook/collide/shapes/cylinder.hpp>
#include <spook/collide/shapes/line.hpp>
#include <spook/collide/shapes/plane.hpp>
#include <spook/collide/shapes/sphere.hpp>
#include "compiled_collide.hpp"
#include "tolerance.hpp"

namespace spook::test {

using Vec3d = spook::Vec3;
using Transformd = spook::Transform;

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
/// A hull in double is handed on as it is: rebuilding the same hull would
/// only take time (it has to be reference-counted, as every shape here is).
template <Scalar S>
ref_ptr<ConvexT<S>> castShape(const ConvexT<double>& s) {
  if constexpr (std::is_same_v<S, double>) {
    return const_cast<ConvexT<double>*>(&s);
  } else {
    std::vector<Vec3T<S>> points;
    for (const Vec3d& v : s.getVertices()) points.push_back(v.cast<S>());
    return new ConvexT<S>(points);
  }
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
  X_SL.linear() = spook::rotate<double>(Vec3d::UnitZ(), q - p).toRotationMatrix();
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
/// The same for a float shape at a float pose (support taken in float).
template <class Shape>
Vec3d supportWorld(const Shape& shape, const spook::TransformT<float>& X, const Vec3d& n) {
  const spook::Vec3T<float> local = X.linear().transpose() * n.cast<float>();
  return (X * shape.support(local)).template cast<double>();
}

/// The overlap of the projections of a and b on the unit direction n (from
/// a toward b): h_a(n) + h_b(−n). The penetration depth is its minimum over
/// n, so a normal n with overlap(n) equal to the depth is as good as any.
template <class A, class B>
double projectionOverlap(const A& a, const Transformd& X_WA, const B& b, const Transformd& X_WB, const Vec3d& n) {
  return n.dot(supportWorld(a, X_WA, n) - supportWorld(b, X_WB, -n));
}

/// The support height max over the shape of d·x in its own frame (m), in
/// closed form: a restatement of the shapes' support functions that shares
/// no code with them.
inline double supportHeight(const SphereT<double>& s, const Vec3d& d) { return s.getRadius() * d.norm(); }
inline double supportHeight(const BoxT<double>& s, const Vec3d& d) { return s.getHalfExtents().dot(d.cwiseAbs()); }
inline double supportHeight(const CylinderT<double>& s, const Vec3d& d) {
  return s.getRadius() * std::sqrt(d.x() * d.x() + d.z() * d.z()) + 0.5 * s.getHeight() * std::abs(d.y());
}
inline double supportHeight(const CapsuleT<double>& s, const Vec3d& d) {
  return s.getRadius() * d.norm() + 0.5 * s.getHeight() * std::abs(d.y());
}
inline double supportHeight(const LineT<double>& s, const Vec3d& d) {
  return std::max(s.getFirstPoint().dot(d), s.getSecondPoint().dot(d));
}

/// A convex shape placed at X: its support height h(n) = max over the
/// shape of n·x (world, m), by supportHeight in the shape's frame.
template <class Shape>
struct PlacedShape {
  const Shape& shape;
  Eigen::Matrix3d R;  // shape → world
  Vec3d p;            // shape origin, world (m)
  PlacedShape(const Shape& s, const Transformd& X) : shape(s), R(X.linear()), p(X.translation()) {}
  [[nodiscard]] double height(const Vec3d& n) const {
    return supportHeight(shape, Vec3d(R.transpose() * n)) + n.dot(p);
  }
};
/// A hull: the largest n·x over its world corners.
template <>
struct PlacedShape<ConvexT<double>> {
  std::vector<Vec3d> corners;
  PlacedShape(const ConvexT<double>& s, const Transformd& X) {
    for (const Vec3d& v : s.getVertices()) corners.push_back(X * v);
  }
  [[nodiscard]] double height(const Vec3d& n) const {
    double highest = -std::numeric_limits<double>::infinity();
    for (const Vec3d& corner : corners) highest = std::max(highest, n.dot(corner));
    return highest;
  }
};

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
  const PlacedShape<A> placedA(a, X_WA);
  const PlacedShape<B> placedB(b, X_WB);
  Reference reference;
  bool first = true;
  for (const Vec3d& axis : axes) {
    if (!(axis.norm() > 1e-9)) continue;
    for (const double sign : {1.0, -1.0}) {
      const Vec3d n = sign * axis.normalized();
      const double f = placedA.height(n) + placedB.height(-n);
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

/// Where a shape's support height h(n) has kinks, world frame. `corners`:
/// directions at which h has a conical kink, the normals of flat faces (a
/// box's or hull's faces, a cylinder's caps); `ridges`: directions d whose
/// perpendicular great circle (or an arc of it) is a crease of h, the edge
/// directions of a box or hull, a cylinder's rims, a capsule's or line's
/// axis. A minimum of the projection overlap at such a kink sits at the tip
/// of a cone too narrow for a lattice of directions to see.
struct Kinks {
  std::vector<Vec3d> corners;
  std::vector<Vec3d> ridges;
};
inline void addKinks(const SphereT<double>&, const Transformd&, Kinks&) {}
inline void addKinks(const BoxT<double>&, const Transformd& X, Kinks& kinks) {
  for (int i = 0; i < 3; ++i) {
    kinks.corners.push_back(X.linear().col(i));
    kinks.corners.push_back(-X.linear().col(i));
    kinks.ridges.push_back(X.linear().col(i));
  }
}
inline void addKinks(const CylinderT<double>&, const Transformd& X, Kinks& kinks) {
  kinks.corners.push_back(X.linear().col(1));
  kinks.corners.push_back(-X.linear().col(1));
  kinks.ridges.push_back(X.linear().col(1));
}
inline void addKinks(const CapsuleT<double>&, const Transformd& X, Kinks& kinks) {
  kinks.ridges.push_back(X.linear().col(1));
}
inline void addKinks(const LineT<double>& s, const Transformd& X, Kinks& kinks) {
  kinks.ridges.push_back(X.linear() * (s.getSecondPoint() - s.getFirstPoint()));
}
inline void addKinks(const ConvexT<double>& s, const Transformd& X, Kinks& kinks) {
  for (const auto& face : s.getFaces()) kinks.corners.push_back(X.linear() * face.normal);
  const auto& v = s.getVertices();
  for (const auto& t : s.getTriangles())
    for (int k = 0; k < 3; ++k)
      if (t[std::size_t(k)] < t[std::size_t((k + 1) % 3)])
        kinks.ridges.push_back(X.linear() *
                               (v[std::size_t(t[std::size_t((k + 1) % 3)])] - v[std::size_t(t[std::size_t(k)])]));
}

/// 500 directions spread evenly over the unit sphere (a Fibonacci lattice,
/// some 0.16 rad apart).
inline const std::vector<Vec3d>& fibonacciLattice() {
  static const std::vector<Vec3d> lattice = [] {
    constexpr int kCount = 500;
    std::vector<Vec3d> directions;
    const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < kCount; ++i) {
      const double z = 1.0 - 2.0 * (i + 0.5) / kCount, rho = std::sqrt(1.0 - z * z), phi = golden * i;
      directions.emplace_back(rho * std::cos(phi), rho * std::sin(phi), z);
    }
    return directions;
  }();
  return lattice;
}

/// Nelder–Mead on g(u, v) = f(normalize(center + u e1 + v e2)), coordinates
/// on the tangent plane of the unit sphere at `center`, from a simplex of
/// `size` (rad), restarted from the best point with fresh simplices (half
/// as large after an improvement, a tenth otherwise) until they are
/// smaller than `smallest` (rad). `best` is f(center); returns the lowest
/// f found and moves `center` there.
template <class F>
double nelderMeadOnSphere(const F& f, Vec3d& center, double best, double size, double smallest) {
  for (int restarts = 0; size > smallest && restarts < 80; ++restarts) {
    const Vec3d e1 = center.unitOrthogonal(), e2 = center.cross(e1);
    const auto at = [&](const Eigen::Vector2d& x) { return Vec3d((center + x.x() * e1 + x.y() * e2).normalized()); };
    std::array<Eigen::Vector2d, 3> x = {Eigen::Vector2d(0, 0), Eigen::Vector2d(size, 0), Eigen::Vector2d(0, size)};
    std::array<double, 3> g = {best, f(at(x[1])), f(at(x[2]))};
    for (int iteration = 0; iteration < 200; ++iteration) {
      std::array<int, 3> order = {0, 1, 2};
      std::sort(order.begin(), order.end(), [&](int i, int j) { return g[std::size_t(i)] < g[std::size_t(j)]; });
      const auto lo = std::size_t(order[0]), mid = std::size_t(order[1]), hi = std::size_t(order[2]);
      if ((x[hi] - x[lo]).norm() + (x[mid] - x[lo]).norm() < smallest) break;
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
          for (const std::size_t i : {mid, hi}) {
            x[i] = x[lo] + 0.5 * (x[i] - x[lo]);
            g[i] = f(at(x[i]));
          }
        }
      }
    }
    const auto lo = std::size_t(std::min_element(g.begin(), g.end()) - g.begin());
    const bool improved = g[lo] < best - 1e-15;
    if (g[lo] < best) {
      center = at(x[lo]);
      best = g[lo];
    }
    size *= improved ? 0.5 : 0.1;
  }
  return best;
}

/// The penetration depth of two convex shapes as the minimum over unit n of
/// the projection overlap f(n) = h_a(n) + h_b(−n) (minus the distance when
/// apart), found by brute force: f on 500 directions spread evenly over the
/// sphere (fibonacciLattice) and on the kinks of f (each shape's flat-face
/// normals, and the crossings ±(d_a × d_b) of the two shapes' creases,
/// addKinks); Nelder–Mead on the tangent plane from the best five lattice
/// directions and the best three kinks, at least 0.2 rad apart, to 1e-4
/// rad, and from the best two results on to 1e-10 rad. The lattice alone
/// misses minima at cone tips (a cylinder's cap pressed on a rim: 7 mm on 1
/// case in 1,500 with 2,000 directions and five seeds), hence the kinks.
/// It shares nothing with libccd or FCL (supportHeight restates the
/// shapes' support functions); on pairs with closed forms it matches them
/// to ~1e-9 (checked in test_colliders_ccd.cpp), and on 30,000 cylinder,
/// box, capsule, hull and line pairs it came within 3e-8 m of a 4,000-point
/// lattice with fourteen seeds polished to 1e-11 rad. Being a search, it
/// may still miss a narrow minimum now and then: differential() then finds
/// f lower along spook's normal than this depth, and says so.
template <class A, class B>
Reference overlapMinimum(const A& a, const Transformd& X_WA, const B& b, const Transformd& X_WB) {
  const PlacedShape<A> placedA(a, X_WA);
  const PlacedShape<B> placedB(b, X_WB);
  const auto f = [&](const Vec3d& n) { return placedA.height(n) + placedB.height(-n); };
  constexpr std::size_t kLatticeSeeds = 5, kKinkSeeds = 3, kPolished = 2;
  const double kSeedSpacing = std::cos(0.2), kCoarse = 1e-4, kFine = 1e-10;  // rad
  using Sample = std::pair<double, Vec3d>;
  const auto lower = [](const Sample& x, const Sample& y) { return x.first < y.first; };

  std::vector<Sample> lattice, kinks;
  for (const Vec3d& n : fibonacciLattice()) lattice.emplace_back(f(n), n);
  const auto sample = [&](const Vec3d& direction) {
    if (!(direction.norm() > 1e-9)) return;
    const Vec3d n = direction.normalized();
    kinks.emplace_back(f(n), n);
  };
  Kinks kinksA, kinksB;
  addKinks(a, X_WA, kinksA);
  addKinks(b, X_WB, kinksB);
  for (const Vec3d& corner : kinksA.corners) sample(corner);
  for (const Vec3d& corner : kinksB.corners) sample(-corner);  // b's overlap term is h_b(−n)
  for (const Vec3d& ridgeA : kinksA.ridges)
    for (const Vec3d& ridgeB : kinksB.ridges) {
      sample(ridgeA.cross(ridgeB));
      sample(ridgeB.cross(ridgeA));
    }
  std::sort(lattice.begin(), lattice.end(), lower);
  std::sort(kinks.begin(), kinks.end(), lower);

  Reference reference;
  reference.depth = lattice.front().first;
  reference.normal = lattice.front().second;
  if (!kinks.empty() && kinks.front().first < reference.depth) {
    reference.depth = kinks.front().first;
    reference.normal = kinks.front().second;
  }
  std::vector<Sample> seeds;
  const auto pick = [&](const std::vector<Sample>& pool, std::size_t count) {
    const std::size_t until = seeds.size() + count;
    for (const Sample& candidate : pool) {
      if (seeds.size() == until) break;
      if (std::none_of(seeds.begin(), seeds.end(),
                       [&](const Sample& seed) { return seed.second.dot(candidate.second) >= kSeedSpacing; }))
        seeds.push_back(candidate);
    }
  };
  pick(lattice, kLatticeSeeds);
  pick(kinks, kKinkSeeds);
  for (auto& [value, n] : seeds) value = nelderMeadOnSphere(f, n, value, 0.05, kCoarse);
  std::sort(seeds.begin(), seeds.end(), lower);
  if (seeds.size() > kPolished) seeds.resize(kPolished);
  for (auto& [value, n] : seeds) {
    value = nelderMeadOnSphere(f, n, value, 10 * kCoarse, kFine);
    if (value < reference.depth) {
      reference.depth = value;
      reference.normal = n;
    }
  }
  reference.intersect = reference.depth >= 0.0;
  reference.signedDistance = -reference.depth;
  return reference;
}

/// overlapMinimum searched once per case for both scalars: the float and
/// the double run of a test collide the same shapes at poses that differ
/// by float's rounding (~1e-7), so the run that comes second takes the
/// first one's direction and polishes it on its own poses (Nelder–Mead
/// from 1e-3 to 1e-10 rad) instead of searching the sphere again: a tenth
/// of the work. Cases are told apart by their poses rounded to float.
template <class A, class B>
Reference sharedOverlapMinimum(const A& a, const Transformd& X_WA, const B& b, const Transformd& X_WB) {
  static std::map<std::array<float, 24>, Vec3d> searched;  // per shape pair type
  std::array<float, 24> key{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) {
      key[std::size_t(4 * i + j)] = float(X_WA.matrix()(i, j));
      key[std::size_t(12 + 4 * i + j)] = float(X_WB.matrix()(i, j));
    }
  const auto found = searched.find(key);
  if (found == searched.end()) {
    const Reference reference = overlapMinimum(a, X_WA, b, X_WB);
    searched.emplace(key, reference.normal);
    return reference;
  }
  const PlacedShape<A> placedA(a, X_WA);
  const PlacedShape<B> placedB(b, X_WB);
  const auto f = [&](const Vec3d& n) { return placedA.height(n) + placedB.height(-n); };
  Reference reference;
  reference.normal = found->second;
  searched.erase(found);
  reference.depth = nelderMeadOnSphere(f, reference.normal, f(reference.normal), 1e-3, 1e-10);
  reference.intersect = reference.depth >= 0.0;
  reference.signedDistance = -reference.depth;
  return reference;
}

// ---------------------------------------------------------------------------
// Polytopes: the separating axes of their Minkowski difference.

/// A polytope's faces and edges, world frame: what the facets of its
/// Minkowski difference with another polytope or a segment are made of.
struct PolytopeFeatures {
  struct Edge {
    Vec3d direction;       // unit
    Vec3d left, right;     // the outward unit normals of the two faces meeting there
    bool hasFaces = true;  // false when the hull's face loops did not give exactly two faces
  };
  std::vector<Vec3d> faceNormals;  // outward, unit
  std::vector<Edge> edges;
};

inline PolytopeFeatures polytopeFeatures(const BoxT<double>&, const Transformd& X) {
  PolytopeFeatures features;
  for (int i = 0; i < 3; ++i) {
    const Vec3d u = X.linear().col(i), v = X.linear().col((i + 1) % 3), w = X.linear().col((i + 2) % 3);
    features.faceNormals.push_back(u);
    features.faceNormals.push_back(-u);
    for (const double sv : {1.0, -1.0})
      for (const double sw : {1.0, -1.0}) features.edges.push_back({u, sv * v, sw * w, true});
  }
  return features;
}

/// A hull's polygon faces, and its edges from the faces' corner loops, each
/// between the two faces whose loops share it.
inline PolytopeFeatures polytopeFeatures(const ConvexT<double>& s, const Transformd& X) {
  PolytopeFeatures features;
  const auto& v = s.getVertices();
  std::vector<std::pair<std::pair<int, int>, std::vector<std::size_t>>> edges;  // (i < j) → faces
  for (std::size_t f = 0; f < s.getFaces().size(); ++f) {
    const auto& face = s.getFaces()[f];
    features.faceNormals.push_back(X.linear() * face.normal);
    for (std::size_t k = 0; k < face.vertices.size(); ++k) {
      const int i = face.vertices[k], j = face.vertices[(k + 1) % face.vertices.size()];
      const std::pair<int, int> key(std::min(i, j), std::max(i, j));
      auto it = std::find_if(edges.begin(), edges.end(), [&](const auto& e) { return e.first == key; });
      if (it == edges.end()) {
        edges.push_back({key, {}});
        it = edges.end() - 1;
      }
      it->second.push_back(f);
    }
  }
  for (const auto& [key, faces] : edges) {
    PolytopeFeatures::Edge edge;
    edge.direction = (X.linear() * (v[std::size_t(key.second)] - v[std::size_t(key.first)])).normalized();
    edge.hasFaces = faces.size() == 2;
    if (edge.hasFaces) {
      edge.left = features.faceNormals[faces[0]];
      edge.right = features.faceNormals[faces[1]];
    }
    features.edges.push_back(edge);
  }
  return features;
}

/// Whether the arcs AB and CD of the unit sphere (each shorter than a half
/// circle) may cross (Gregorius, "The Separating Axis Test between Convex
/// Polyhedra", GDC 2013), with some slack: a pair let through needlessly
/// only adds an axis, one held back wrongly would lose a facet.
inline bool arcsMayCross(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d) {
  constexpr double kSlack = 1e-9;
  const Vec3d bxa = b.cross(a), dxc = d.cross(c);
  const double cba = c.dot(bxa), dba = d.dot(bxa), adc = a.dot(dxc), bdc = b.dot(dxc);
  return cba * dba < kSlack && adc * bdc < kSlack && cba * bdc > -kSlack;
}

/// The facet normals of the Minkowski difference of two polytopes: the face
/// normals of both and the cross products of their edges. With `prune`,
/// only the edge pairs whose arcs on the Gauss map cross (those of b
/// mirrored: −b's faces are b's, negated) form a facet; without, every pair
/// (the textbook separating axis test, O(edges²) axes).
inline std::vector<Vec3d> minkowskiAxes(const PolytopeFeatures& a, const PolytopeFeatures& b, bool prune = true) {
  std::vector<Vec3d> axes = a.faceNormals;
  axes.insert(axes.end(), b.faceNormals.begin(), b.faceNormals.end());
  for (const auto& ea : a.edges)
    for (const auto& eb : b.edges)
      if (!prune || !ea.hasFaces || !eb.hasFaces || arcsMayCross(ea.left, ea.right, -eb.left, -eb.right))
        axes.push_back(ea.direction.cross(eb.direction));
  return axes;
}

/// The facet normals of the Minkowski difference of a polytope and a
/// segment along `direction`: the polytope's faces, and its edges crossed
/// with the segment (the parallelograms an edge sweeps along it).
inline std::vector<Vec3d> segmentAxes(const PolytopeFeatures& polytope, const Vec3d& direction) {
  std::vector<Vec3d> axes = polytope.faceNormals;
  const Vec3d d = direction.normalized();
  for (const auto& e : polytope.edges) axes.push_back(e.direction.cross(d));
  return axes;
}

/// Exact penetration of two polytopes (boxes or hulls) by the separating
/// axes of their Minkowski difference; apart, minus the largest separation
/// along them, a lower bound of the distance.
template <class A, class B>
Reference polytopeReference(const A& a, const Transformd& X_WA, const B& b, const Transformd& X_WB) {
  return axesMinimum(a, X_WA, b, X_WB, minkowskiAxes(polytopeFeatures(a, X_WA), polytopeFeatures(b, X_WB)));
}

// ---------------------------------------------------------------------------
// Closest points.

/// The point of the triangle (p0, p1, p2) closest to c (Ericson, Real-Time
/// Collision Detection, §5.1.5, by Voronoi regions).
inline Vec3d closestPointOnTriangle(const Vec3d& c, const Vec3d& p0, const Vec3d& p1, const Vec3d& p2) {
  const Vec3d ab = p1 - p0, ac = p2 - p0, ap = c - p0;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return p0;
  const Vec3d bp = c - p1;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return p1;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return p0 + d1 / (d1 - d3) * ab;
  const Vec3d cp = c - p2;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return p2;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return p0 + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return p1 + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (p2 - p1);
  const double denominator = 1.0 / (va + vb + vc);
  return p0 + ab * (vb * denominator) + ac * (vc * denominator);
}

/// Closest points of the segments [p1, q1] and [p2, q2]: FCL's closed form
/// (fcl::detail::closestPtSegmentSegment, used by its capsule distance).
struct SegmentPoints {
  Vec3d onFirst, onSecond;
  [[nodiscard]] double distance() const { return (onSecond - onFirst).norm(); }
};
inline SegmentPoints closestSegmentPoints(const Vec3d& p1, const Vec3d& q1, const Vec3d& p2, const Vec3d& q2) {
  double s = 0, t = 0;
  SegmentPoints points;
  fcl::detail::closestPtSegmentSegment<double>(p1, q1, p2, q2, &s, &t, &points.onFirst, &points.onSecond);
  return points;
}

/// A segment's world endpoints: a Line's, or a Capsule's axis (local y).
inline std::pair<Vec3d, Vec3d> worldSegment(const LineT<double>& s, const Transformd& X) {
  return {X * s.getFirstPoint(), X * s.getSecondPoint()};
}
inline std::pair<Vec3d, Vec3d> worldSegment(const CapsuleT<double>& s, const Transformd& X) {
  const Vec3d half = X.linear().col(1) * (0.5 * s.getHeight());
  return {X.translation() - half, X.translation() + half};
}

/// Hull–segment: the hull's faces and its edges crossed with the segment.
inline Reference convexLineReference(const ConvexT<double>& a, const Transformd& X_WA, const LineT<double>& b,
                                     const Transformd& X_WB) {
  const auto [p, q] = worldSegment(b, X_WB);
  return axesMinimum(a, X_WA, b, X_WB, segmentAxes(polytopeFeatures(a, X_WA), q - p));
}

/// Closest points of a segment [p, q] and a hull that it does not meet: the
/// nearest over the hull's triangles of the endpoints' closest points on
/// them (closestPointOnTriangle) and of the segment's closest points to
/// their edges (closestSegmentPoints). A segment apart from the hull comes
/// nearest to it on its surface, where one of these is the closest pair.
inline SegmentPoints segmentHullPoints(const Vec3d& p, const Vec3d& q, const ConvexT<double>& hull,
                                       const Transformd& X) {
  std::vector<Vec3d> w;
  for (const Vec3d& v : hull.getVertices()) w.push_back(X * v);
  SegmentPoints best{p, w.front()};
  const auto consider = [&](const SegmentPoints& candidate) {
    if (candidate.distance() < best.distance()) best = candidate;
  };
  for (const auto& t : hull.getTriangles()) {
    const Vec3d &p0 = w[std::size_t(t[0])], &p1 = w[std::size_t(t[1])], &p2 = w[std::size_t(t[2])];
    consider({p, closestPointOnTriangle(p, p0, p1, p2)});
    consider({q, closestPointOnTriangle(q, p0, p1, p2)});
    consider(closestSegmentPoints(p, q, p0, p1));
    consider(closestSegmentPoints(p, q, p1, p2));
    consider(closestSegmentPoints(p, q, p2, p0));
  }
  return best;
}

/// Exact penetration of a convex hull (world corners and outward faces from
/// its triangles) and a sphere: a center c outside the hull at distance d
/// from it (the nearest of the triangles, closestPointOnTriangle) gives
/// depth r − d along (c − q)/d; a center inside pushes out through the
/// nearest face plane, depth r + (offset − n·c).
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
      const Vec3d x = closestPointOnTriangle(c, v[std::size_t(t[0])], v[std::size_t(t[1])], v[std::size_t(t[2])]);
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
  int referenceMisses = 0;             // compared cases where f along spook's normal is below the reference depth
  double worstReferenceMiss = 0.0;     // m, by how much, at most
  int deep = 0;                        // compared cases deeper than the comparison limit, measured apart
  double worstDeepDepth = 0.0;         // m, over those
  double worstDepth = 0.0;             // m
  double worstAngle = 0.0;             // rad, over all compared cases
  double worstStrictAngle = 0.0;       // rad, over cases whose reference minimum is not flat or tied
  double worstEquivalentExcess = 0.0;  // m, overlap along spook's normal above the reference depth, at most
  int pointsOutside = 0;               // contacts farther than their depth (+ tolerance) outside either shape
  double worstPointExcess = 0.0;       // m, by how much, at most (convex pairs)

  static constexpr double kDecided = 1e-6;        // m
  static constexpr double kAngle = 1e-3;          // rad
  static constexpr double kReferenceMiss = 1e-7;  // m
};

/// How far the contact point p of depth `depth` lies beyond the overlap of
/// two convex shapes: the largest d·p − h(d) − depth over a spread of unit
/// directions d (and ±n) for either shape, h its support height at d. A
/// point in the overlap has none; one on a far corner of a wide face has
/// the distance to the small shape.
template <class A, class B, class Transform>
double pointExcess(const A& a, const Transform& X_WA, const B& b, const Transform& X_WB, const Vec3d& p,
                   const Vec3d& n, double depth) {
  double excess = -std::numeric_limits<double>::infinity();
  const auto judge = [&](const Vec3d& d) {
    excess = std::max(excess, d.dot(p - supportWorld(a, X_WA, d)) - depth);
    excess = std::max(excess, d.dot(p - supportWorld(b, X_WB, d)) - depth);
  };
  judge(n);
  judge(-n);
  constexpr int kDirections = 128;
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < kDirections; ++i) {
    const double z = 1.0 - (i + 0.5) * 2.0 / kDirections, rho = std::sqrt(1.0 - z * z), phi = golden * i;
    judge(Vec3d(rho * std::cos(phi), rho * std::sin(phi), z));
  }
  return excess;
}

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
/// the same distance, or a minimum too flat for S to place). The deepest
/// contact is the one compared, and where the overlap is given, the
/// reference's depth is lowered to the overlap along spook's normal when
/// that is smaller (a brute-force reference that missed the minimum; such
/// cases are counted and logged). Cases deeper than `compareUpTo` (m) are
/// measured apart and not judged.
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
    const TransformT<S> X_WA = c.X_WA.template cast<S>(), X_WB = c.X_WB.template cast<S>();
    const Transformd XA = X_WA.template cast<double>(), XB = X_WB.template cast<double>();
    points.clear();
    ContactSinkT<S> sink(points);
    run(*castShape<S>(*c.a), X_WA, *castShape<S>(*c.b), X_WB, sink);
    const Reference reference0 = reference(*c.a, XA, *c.b, XB);

    ++agreement.cases;
    agreement.intersecting += reference0.intersect ? 1 : 0;
    agreement.maxContacts = std::max(agreement.maxContacts, int(points.size()));
    const bool found = !points.empty();
    if (std::abs(reference0.signedDistance) > Agreement::kDecided) {
      ++agreement.decided;
      if (found != reference0.intersect) ++agreement.disagreements;
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
      if constexpr (ConvexShape<A> && ConvexShape<B>) {
        const double excess = pointExcess(*c.a, XA, *c.b, XB, p.point.template cast<double>(), n.normalized(),
                                          double(p.depth));
        agreement.worstPointExcess = std::max(agreement.worstPointExcess, excess);
        if (excess > depthTolerance) ++agreement.pointsOutside;
      }
    }
    if (!(found && reference0.intersect)) continue;
    // The penetration depth is the minimum of the projection overlap f over
    // unit directions, so f along spook's normal bounds it from above as
    // well as the reference's depth does. Lower than that depth, it shows
    // that the reference (a search, for curved shapes) missed the minimum:
    // spook's normal is then the better reference, and the miss is counted.
    Reference ref = reference0;
    if (overlap) {
      const double along = overlap(*c.a, XA, *c.b, XB, normal);
      if (along < ref.depth - Agreement::kReferenceMiss) {
        ++agreement.referenceMisses;
        agreement.worstReferenceMiss = std::max(agreement.worstReferenceMiss, ref.depth - along);
        ref.depth = along;
        ref.normal = normal;
      }
    }
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
  char deepText[256] = "";
  if (a.deep > 0)
    std::snprintf(deepText, sizeof deepText, "; %d deeper cases apart, worst depth error %.3g m", a.deep,
                  a.worstDeepDepth);
  if (a.referenceMisses > 0)
    std::snprintf(deepText + std::strlen(deepText), sizeof deepText - std::strlen(deepText),
                  "; %d reference misses (spook's normal overlaps less, by up to %.3g m)", a.referenceMisses,
                  a.worstReferenceMiss);
  char buffer[768];
  std::snprintf(buffer, sizeof buffer,
                "%s <%s>: %d cases, %d intersecting, %d/%d decided cases disagree; worst depth error %.3g m; "
                "worst normal error %.3g rad (%.3g rad outside %d equivalent normals, those within %.3g m); "
                "up to %d contacts; %d points outside the overlap (worst by %.3g m)%s",
                pair.c_str(), scalarName<S>(), a.cases, a.intersecting, a.disagreements, a.decided, a.worstDepth,
                a.worstAngle, a.worstStrictAngle, a.equivalentNormals, a.worstEquivalentExcess, a.maxContacts,
                a.pointsOutside, a.worstPointExcess, deepText);
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
/// (deeper than `compareUpTo` or not). 10,000 cases in optimized builds,
/// 2,000 in the sanitized one (spook::test::sweep), where the references
/// run unoptimized.
template <class S, class A, class B>
Agreement checkDifferential(const std::string& name, std::uint64_t seed, auto&& sample, auto&& run, auto&& reference,
                            double tolerance, int count = spook::test::sweep(10000, 2000),
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
/// pair in ShapeType order) over its default count of cases, depth within depthTolerance<S>(),
/// every contact point of two convex shapes in their overlap.
template <class S, class A, class B>
Agreement checkPair(const std::string& name, std::uint64_t seed, auto&& sample, auto&& reference) {
  const auto run = [](const auto& a, const auto& X_WA, const auto& b, const auto& X_WB, auto& sink) {
    spook::test::collideCompiled(a, X_WA, b, X_WB, sink);
  };
  const Agreement agreement = checkDifferential<S, A, B>(name, seed, sample, run, reference, depthTolerance<S>());
  CHECK(agreement.pointsOutside == 0);
  return agreement;
}

// ---------------------------------------------------------------------------
// The libccd pairs (test_colliders_ccd.cpp, test_colliders_ccd_more.cpp).

/// Runs the libccd bridge itself, whatever the pair's collider.
inline constexpr auto collideByBridge = [](const auto& a, const auto& X_WA, const auto& b, const auto& X_WB,
                                           auto& sink) { spook::detail::collideByCcd(a, X_WA, b, X_WB, sink); };

/// Depth tolerance of the libccd pairs, float and double (m).
inline constexpr double kCcdDepth = 1e-4;

/// Cases per libccd pair and scalar: 10,000 contacts as a simulation makes
/// them (and a twentieth as many deep overlaps, logged) in optimized
/// builds. Without NDEBUG (the Debug + AddressSanitizer build of CI, some
/// 20 times slower) 100 (and 60 deep: at least a fifth of them must
/// intersect, which 20 draws missed by chance): the bridge's polishing
/// (0.08–0.65 ms a call in Release) and the brute-force references
/// would take most of an hour there. -DSPOOK_CCD_CASES=n sets the count
/// for quick runs.
#if defined(SPOOK_CCD_CASES)
inline constexpr int kCcdCases = SPOOK_CCD_CASES;
#elif defined(NDEBUG)
inline constexpr int kCcdCases = 10000;
#else
inline constexpr int kCcdCases = 100;
#endif
inline constexpr int kCcdDeepCases = kCcdCases / 20 > 60 ? kCcdCases / 20 : 60;

/// Contacts as a simulation makes them: the second shape turned at random
/// and moved so that its deepest point along −u, for a random direction u,
/// sits δ ∈ [−5, 10] cm below the first shape's highest point along u: the
/// shapes are apart (the plane between the two points separates them) for
/// δ < 0, and overlap by at most δ otherwise.
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

/// The second shape anywhere within `reach` of the first one's center:
/// mostly deep overlaps.
template <class A, class B>
PairCase<A, B> near(RandomPoses& random, A* a, B* b, double reach) {
  PairCase<A, B> c;
  c.a = a;
  c.b = b;
  c.X_WA = random.pose(1.0);
  c.X_WB = random.poseNear(c.X_WA.translation(), reach);
  return c;
}

inline BoxT<double>* randomBox(RandomPoses& random) {
  return new BoxT<double>(Vec3d(random.length(0.1, 0.8), random.length(0.1, 0.8), random.length(0.1, 0.8)));
}
inline CylinderT<double>* randomCylinder(RandomPoses& random) {
  return new CylinderT<double>(random.length(0.1, 0.8), random.length(0.2, 1.6));
}
inline CapsuleT<double>* randomCapsule(RandomPoses& random) {
  return new CapsuleT<double>(random.length(0.1, 0.5), random.length(0.1, 1.5));
}
inline SphereT<double>* randomSphere(RandomPoses& random) { return new SphereT<double>(random.length(0.1, 0.8)); }

/// A point rounded to float, so that the float and double runs collide the
/// same hull (m).
inline Vec3d floatExact(const Vec3d& p) { return p.cast<float>().cast<double>(); }

/// A segment of length 0.1–2 m through a point up to 0.3 m from its frame's
/// origin, float-exact endpoints.
inline LineT<double>* randomLine(RandomPoses& random) {
  const Vec3d offset = random.unit() * random.uniform(0.0, 0.3), along = random.unit() * random.length(0.05, 1.0);
  return new LineT<double>(floatExact(offset - along), floatExact(offset + along));
}

/// A hull with float-exact corners: half the time that of 20–40 random
/// points on an ellipsoid of semi-axes 0.2–0.8 m (every point a corner,
/// triangular faces), half the time a box-shaped one (8 corners, half
/// extents 0.1–0.8 m, quadrilateral faces) off its frame's origin by up to
/// 0.2 m.
inline ConvexT<double>* randomHull(RandomPoses& random) {
  std::vector<Vec3d> points;
  if (random.uniform(0.0, 1.0) < 0.5) {
    const Vec3d axes(random.length(0.2, 0.8), random.length(0.2, 0.8), random.length(0.2, 0.8));
    const int count = 20 + int(random.uniform(0.0, 21.0));
    for (int i = 0; i < count; ++i) points.push_back(floatExact(random.unit().cwiseProduct(axes)));
  } else {
    const Vec3d half(random.length(0.1, 0.8), random.length(0.1, 0.8), random.length(0.1, 0.8));
    const Vec3d offset = floatExact(random.unit() * random.uniform(0.0, 0.2));
    for (int c = 0; c < 8; ++c)
      points.push_back(offset +
                       half.cwiseProduct(Vec3d((c & 1) ? 1.0 : -1.0, (c & 2) ? 1.0 : -1.0, (c & 4) ? 1.0 : -1.0)));
  }
  return new ConvexT<double>(points);
}

/// Intersecting or not by FCL's GJK (GST_INDEP); depth, normal and signed
/// distance by `exact`.
template <class A, class B>
auto withFclIntersection(auto exact) {
  return [exact](const A& a, const Transformd& X_WA, const B& b, const Transformd& X_WB) {
    const FclObject oa = toFcl(a, X_WA), ob = toFcl(b, X_WB);
    Reference reference = exact(a, X_WA, b, X_WB);
    reference.intersect = fclCollide(*oa, *ob).intersect;
    return reference;
  };
}

/// A libccd pair: kCcdCases contacts as a simulation makes them (touching),
/// judged by checkDifferential with depth within kCcdDepth; then
/// kCcdDeepCases deep overlaps (near, the second shape's center within
/// `reach` of the first's), intersecting or not and contacts judged, the
/// depth error only logged. The bridge reports the corners of the overlap
/// of the two supporting features (one point for a vertex or a curved
/// surface, up to 16 for two faces, FeatureClipping); the deepest is what
/// checkDifferential compares.
///
/// Every contact point is also judged against the overlap of the two shapes
/// (pointExcess): at most 1 in 5,000 may lie outside it by more than the
/// depth tolerance (libccd's own point was outside in up to 56% of the
/// cases, by up to 0.6 m; features sampled by tilted supports left up to
/// 0.4%, by up to 0.4 m; the shapes' own supporting features leave one
/// float convex–convex case of 10,000, issue 24). Returns the shallow and
/// the deep agreement.
template <class S, class A, class B>
std::pair<Agreement, Agreement> checkCcd(const std::string& name, std::uint64_t seed, auto&& makeA, auto&& makeB,
                                         double reach, auto&& reference) {
  const Agreement shallow = checkDifferential<S, A, B>(
      name, seed, [&](RandomPoses& random) { return touching(random, makeA(random), makeB(random)); }, collideByBridge,
      reference, kCcdDepth, kCcdCases);
  CHECK(shallow.maxContacts <= 16);
  CHECK(shallow.pointsOutside * 5000 <= shallow.cases);
  const Agreement deep = checkDifferential<S, A, B>(
      name + " (deep)", seed + 1000,
      [&](RandomPoses& random) { return near(random, makeA(random), makeB(random), reach); }, collideByBridge,
      reference, kCcdDepth, kCcdDeepCases, 0.0);
  CHECK(deep.maxContacts <= 16);
  CHECK(deep.pointsOutside * 5000 <= deep.cases);
  return {shallow, deep};
}

}  // namespace spook::test
