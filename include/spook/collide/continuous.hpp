#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <unordered_map>
#include <vector>

#include <ccd/ccd.h>

#include <spook/collide/all_shapes.hpp>
#include <spook/collide/detail/aabb_tree.hpp>
#include <spook/collide/detail/ccd_bridge.hpp>
#include <spook/collide/detail/triangle.hpp>
#include <spook/collide/geometry.hpp>
#include <spook/collide/space.hpp>
#include <spook/core/implementation.hpp>
#include <spook/core/math.hpp>
#include <spook/core/ref_ptr.hpp>
#include <spook/dynamics/rigid_body.hpp>

/// Continuous collision detection (CCD), a stage of the step that runs after
/// the bodies have moved (Simulation::stepForward).
///
/// Covers: dynamic bodies with RigidBody::setEnableCCD(true) whose step
/// displacement h·v exceeds their reach: their thinnest half-width w less
/// the depth of their deepest contact of the step (counted up to w/2).
/// Below that the discrete contacts catch every wall: the body's center
/// cannot cross a wall's near face in one step, nor reach a thin wall's far
/// side. Their sphere, box, capsule, cylinder and convex shapes (composites
/// of them included) are swept linearly, in the orientation
/// they end the step with, from where the center-of-mass motion h·v started
/// them to where it left them, against every geometry the space lets them
/// collide with: planes, boxes, spheres, capsules, cylinders, convex hulls,
/// lines, and the triangles of trimeshes and height fields (composites of
/// them included). The time of impact is found on the shapes' support
/// functions: the shape swept over [0, t·h·v] is convex (its support is
/// s(d) + max(0, d·Δ)/(d·Δ)·Δ along d, with Δ = t·h·v), it overlaps a
/// target from the first contact on, so bisection on t with libccd's GJK
/// overlap test brackets the first contact to w/200; planes are solved in
/// closed form. The body is then put back along its path to first contact
/// plus a penetration of w/100 (between w/200 and w/100), so that the next
/// step's discrete contacts take over; its velocities are kept and the
/// contact rows handle the impact (restitution included).
///
/// A target the shape already overlaps at the start of the sweep (a resting
/// or sliding contact, or an impact the contact rows have not stopped yet:
/// a damped SPOOK contact takes a few steps to stop a fast body) is swept
/// with the shape's core instead, the sphere of radius w/2 at its center of
/// volume, and the body is placed just short of the core's first contact:
/// it then overlaps the target by at most about w/2 and its center stays on
/// the near side, where the discrete contacts push it back out.
///
/// Leaves to the discrete contacts: hits whose motion along the contact
/// normal is at most the reach (a grazing approach, e.g. a fast body
/// sliding across a floor; the discrete contacts hold such penetrations),
/// and cores that start inside a target. The normal is the plane's, the
/// triangle's face normal, or libccd's penetration direction for convex
/// targets.
///
/// Does not cover: rotation (the sweep keeps the end orientation: a fast
/// spinning thin body may still tunnel, and a rotation into a wall counts as
/// starting in contact); kinematic bodies (they go where they are told);
/// trimesh, height field, plane and line shapes on the moving body; other
/// bodies are taken where the step left them (no relative motion between
/// two moving bodies: two fast bodies may pass through each other); sensor
/// geometries and contacts a listener would remove are not anticipated.
namespace spook::detail {

/// A convex shape swept along the segment [0, motion] of its own frame: the
/// Minkowski sum of the two, which is convex, with the support below.
struct SweptConvex {
  const ConvexSupport* shape;
  Vec3T<double> motion;  // shape frame (m)

  [[nodiscard]] ConvexSupport view() const {
    ConvexSupport convex;
    convex.shape = this;
    convex.support = [](const void* s, const Vec3T<double>& d) -> Vec3T<double> {
      const auto& swept = *static_cast<const SweptConvex*>(s);
      const Vec3T<double> p = swept.shape->supportAlong(d);
      return d.dot(swept.motion) > 0.0 ? Vec3T<double>(p + swept.motion) : p;
    };
    convex.centerOfVolume = shape->centerOfVolume + 0.5 * motion;
    convex.size = shape->size + 0.5 * motion.norm();
    return convex;
  }
};

/// The core of a swept shape: a sphere of `radius` at `center` (shape frame).
struct CoreSphere {
  Vec3T<double> center;
  double radius;

