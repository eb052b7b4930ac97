#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <type_traits>

#include <spook/collide/collider.hpp>
#include <spook/collide/detail/box_clipping.hpp>
#include <spook/collide/shapes/box.hpp>
#include <spook/collide/supporting_feature.hpp>

namespace spook {

namespace detail::box_box {

/// A box seen from box A's frame: center, axes (columns) and half extents.
template <Scalar S>
struct Placed {
  Vec3T<S> center;
  Mat3T<S> axes;
  Vec3T<S> half;

  /// Half-width of the box's projection onto the unit axis n.
  [[nodiscard]] S radius(const Vec3T<S>& n) const { return (axes.transpose() * n).cwiseAbs().dot(half); }
  /// The corner farthest along n (a zero component picks +).
  [[nodiscard]] Vec3T<S> corner(const Vec3T<S>& n) const {
    Vec3T<S> p = center;
    for (int k = 0; k < 3; ++k) p += axes.col(k) * (axes.col(k).dot(n) < S(0) ? -half[k] : half[k]);
    return p;
  }
};

/// The candidate separating axis of least penetration: `axis` points from A
/// toward B, `depth` is the overlap of the two projections on it (m).
/// kind 0: a face normal of A (index = axis of A); kind 1: a face normal of
/// B; kind 2: the cross product of A's edge `index / 3` and B's edge
/// `index % 3`.
template <Scalar S>
struct Axis {
  Vec3T<S> axis = Vec3T<S>::UnitZ();
  S depth = std::numeric_limits<S>::infinity();
  int kind = -1;
  int index = -1;
};

/// Edge–edge axes win only when their overlap is below that of the best face
/// axis divided by this factor: a resting box then keeps its face manifold
/// instead of flickering to a single edge point. 1.05 is the value of ODE's
/// dBoxBox, also used by Bullet and FCL.
inline constexpr double kEdgeBias = 1.05;

}  // namespace detail::box_box

/// Box–box contacts by the separating axis theorem (Gottschalk's 15 axes)
/// and face clipping, after ODE's dBoxBox:
///  - the overlap of the two boxes' projections onto each candidate axis
///    (3 + 3 face normals, 9 cross products of edge directions) is
///    r_A(n) + r_B(n) − |n·(c_B − c_A)|, r the projected half-width; a
///    positive gap on any axis separates the boxes, otherwise the axis of
///    least overlap gives the normal and the depth: the least edge axis
///    against the least face axis with kEdgeBias (dBoxBox also applies the
///    bias between two edge axes, so it may keep one up to 5 % deeper);
///  - on a face axis, the face of the other (incident) box most opposed to
///    it is clipped against the side planes of the reference face
///    (Sutherland–Hodgman), and every clipped corner below the reference
///    face becomes a contact with its own depth: up to 8 points;
///  - on an edge axis, one contact midway between the closest points of the
///    two edges, with the axis overlap as depth.
/// Boxes apart by less than the touching gap (detail::kTouchingGap of the
/// smaller box's size) touch, and so do the clipped corners within that gap
/// of the reference face (contacts of depth 0): a box resting on another
/// keeps its four corners when it tilts by round-off, or when float
/// coordinates cannot resolve its settling depth.
/// Boxes apart by less than the sink's speculative margin along a face
/// axis give the clipped corners with their gaps (gap points), unless they
/// meet flush along another face axis (kFlush): a box sliding off one tile
/// onto the next, level with it, would be stopped by the next one's side.
/// Apart along an edge axis (by 5% more than along any face axis), they
/// give none.
/// Cross products of near-parallel edges are skipped: their direction is
/// lost to round-off, and the face axes then separate the boxes anyway.
template <Scalar S>
struct Collider<BoxT<S>, BoxT<S>> {
  using Vec3 = spook::Vec3T<S>;
  using Mat3 = spook::Mat3T<S>;
  using Placed = detail::box_box::Placed<S>;
  using Axis = detail::box_box::Axis<S>;

