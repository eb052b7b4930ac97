#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <spook/collide/contact_sink.hpp>
#include <spook/collide/detail/ccd_bridge.hpp>
#include <spook/collide/detail/segment_distance.hpp>
#include <spook/collide/detail/triangle.hpp>
#include <spook/collide/shapes/capsule.hpp>

namespace spook::detail {

/// The closest points of a segment and a triangle, and whether the segment
/// crosses the triangle (then both are where it crosses).
struct SegmentTriangleClosest {
  Vec3T<double> onSegment = Vec3T<double>::Zero();
  Vec3T<double> onTriangle = Vec3T<double>::Zero();
  bool crosses = false;
};

/// Segment [p, q] and triangle t: a segment that does not cross the
/// triangle comes nearest to it at one of its ends (against the face) or
/// against one of the triangle's edges (Ericson, Real-Time Collision
/// Detection, §5.1.10's case analysis for a segment and a triangle).
inline SegmentTriangleClosest closestPointsOfSegmentAndTriangle(const Vec3T<double>& p, const Vec3T<double>& q,
                                                     const Triangle<double>& t) {
  SegmentTriangleClosest best;
  const Vec3T<double> area = (t.v[1] - t.v[0]).cross(t.v[2] - t.v[0]);
  if (const double twice = area.norm(); twice > 0.0) {
    const Vec3T<double> n = area / twice;
    const double hp = n.dot(p - t.v[0]), hq = n.dot(q - t.v[0]);
    if (((hp <= 0.0 && hq >= 0.0) || (hp >= 0.0 && hq <= 0.0)) && hp != hq) {
      const Vec3T<double> x = p + (hp / (hp - hq)) * (q - p);
      bool onFace = false;
      const Vec3T<double> y = closestOnTriangle<double>(t, x, onFace);
      if (onFace) return {x, y, true};
    }
  }
  double nearest = std::numeric_limits<double>::infinity();
  const auto consider = [&](const Vec3T<double>& onSegment, const Vec3T<double>& onTriangle) {
    const double d = (onTriangle - onSegment).squaredNorm();
    if (d < nearest) {
      nearest = d;
      best.onSegment = onSegment;
      best.onTriangle = onTriangle;
    }
  };
  bool onFace = false;
  consider(p, closestOnTriangle<double>(t, p, onFace));
  consider(q, closestOnTriangle<double>(t, q, onFace));
  for (int k = 0; k < 3; ++k) {
    const SegmentClosestPoints<double> c = closestPointsBetweenSegments<double>(p, q, t.v[k], t.v[(k + 1) % 3]);
    consider(c.onFirst, c.onSecond);
  }
  return best;
}

/// Gap points of a capsule (core [p, q], radius r) apart from a triangle by
/// up to the sink's margin: each end of the core over the face, on its
/// front, within the margin of it, as a sphere of the capsule's radius
/// there (collideSphereTriangle); over an edge or a corner none, as for the
/// other shapes (a ghost contact on the seam of two triangles).
template <Scalar S>
void capsuleGapPoints(const Vec3T<double>& p, const Vec3T<double>& q, double r, const Triangle<double>& t,
                      double touching, ContactSinkT<S>& sink) {
  const Vec3T<double> front = t.normal();
  for (const Vec3T<double>& end : {p, q}) {
    const double height = front.dot(end - t.v[0]);
    if (!(height > r) || !sink.accepts(S(r - height), S(touching))) continue;
    const Vec3T<double> foot = end - height * front;
    if (t.edgesBeside(foot, front) == 0)
      sink.addSpeculative(Vec3T<double>(foot + 0.5 * (height - r) * front).cast<S>(), Vec3T<double>(-front).cast<S>(),
                          S(r - height), S(touching));
  }
}

/// Capsule against one triangle of a mesh (mesh frame t_M, placed by X_WM),
/// in closed form: apart from the triangle, the capsule's segment core
/// (its axis between the hemisphere centers) comes within r of it at depth
/// r − d along the line of the closest points; crossing it, the smallest
/// overlap over the facet normals of the prism core − triangle (the
/// triangle's normal and the axis × each edge) plus r. Both are the exact
/// penetration of the convex pair (the capsule is the core grown by r).
/// The contacts are the overlap of the two supporting features along that
/// normal (contactsOfFeatures: two points for a capsule lying on the face),
/// as libccd's path gave them, at a sixtieth of its cost (bench_colliders).
/// Apart within the sink's margin: capsuleGapPoints.
template <Scalar S>
void collideCapsuleTriangle(const CapsuleT<S>& capsule, const TransformT<S>& X_WA, const Triangle<S>& t_M,
                            const TransformT<S>& X_WM, ContactSinkT<S>& sink) {
  const ConvexSupport viewA = convexSupportOf(capsule), viewB = convexSupportOf(t_M);
  const double sizeA = viewA.size, sizeB = viewB.size;
  if (!std::isfinite(sizeA) || !std::isfinite(sizeB)) return;
  const TransformT<double> X_WMd = X_WM.template cast<double>();
  const Triangle<double> t{{X_WMd * t_M.v[0].template cast<double>(), X_WMd * t_M.v[1].template cast<double>(),
                            X_WMd * t_M.v[2].template cast<double>()}};
  const Vec3T<double> axis = X_WA.linear().col(1).template cast<double>();
  const Vec3T<double> center = X_WA.translation().template cast<double>();
  const Vec3T<double> half = (0.5 * double(capsule.getHeight())) * axis;
  const Vec3T<double> p = center - half, q = center + half;
  const double r = double(capsule.getRadius());
  // As libccd's path: a gap within kTouchingGap of the smaller size touches.
  const double touching = kTouchingGap * std::min(sizeA, sizeB);

  const SegmentTriangleClosest closest = closestPointsOfSegmentAndTriangle(p, q, t);
  const Vec3T<double> gap = closest.onTriangle - closest.onSegment;
  const double distance = gap.norm();
  Vec3T<double> n;
  double depth;
  if (!closest.crosses && distance > 1e-12 * (sizeA + sizeB)) {
    depth = r - distance;
    if (depth < -touching) {
      if (sink.accepts(depth)) capsuleGapPoints(p, q, r, t, touching, sink);
      return;
    }
    n = gap / distance;
  } else {
    // f(a) = h_capsule(a) + h_triangle(−a): the overlap of the projections
    // onto the unit a, from the capsule toward the triangle.
    depth = std::numeric_limits<double>::infinity();
    n = t.normal();
    const auto consider = [&](const Vec3T<double>& direction) {
      const double length = direction.norm();
      if (!(length > 1e-12)) return;
      for (const double sign : {1.0, -1.0}) {
        const Vec3T<double> a = direction * (sign / length);
        const double f = std::max(a.dot(p), a.dot(q)) + r - std::min({a.dot(t.v[0]), a.dot(t.v[1]), a.dot(t.v[2])});
        if (f < depth) {
          depth = f;
          n = a;
        }
      }
    };
    consider((t.v[1] - t.v[0]).cross(t.v[2] - t.v[0]));
    for (int k = 0; k < 3; ++k) consider(axis.cross(t.v[(k + 1) % 3] - t.v[k]));
    if (!std::isfinite(depth)) return;
  }
  const CcdObject objectA(viewA, X_WA);
  const CcdObject objectB(viewB, X_WM);
  for (const FeatureClipping::Contact& contact : contactsOfFeatures(objectA, objectB, n, std::max(depth, 0.0)))
    sink.add(contact.point.cast<S>(), n.cast<S>(), S(contact.depth));
}

}  // namespace spook::detail