  [[nodiscard]] ConvexSupport view() const {
    ConvexSupport convex;
    convex.shape = this;
    convex.support = [](const void* s, const Vec3T<double>& d) -> Vec3T<double> {
      const auto& core = *static_cast<const CoreSphere*>(s);
      const double length = d.norm();
      return length > 0.0 ? Vec3T<double>(core.center + (core.radius / length) * d) : core.center;
    };
    convex.centerOfVolume = center;
    convex.size = std::sqrt(3.0) * radius;
    return convex;
  }
};

/// Whether two convex objects overlap (libccd's GJK).
[[nodiscard]] inline bool ccdOverlap(const CcdObject& a, const CcdObject& b) {
  const ccd_t ccd = ccdSettings();
  return ccdGJKIntersect(&a, &b, &ccd) != 0;
}

/// The first contact of one body's sweep, kept across its shapes and targets.
struct SweepHit {
  double fraction = 1.0;  ///< of the step's motion, at or just past first contact
  bool found = false;
};

/// The sweep of one body over one step: its motion Δ = h·v (world, m), its
/// thinnest half-width w (m) and the tolerances derived from it.
template <Scalar S>
class BodySweep {
 public:
  using Vec3 = spook::Vec3T<S>;
  using Transform = spook::TransformT<S>;
  using Shape = ShapeT<S>;

  /// `reach` (m): the approach along a contact normal that the discrete
  /// contacts hold, the half-width less the body's present overlap.
  BodySweep(const Vec3& motion, double halfWidth, double reach)
      : motion_(motion.template cast<double>()), length_(motion_.norm()), halfWidth_(halfWidth), reach_(reach) {}

  /// The depth that the body is placed at past first contact (m).
  [[nodiscard]] double contactDepth() const { return 0.01 * halfWidth_; }
  [[nodiscard]] const SweepHit& hit() const { return hit_; }

  /// Sweeps the moving shape `a` (at X_end, the end of the step) against
  /// the target shape `b` at X_WB.
  void sweep(const Shape& a, const Transform& X_end, const Shape& b, const Transform& X_WB) {
    switch (a.getType()) {
      case ShapeType::BOX:
        return against(a, convexSupportOf(static_cast<const BoxT<S>&>(a)), X_end, b, X_WB);
      case ShapeType::CAPSULE:
        return against(a, convexSupportOf(static_cast<const CapsuleT<S>&>(a)), X_end, b, X_WB);
      case ShapeType::CONVEX:
        return against(a, convexSupportOf(static_cast<const ConvexT<S>&>(a)), X_end, b, X_WB);
      case ShapeType::CYLINDER:
        return against(a, convexSupportOf(static_cast<const CylinderT<S>&>(a)), X_end, b, X_WB);
      case ShapeType::SPHERE:
        return against(a, convexSupportOf(static_cast<const SphereT<S>&>(a)), X_end, b, X_WB);
      case ShapeType::COMPOSITE:
        for (const auto& child : static_cast<const CompositeT<S>&>(a).getChildren())
          sweep(*child.shape, X_end * child.transform, b, X_WB);
        return;
      default:
        return;  // not swept: see the header
    }
  }

 private:
  // `shape` is the moving convex shape, `a` the bridge's view of it.
  void against(const Shape& shape, const ConvexSupport& a, const Transform& X_end, const Shape& b,
               const Transform& X_WB) {
    switch (b.getType()) {
      case ShapeType::BOX:
        return convex(a, X_end, convexSupportOf(static_cast<const BoxT<S>&>(b)), X_WB);
      case ShapeType::CAPSULE:
        return convex(a, X_end, convexSupportOf(static_cast<const CapsuleT<S>&>(b)), X_WB);
      case ShapeType::CONVEX:
        return convex(a, X_end, convexSupportOf(static_cast<const ConvexT<S>&>(b)), X_WB);
      case ShapeType::CYLINDER:
        return convex(a, X_end, convexSupportOf(static_cast<const CylinderT<S>&>(b)), X_WB);
      case ShapeType::LINE:
        return convex(a, X_end, convexSupportOf(static_cast<const LineT<S>&>(b)), X_WB);
      case ShapeType::SPHERE:
        return convex(a, X_end, convexSupportOf(static_cast<const SphereT<S>&>(b)), X_WB);
      case ShapeType::PLANE:
        return plane(a, X_end, static_cast<const PlaneT<S>&>(b), X_WB);
      case ShapeType::TRIMESH:
        return triangles(shape, a, X_end, static_cast<const TrimeshT<S>&>(b), X_WB);
      case ShapeType::HEIGHTFIELD:
        return triangles(shape, a, X_end, static_cast<const HeightFieldT<S>&>(b), X_WB);
      case ShapeType::COMPOSITE:
        for (const auto& child : static_cast<const CompositeT<S>&>(b).getChildren())
          against(shape, a, X_end, *child.shape, X_WB * child.transform);
        return;
    }
  }