  /// |a × b| below this (unit a and b, about √ε) skips the edge axis a × b:
  /// the direction error ε/|a × b| of keeping it then balances the depth
  /// error |a × b|·size of skipping it.
  static constexpr S kParallel = std::is_same_v<S, float> ? S(3e-4) : S(1.5e-8);
  /// Boxes that overlap along a face axis by at most this much of the
  /// smaller one's half-diagonal meet flush there (one on the level of the
  /// other's face: two tiles of a floor, a crate on the next tile): a gap
  /// beside them is a seam to slide over, which gives no gap points.
  static constexpr double kFlush = 1e-3;

  static void collide(const BoxT<S>& a, const TransformT<S>& X_WA, const BoxT<S>& b, const TransformT<S>& X_WB,
                      ContactSinkT<S>& sink) {
    // Everything in A's frame, where A is axis-aligned at the origin.
    const Mat3 R_WA = X_WA.linear();
    const Placed boxA{Vec3::Zero(), Mat3::Identity(), a.getHalfExtents()};
    const Placed boxB{R_WA.transpose() * (X_WB.translation() - X_WA.translation()), R_WA.transpose() * X_WB.linear(),
                      b.getHalfExtents()};
    const Vec3 d = boxB.center;
    const S gap = S(detail::kTouchingGap) * std::min(boxA.half.norm(), boxB.half.norm());
    const S reach = std::max(gap, sink.margin());  // the farthest apart that may still give points
    const S flush = S(kFlush) * std::min(boxA.half.norm(), boxB.half.norm());
    std::array<Vec3, 6> flushNormals;
    std::size_t flushCount = 0;

    Axis face, edge;
    // Overlap along the unit axis n; returns false when n separates them.
    auto consider = [&](const Vec3& n, int kind, int index, Axis& best) {
      const S along = n.dot(d);
      const S overlap = boxA.radius(n) + boxB.radius(n) - std::abs(along);
      if (overlap < -reach) return false;
      if (kind != 2 && overlap >= -gap && overlap <= flush) flushNormals[flushCount++] = n;
      if (overlap < best.depth) best = Axis{along < S(0) ? Vec3(-n) : n, overlap, kind, index};
      return true;
    };
    for (int i = 0; i < 3; ++i)
      if (!consider(boxA.axes.col(i), 0, i, face)) return;
    for (int j = 0; j < 3; ++j)
      if (!consider(boxB.axes.col(j), 1, j, face)) return;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        const Vec3 n = boxA.axes.col(i).cross(boxB.axes.col(j));
        const S length = n.norm();
        if (!(length > kParallel)) continue;
        if (!consider(n / length, 2, 3 * i + j, edge)) return;
      }
    }

    // A flush face runs across the least axis (kFlushAcrossCos). A box 2.2e-5 m
    // above a 40 m box, its bottom turned by 1.1e-6 rad, saw its own bottom
    // face axis overlap the ground by ~0 (the ground's 20 m half width
    // spans 2.2e-5 m more along it), took that for a seam and wrote no gap
    // points: a step of free fall into the ground (98 mm at h = 0.1 s).
    bool flushFace = false;
    for (std::size_t k = 0; k < flushCount; ++k)
      if (std::abs(flushNormals[k].dot(face.axis)) < S(kFlushAcrossCos)) flushFace = true;
    // Apart (gap points): only across a face, and not beside a flush face.
    // An edge axis wins with the bias and the gap, as below: where an edge
    // of one box is parallel to a face of the other (a tipping domino's top
    // edge against the next one's face), an edge axis is that face's normal
    // but for round-off or a slight skew, which decided between gap points
    // and none (dominoes then met 7 cm deep). The face's gap points are then
    // short of the edges' by at most 5%: the pair stops that much early.
    if (std::min(face.depth, edge.depth) < -gap &&
        (flushFace || edge.depth < S(detail::box_box::kEdgeBias) * face.depth - gap))
      return;

