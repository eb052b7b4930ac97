#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include <spook/collide/contact_sink.hpp>
#include <spook/collide/detail/polytope_sat.hpp>
#include <spook/collide/detail/segment_distance.hpp>
#include <spook/collide/detail/triangle.hpp>
#include <spook/collide/shapes/box.hpp>
#include <spook/collide/shapes/capsule.hpp>
#include <spook/collide/shapes/convex.hpp>
#include <spook/collide/shapes/cylinder.hpp>
#include <spook/collide/shapes/line.hpp>
#include <spook/collide/shapes/sphere.hpp>
#include <spook/core/math.hpp>

namespace spook::detail {

/// The supporting feature of a convex shape along a unit direction d: the
/// surface points that reach farthest along d, where "farthest" allows a
/// tilt of d by up to kFeatureSine (0.02, 1.1°) so that a face, an edge or a
/// side line lying within that angle of the contact plane counts whole. One
/// point (a curved surface, a corner), two (an edge, the side line of a
/// cylinder or a capsule) or a polygon in loop order (a face, a cylinder's
/// cap rim as an octagon starting at its deepest rim point). In the shape's
/// own frame, double.
inline constexpr double kFeatureSine = 0.02;
inline constexpr double kFeatureCosine = 0.9998;  // sqrt(1 − kFeatureSine²)
using FeaturePoints = std::vector<Vec3T<double>>;

/// The unit component of d across the unit axis u, or a fallback when d is along u.
inline Vec3T<double> acrossAxis(const Vec3T<double>& d, const Vec3T<double>& u, const Vec3T<double>& fallback) {
  const Vec3T<double> across = d - d.dot(u) * u;
  const double length = across.norm();
  return length > 1e-12 ? Vec3T<double>(across / length) : fallback;
}

template <Scalar T>
void supportingFeature(const SphereT<T>& sphere, const Vec3T<double>& d, FeaturePoints& out) {
  out.assign(1, double(sphere.getRadius()) * d);
}

template <Scalar T>
void supportingFeature(const BoxT<T>& box, const Vec3T<double>& d, FeaturePoints& out) {
  const Vec3T<double> h = box.getHalfExtents().template cast<double>();
  // Each axis along which d has (almost) no component is spanned by the feature.
  Vec3T<double> sign;
  int spanned[2] = {-1, -1}, count = 0;
  for (int i = 0; i < 3; ++i) {
    sign[i] = d[i] < 0.0 ? -1.0 : 1.0;
    if (std::abs(d[i]) <= kFeatureSine && count < 2) spanned[count++] = i;
  }
  const Vec3T<double> corner = sign.cwiseProduct(h);
  out.assign(1, corner);
  if (count == 0) return;
  const auto flipped = [&](Vec3T<double> p, int axis) {
    p[axis] = -p[axis];
    return p;
  };
  out.push_back(flipped(corner, spanned[0]));
  if (count == 2) {
    out.push_back(flipped(out[1], spanned[1]));
    out.push_back(flipped(corner, spanned[1]));
  }
}

template <Scalar T>
void supportingFeature(const CapsuleT<T>& capsule, const Vec3T<double>& d, FeaturePoints& out) {
  const double r = capsule.getRadius(), h = 0.5 * double(capsule.getHeight());
  const Vec3T<double> u = Vec3T<double>::UnitY();
  if (std::abs(d.y()) <= kFeatureSine)
    out = {Vec3T<double>(h * u + r * d), Vec3T<double>(-h * u + r * d)};
  else
    out.assign(1, (d.y() < 0.0 ? -h : h) * u + r * d);
}

template <Scalar T>
void supportingFeature(const CylinderT<T>& cylinder, const Vec3T<double>& d, FeaturePoints& out) {
  const double r = cylinder.getRadius(), h = 0.5 * double(cylinder.getHeight());
  const Vec3T<double> u = Vec3T<double>::UnitY();
  const Vec3T<double> v = acrossAxis(d, u, Vec3T<double>::UnitX());
  const Vec3T<double> cap = (d.y() < 0.0 ? -h : h) * u;
  if (std::abs(d.y()) >= kFeatureCosine) {
    const Vec3T<double> w = u.cross(v);
    out.clear();
    for (int k = 0; k < 8; ++k) {
      const double angle = 0.25 * 3.141592653589793 * k;
      out.push_back(cap + r * (std::cos(angle) * v + std::sin(angle) * w));
    }
  } else if (std::abs(d.y()) <= kFeatureSine) {
    out = {Vec3T<double>(h * u + r * v), Vec3T<double>(-h * u + r * v)};
  } else {
    out.assign(1, cap + r * v);
  }
}

/// A polyhedron given by its corners: the face whose normal is within the
/// tolerance of d, else the edge from the farthest corner that is, else
/// that corner.
inline void polyhedronFeature(const auto& corner, std::size_t corners, const auto& faceNormal,
                              const auto& faceLoop, std::size_t faces, const auto& edgeEnds, std::size_t edges,
                              const Vec3T<double>& d, FeaturePoints& out) {
  std::size_t bestFace = 0;
  double alignment = -2.0;
  for (std::size_t f = 0; f < faces; ++f)
    if (const double a = d.dot(faceNormal(f)); a > alignment) alignment = a, bestFace = f;
  out.clear();
  if (alignment >= kFeatureCosine) {
    for (const int k : faceLoop(bestFace)) out.push_back(corner(std::size_t(k)));
    return;
  }
  std::size_t best = 0;
  for (std::size_t i = 1; i < corners; ++i)
    if (d.dot(corner(i)) > d.dot(corner(best))) best = i;
  out.push_back(corner(best));
  for (std::size_t e = 0; e < edges; ++e) {
    const auto [from, to] = edgeEnds(e);
    if (from != best && to != best) continue;
    const Vec3T<double> other = corner(from == best ? to : from);
    const Vec3T<double> along = out[0] - other;
    if (d.dot(along) <= kFeatureSine * along.norm()) {
      out.push_back(other);
      return;
    }
  }
}

template <Scalar T>
void supportingFeature(const ConvexT<T>& convex, const Vec3T<double>& d, FeaturePoints& out) {
  const auto& vertices = convex.getVertices();
  const auto& faces = convex.getFaces();
  const auto& edges = convex.getEdges();
  polyhedronFeature([&](std::size_t i) { return Vec3T<double>(vertices[i].template cast<double>()); },
                    vertices.size(), [&](std::size_t f) { return Vec3T<double>(faces[f].normal.template cast<double>()); },
                    [&](std::size_t f) -> const auto& { return faces[f].vertices; }, faces.size(),
                    [&](std::size_t e) {
                      return std::pair<std::size_t, std::size_t>(std::size_t(edges[e].from), std::size_t(edges[e].to));
                    },
                    edges.size(), d, out);
}

template <Scalar T>
void supportingFeature(const Triangle<T>& triangle, const Vec3T<double>& d, FeaturePoints& out) {
  const Vec3T<double> n = triangle.normal().template cast<double>();
  static constexpr std::array<int, 3> kLoop = {0, 1, 2};
  polyhedronFeature([&](std::size_t i) { return Vec3T<double>(triangle.v[i].template cast<double>()); }, 3,
                    [&](std::size_t f) { return f == 0 ? n : Vec3T<double>(-n); },
                    [&](std::size_t) -> const auto& { return kLoop; }, 2,
                    [](std::size_t e) { return std::pair<std::size_t, std::size_t>(e, (e + 1) % 3); }, 3, d, out);
}

template <Scalar T>
void supportingFeature(const LineT<T>& line, const Vec3T<double>& d, FeaturePoints& out) {
  const Vec3T<double> p = line.getFirstPoint().template cast<double>(), q = line.getSecondPoint().template cast<double>();
  const Vec3T<double> along = q - p;
  if (std::abs(d.dot(along)) <= kFeatureSine * along.norm())
    out = {p, q};
  else
    out.assign(1, d.dot(along) > 0.0 ? q : p);
}

/// The supporting feature of a placed shape along the world direction d_W, in world coordinates.
template <class Shape>
void worldFeature(const Shape& shape, const Mat3T<double>& R, const Vec3T<double>& p, const Vec3T<double>& d_W,
                  FeaturePoints& out) {
  supportingFeature(shape, Vec3T<double>(R.transpose() * d_W), out);
  for (auto& x : out) x = R * x + p;
}

/// Clips `corners` (a point list: polygon or segment) to the prism over the
/// polygon `loop` (world, loop order) along the direction r.
inline void clipToPrism(FeaturePoints& corners, const FeaturePoints& loop, const Vec3T<double>& r,
                        FeaturePoints& scratch) {
  Vec3T<double> centroid = Vec3T<double>::Zero();
  for (const auto& y : loop) centroid += y;
  centroid /= double(loop.size());
  for (std::size_t k = 0; k < loop.size() && !corners.empty(); ++k) {
    const Vec3T<double>& y = loop[k];
    Vec3T<double> side = (loop[(k + 1) % loop.size()] - y).cross(r);
    if (side.dot(centroid - y) > 0.0) side = -side;
    const double length = side.norm();
    if (!(length > 0.0)) continue;
    side /= length;
    clipToHalfSpace(corners, side, side.dot(y), scratch);
  }
}

/// Contacts of two shapes that overlap by `depth` along the unit n (from a
/// toward b), from their supporting features fa (of a along n) and fb (of b
/// along −n), world. The rule:
/// - where one feature is a single point (a curved surface or a corner:
///   the support there is unique), one contact at that point moved by
///   depth/2 into the overlap; where both are, at the midpoint of the two;
/// - where both features extend, the incident feature is clipped against
///   the reference one (a polygon of b, else one of a; two segments
///   against each other's span, Sutherland–Hodgman), and each clipped
///   point below the reference plane is a contact of its own depth, moved
///   halfway to that plane. Two crossing segments give the midpoint of
///   their closest points.
/// So every point lies in the overlap, and a support point chosen among
/// the corners of a flat face is never the contact. Returns false when the
/// clipping left nothing (the caller then falls back to one point).
template <Scalar S>
bool featureContacts(const FeaturePoints& fa, const FeaturePoints& fb, const Vec3T<double>& n, double depth,
                     ContactSinkT<S>& sink) {
  const auto add = [&](const Vec3T<double>& x, double d) { sink.add(x.cast<S>(), n.cast<S>(), S(d)); };
  if (fa.size() == 1 || fb.size() == 1) {
    if (fa.size() == 1 && fb.size() == 1)
      add(0.5 * (fa[0] + fb[0]), depth);
    else if (fa.size() == 1)
      add(fa[0] - 0.5 * depth * n, depth);
    else
      add(fb[0] + 0.5 * depth * n, depth);
    return true;
  }
  thread_local FeaturePoints corners, scratch;
  const double scale = 1.0 + std::abs(n.dot(fa[0])) + std::abs(n.dot(fb[0]));
  const double tolerance = 1e-9 * scale;  // touching to round-off still counts (at depth 0)
  std::size_t added = 0;
  if (fa.size() == 2 && fb.size() == 2) {
    const Vec3T<double> e = fa[1] - fa[0], f = fb[1] - fb[0];
    const double fLength = f.norm();
    if (e.cross(f).norm() > kFeatureSine * e.norm() * fLength || !(fLength > 0.0)) {
      const auto closest = closestPointsBetweenSegments<double>(fa[0], fa[1], fb[0], fb[1]);
      add(0.5 * (closest.onFirst + closest.onSecond), depth);
      return true;
    }
    // Parallel: a's segment clipped to the slab of b's, each end's depth
    // measured against b's line at the same place.
    const Vec3T<double> t = f / fLength;
    corners = fa;
    clipToHalfSpace(corners, t, t.dot(fb[1]), scratch);
    clipToHalfSpace(corners, Vec3T<double>(-t), -t.dot(fb[0]), scratch);
    for (const auto& x : corners) {
      const Vec3T<double> y = fb[0] + t * t.dot(x - fb[0]);
      const double d = n.dot(x - y);
      if (d < -tolerance) continue;
      add(x - 0.5 * d * n, d);
      ++added;
    }
    return added > 0;
  }
  // A polygon as the reference (b's first), the other feature incident.
  const bool referenceIsB = fb.size() >= 3;
  const FeaturePoints& reference = referenceIsB ? fb : fa;
  const Vec3T<double> outward = referenceIsB ? Vec3T<double>(-n) : n;  // out of the reference, toward the incident
  // The reference plane's normal (Newell), facing the incident shape.
  Vec3T<double> r = Vec3T<double>::Zero();
  for (std::size_t k = 0; k < reference.size(); ++k) r += reference[k].cross(reference[(k + 1) % reference.size()]);
  r = r.dot(outward) < 0.0 ? Vec3T<double>(-r) : r;
  r = r.norm() > 0.0 ? Vec3T<double>(r.normalized()) : outward;
  if (!(r.dot(outward) >= kFeatureCosine)) r = outward;
  corners = referenceIsB ? fa : fb;
  clipToPrism(corners, reference, outward, scratch);
  const double offset = r.dot(reference[0]), cosine = r.dot(outward);
  for (const auto& x : corners) {
    const double d = (offset - r.dot(x)) / cosine;  // below the reference plane, along n
    if (d < -tolerance) continue;
    add(x + 0.5 * d * outward, d);
    ++added;
  }
  return added > 0;
}

}  // namespace spook::detail