  // Records a hit at `fraction` unless the approach (m), the motion along
  // the contact normal, is one the discrete contacts hold: at most the
  // reach per step.
  void record(double fraction, double approach) {
    if (!(approach > reach_) || !(fraction < hit_.fraction)) return;
    hit_.fraction = fraction;
    hit_.found = true;
  }

  [[nodiscard]] Transform startOf(const Transform& X_end) const {
    Transform X = X_end;
    X.translation() -= motion_.template cast<S>();
    return X;
  }
  [[nodiscard]] CoreSphere coreOf(const ConvexSupport& a) const { return {a.centerOfVolume, 0.5 * halfWidth_}; }

  // A half-space: the deepest point along −n of the shape (or, when the
  // shape starts inside, of its core) reaches the plane after the gap over
  // the approach, in closed form.
  void plane(const ConvexSupport& a, const Transform& X_end, const PlaneT<S>& b, const Transform& X_WB) {
    const Vec3T<double> n = (X_WB.linear() * b.getNormal()).template cast<double>();
    const Vec3T<double> point = (X_WB * b.getPoint()).template cast<double>();
    const Transform X_start = startOf(X_end);
    const Mat3T<double> R = X_start.linear().template cast<double>();
    const Vec3T<double> p = X_start.translation().template cast<double>(), down = R.transpose() * -n;
    const auto gapOf = [&](const ConvexSupport& shape) { return n.dot(R * shape.supportAlong(down) + p - point); };
    const double approach = -n.dot(motion_);
    double gap = gapOf(a), depth = contactDepth();
    if (!(gap > 0.0)) {
      const CoreSphere core = coreOf(a);
      gap = gapOf(core.view());
      depth = 0.0;
    }
    if (gap > 0.0 && approach > gap) record(std::min(1.0, gap / approach + depth / length_), approach);
  }

  // Each triangle of a mesh or height field near the sweep, as a convex
  // target whose contact normal is its face normal (either side).
  template <class Soup>
  void triangles(const Shape& shape, const ConvexSupport& a, const Transform& X_end, const Soup& b,
                 const Transform& X_WB) {
    const BoundingBoxT<S> local = shape.getBoundingBox();
    const BoundingBoxT<S> end = transformBox<S>(local, X_end), start = transformBox<S>(local, startOf(X_end));
    const BoundingBoxT<S> swept{end.min.cwiseMin(start.min), end.max.cwiseMax(start.max)};
    const Transform X_BW = X_WB.inverse();
    b.forEachTriangle(transformBox<S>(swept, X_BW), [&](std::size_t, const Vec3& p, const Vec3& q, const Vec3& r) {
      const Triangle<S> triangle{{p, q, r}};
      if (const std::optional<double> t = placement(a, X_end, convexSupportOf(triangle), X_WB))
        record(*t, std::abs(motion_.dot((X_WB.linear() * triangle.normal()).template cast<double>())));
    });
  }