    auto emit = [&](const Vec3& point_A, const Vec3& normal_A, S depth) {
      sink.addSpeculative(Vec3(R_WA * point_A + X_WA.translation()), Vec3(R_WA * normal_A), depth, gap);
    };
    // The bias is relative; at depths below round-off (a light box resting
    // in float) only an edge axis shallower by more than the gap wins.
    if (edge.kind == 2 && S(detail::box_box::kEdgeBias) * edge.depth < face.depth && edge.depth + gap < face.depth) {
      emitEdge(boxA, boxB, edge, emit);
      return;
    }
    // The face case: reference face on the box that owns the axis.
    const bool onA = face.kind == 0;
    const Placed& reference = onA ? boxA : boxB;
    const Placed& incident = onA ? boxB : boxA;
    const Vec3 n = onA ? face.axis : Vec3(-face.axis);  // out of the reference face, toward the incident box
    if (emitFace(reference, face.index, n, incident, face.axis, face.depth, reach, emit) == 0) {
      // Round-off (or the face bias) left no clipped corner below the
      // reference face: one point at the incident box's deepest corner.
      const Vec3 deepest = incident.corner(-n);
      emit(Vec3(deepest + n * (S(0.5) * face.depth)), face.axis, face.depth);
    }
  }

 private:
  template <class Emit>
  static void emitEdge(const Placed& boxA, const Placed& boxB, const Axis& edge, Emit& emit) {
    const int i = edge.index / 3, j = edge.index % 3;
    const Vec3& n = edge.axis;
    // The edge of A farthest along n and the edge of B farthest along −n,
    // each through its midpoint.
    Vec3 midA = boxA.corner(n), midB = boxB.corner(-n);
    midA -= boxA.axes.col(i) * boxA.axes.col(i).dot(midA - boxA.center);
    midB -= boxB.axes.col(j) * boxB.axes.col(j).dot(midB - boxB.center);
    S s = S(0), t = S(0);
    detail::clampedLineClosest<S>(midA, boxA.axes.col(i), boxA.half[i], midB, boxB.axes.col(j), boxB.half[j], s, t);
    const Vec3 pointA = midA + boxA.axes.col(i) * s, pointB = midB + boxB.axes.col(j) * t;
    emit(Vec3(S(0.5) * (pointA + pointB)), n, edge.depth);
  }

  /// Clips the incident face against the reference face `axis` whose
  /// outward normal is n and writes the points below it, or above it by
  /// less than `reach`, with the normal normal_AB (from A toward B);
  /// returns how many.
  template <class Emit>
  static int emitFace(const Placed& reference, int axis, const Vec3& n, const Placed& incident, const Vec3& normal_AB,
                      S depthOfAxis, S reach, Emit& emit) {
    // Incident face: the face of the incident box most opposed to n.
    const Vec3 alignment = incident.axes.transpose() * n;
    int k = 0;
    alignment.cwiseAbs().maxCoeff(&k);
    const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
    const Vec3 faceCenter =
        incident.center - incident.axes.col(k) * (alignment[k] > S(0) ? incident.half[k] : -incident.half[k]);
    const Vec3 e1 = incident.axes.col(k1) * incident.half[k1], e2 = incident.axes.col(k2) * incident.half[k2];
    detail::ClipPolygon<S> polygon;
    polygon.push(faceCenter - e1 - e2);
    polygon.push(faceCenter + e1 - e2);
    polygon.push(faceCenter + e1 + e2);
    polygon.push(faceCenter - e1 + e2);

    // Side planes of the reference face: |(x − c)·t| <= h for its two
    // tangent axes t.
    for (const int side : {(axis + 1) % 3, (axis + 2) % 3}) {
      const Vec3 tangent = reference.axes.col(side);
      const S offset = tangent.dot(reference.center);
      polygon = detail::clipPolygon<S>(polygon, tangent, offset + reference.half[side]);
      polygon = detail::clipPolygon<S>(polygon, Vec3(-tangent), reference.half[side] - offset);
    }

    // Depth of each clipped corner below the reference face plane
    // n·x = n·c + h; the contact point is midway to that plane. No corner
    // lies deeper than the axis overlap but by round-off, which the min
    // removes.
    const S facePlane = n.dot(reference.center) + reference.half[axis];
    int written = 0;
    for (std::size_t m = 0; m < polygon.count; ++m) {
      const Vec3& x = polygon.points[m];
      const S depth = std::min(facePlane - n.dot(x), depthOfAxis);
      if (!(depth >= -reach)) continue;
      emit(Vec3(x + n * (S(0.5) * depth)), normal_AB, depth);
      ++written;
    }
    return written;
  }
};

}  // namespace spook