  // A convex target: the contact normal is libccd's penetration direction
  // at the placed pose (the motion's direction when libccd finds none).
  void convex(const ConvexSupport& a, const Transform& X_end, const ConvexSupport& b, const Transform& X_WB) {
    const std::optional<double> t = placement(a, X_end, b, X_WB);
    if (!t) return;
    Transform X_hit = X_end;
    X_hit.translation() -= ((1.0 - *t) * motion_).template cast<S>();
    // libccd's MPR refines its portal without an iteration cap either: the
    // same support budget as the bridge's EPA (ccd_bridge.hpp) ends it.
    CcdSupportBudget budget{kCcdSupportBudget};
    CcdObject objectA(a, X_hit);
    CcdObject objectB(b, X_WB);
    objectA.budget = objectB.budget = &budget;
    objectA.countsCalls = true;
    const ccd_t ccd = ccdSettings();
    ccd_real_t depth = 0;
    ccd_vec3_t direction, position;
    double approach = length_;
    if (ccdMPRPenetration(&objectA, &objectB, &ccd, &depth, &direction, &position) == 0) {
      const Vec3T<double> d(direction.v[0], direction.v[1], direction.v[2]);
      if (d.norm() > 0.0) approach = std::abs(motion_.dot(d.normalized()));
    }
    record(*t, approach);
  }

  // The fraction of the motion at which the body is to be placed against
  // convex b: the first contact of the shape plus the contact depth or,
  // when the shape starts overlapping b (a contact the solver has not yet
  // stopped), the first contact of its core; none when out of reach.
  [[nodiscard]] std::optional<double> placement(const ConvexSupport& a, const Transform& X_end, const ConvexSupport& b,
                                                const Transform& X_WB) const {
    const Contact shape = firstContact(a, X_end, b, X_WB, contactDepth());
    if (!shape.startsInside) return shape.fraction;
    const CoreSphere core = coreOf(a);
    return firstContact(core.view(), X_end, b, X_WB, 0.0).fraction;
  }

  struct Contact {
    bool startsInside = false;
    std::optional<double> fraction;  ///< where to place the body
  };
  // First contact of convex a swept against convex b, bracketed by bisection
  // to half the contact depth; placed `depth` (m) past it, or just short of
  // it for a depth of 0.
  [[nodiscard]] Contact firstContact(const ConvexSupport& a, const Transform& X_end, const ConvexSupport& b,
                                     const Transform& X_WB, double depth) const {
    const Transform X_start = startOf(X_end);
    const Mat3T<double> R_start = X_start.linear().template cast<double>();
    const Vec3T<double> p_start = X_start.translation().template cast<double>();
    const Vec3T<double> motionLocal = R_start.transpose() * motion_;
    const CcdObject objectB(b, X_WB);
    const auto reaches = [&](double t) {
      const SweptConvex swept{&a, t * motionLocal};
      return ccdOverlap(CcdObject(swept.view(), R_start, p_start), objectB);
    };
    if (reaches(0.0)) return {true, std::nullopt};
    if (!reaches(1.0)) return {};
    double lo = 0.0, hi = 1.0;
    while ((hi - lo) * length_ > 0.5 * contactDepth()) {
      const double mid = 0.5 * (lo + hi);
      (reaches(mid) ? hi : lo) = mid;
    }
    return {false, depth > 0.0 ? std::min(1.0, hi + (depth - 0.5 * contactDepth()) / length_) : lo};
  }

  Vec3T<double> motion_;
  double length_;
  double halfWidth_;
  double reach_;
  SweepHit hit_;
};

/// The thinnest half-width of the shapes swept for a body (m): the least of
/// (h(d) + h(−d))/2 over the 13 directions of the axes and the face and body
/// diagonals of each shape's frame (exact for spheres, boxes, capsules and
/// cylinders); infinity when none is swept.
template <Scalar S>
[[nodiscard]] double sweptHalfWidth(const ShapeT<S>& shape) {
  const auto width = [](const auto& convex) {
    double least = std::numeric_limits<double>::infinity();
    for (int x = -1; x <= 1; ++x)
      for (int y = -1; y <= 1; ++y)
        for (int z = 0; z <= 1; ++z) {
          const Vec3T<S> d = Vec3T<S>(S(x), S(y), S(z));
          if (z == 0 && (y < 0 || (y == 0 && x <= 0))) continue;  // one of ±d, and not 0
          const Vec3T<S> u = d.normalized();
          least = std::min(least, 0.5 * double(u.dot(convex.support(u)) - u.dot(convex.support(Vec3T<S>(-u)))));
        }
    return least;
  };
  switch (shape.getType()) {
    case ShapeType::BOX:
      return width(static_cast<const BoxT<S>&>(shape));
    case ShapeType::CAPSULE:
      return width(static_cast<const CapsuleT<S>&>(shape));
    case ShapeType::CONVEX:
      return width(static_cast<const ConvexT<S>&>(shape));
    case ShapeType::CYLINDER:
      return width(static_cast<const CylinderT<S>&>(shape));
    case ShapeType::SPHERE:
      return width(static_cast<const SphereT<S>&>(shape));
    case ShapeType::COMPOSITE: {
      double least = std::numeric_limits<double>::infinity();
      for (const auto& child : static_cast<const CompositeT<S>&>(shape).getChildren())
        least = std::min(least, sweptHalfWidth<S>(*child.shape));
      return least;
    }
    default:
      return std::numeric_limits<double>::infinity();
  }
}

/// The CCD stage of the step (see the top of this file): after the bodies
/// have moved, puts each fast CCD body back to its first contact along its
/// path. Velocities are left as they are.
template <Scalar S>
void stopAtFirstContact(const std::vector<ref_ptr<RigidBodyT<S>>>& bodies, const SpaceT<S>& space, S h) {
  using Body = RigidBodyT<S>;
  using Geometry = GeometryT<S>;
  const auto sweeps = [](const Body& body) {
    return body.getEnableCCD() && body.getEnable() && body.getMotionControl() == Body::DYNAMICS;
  };
  if (std::none_of(bodies.begin(), bodies.end(), [&](const auto& body) { return sweeps(*body); })) return;
  // Each swept body's deepest contact of the step (m).
  std::unordered_map<const Body*, double> deepest;
  for (const auto& contact : space.getGeometryContacts())
    for (std::size_t i = 0; i < 2; ++i)
      if (const Body* body = contact.rigidBody(i); body && sweeps(*body))
        for (const auto& point : contact.points())
          if (point.enabled && double(point.depth) > 0.0) deepest[body] = std::max(deepest[body], double(point.depth));
  for (const auto& body : bodies) {
    if (!sweeps(*body)) continue;
    const Vec3T<S> motion = h * body->getVelocity();
    double halfWidth = std::numeric_limits<double>::infinity();
    for (const auto& g : body->getGeometries())
      if (!g->isSensor())
        for (const auto& e : g->getShapes()) halfWidth = std::min(halfWidth, sweptHalfWidth<S>(*e.shape));
    const auto depth = deepest.find(body.get());
    const double reach = halfWidth - (depth == deepest.end() ? 0.0 : std::min(depth->second, 0.5 * halfWidth));
    if (!(motion.allFinite() && double(motion.norm()) > reach)) continue;
    BodySweep<S> sweep(motion, halfWidth, reach);
    const auto against = [&](const Geometry& target) {
      for (const auto& g : body->getGeometries()) {
        if (g->isSensor() || !space.canCollide(*g, target)) continue;
        const BoundingBoxT<S> end = g->getBoundingBox();
        const BoundingBoxT<S> swept{end.min.cwiseMin(end.min - motion), end.max.cwiseMax(end.max - motion)};
        if (!overlaps<S>(swept, target.getBoundingBox())) continue;
        const TransformT<S> X_WG = g->getTransform(), X_WT = target.getTransform();
        for (const auto& a : g->getShapes())
          for (const auto& b : target.getShapes()) sweep.sweep(*a.shape, X_WG * a.transform, *b.shape, X_WT * b.transform);
      }
    };
    for (const auto& target : space.getGeometries())
      if (!target->isSensor()) against(*target);
    for (const auto& other : bodies)
      if (other != body && other->getEnable())
        for (const auto& target : other->getGeometries())
          if (!target->isSensor()) against(*target);
    if (sweep.hit().found)
      body->setCmPosition(body->getCmPosition() - S(1.0 - sweep.hit().fraction) * motion);
  }
}

}  // namespace spook::detail

namespace spook {

template <Scalar S>
void RigidBodyT<S>::setEnableCCD(bool enable) {
  if (enable) detail::ccdStage<S>.store(&detail::stopAtFirstContact<S>, std::memory_order_relaxed);
  enableCCD_ = enable;
}

// Defined after the class's own explicit instantiation (dynamics/rigid_body.hpp).
SPOOK_COMPILED_DOUBLE(void RigidBodyT<double>::setEnableCCD(bool))
SPOOK_COMPILED_FLOAT(void RigidBodyT<float>::setEnableCCD(bool))

}  // namespace spook
