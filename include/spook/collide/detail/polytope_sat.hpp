#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include <spook/collide/contact_sink.hpp>
#include <spook/collide/detail/polytope.hpp>
#include <spook/collide/detail/segment_distance.hpp>
#include <spook/collide/supporting_feature.hpp>
#include <spook/core/math.hpp>

namespace spook::detail {

/// The axis of least overlap of two polytopes, from a toward b.
struct SeparatingAxis {
  using S = double;
  enum Kind { FACE_OF_A, FACE_OF_B, EDGES };
  S depth = std::numeric_limits<S>::infinity();  // overlap of the projections on n (m)
  Vec3T<S> n = Vec3T<S>::UnitZ();
  Kind kind = FACE_OF_A;
  int first = -1, second = -1;  // the face, or the edge of a and the edge of b
  // Apart (depth < 0, within leastOverlap's reach): the most any axis
  // separates them, and whether a face axis across this one meets flush
  // (see leastOverlap).
  S widestGap = std::numeric_limits<S>::infinity();
  bool flushFace = false;
  S touching = 0;  // apart by less than this, they touch (m)
};

/// Whether edges with face normals (a, b) on one polytope and (c, d) on the
/// other make a face of their Minkowski difference: the arcs a–b and
/// −c–−d cross on the Gauss map (Gregorius, "The Separating Axis Test
/// between Convex Polyhedra", GDC 2013). Only such edge pairs can give the
/// least overlap, which prunes most of the E_a·E_b cross products.
[[nodiscard]] inline bool arcsCross(const Vec3T<double>& a, const Vec3T<double>& b, const Vec3T<double>& c,
                                    const Vec3T<double>& d) {
  const Vec3T<double> bxa = b.cross(a), dxc = d.cross(c);
  const double cba = c.dot(bxa), dba = d.dot(bxa), adc = a.dot(dxc), bdc = b.dot(dxc);
  return cba * dba < 0.0 && adc * bdc < 0.0 && cba * bdc > 0.0;
}

/// The separating axis theorem for polytopes: the penetration depth is the
/// least overlap f(n) = h_a(n) + h_b(−n) over the face normals of each and
/// the cross products of their edges (the face normals of the Minkowski
/// difference), both signs. Returns false as soon as an axis separates them
/// by more than `reach` (m). Within it, the least overlap is negative (apart);
/// best.widestGap is then the least overlap over every axis tested, and
/// best.flushFace tells whether some face axis at more than 45° to the
/// least one overlaps by no more than 1e-3 of the smaller solid's size (one
/// level with the other's face while apart from its side: a hull sliding
/// onto the next box tile, a box over a flat mesh beside the triangle it
/// rests on). A face axis nearly along the least one is no such seam: a
/// hull's bottom face tilted by 1e-4 rad over a large triangle overlaps it
/// by a fraction of a millimetre.
[[nodiscard]] inline bool leastOverlap(const Polytope& a, const Polytope& b, SeparatingAxis& best, double reach = 0.0) {
  using S = double;
  using Kind = SeparatingAxis::Kind;
  const auto overlap = [&](const Vec3T<S>& n) { return a.support(n).first + b.support(-n).first; };
  const S roundOff = S(64) * ScalarTraits<S>::epsilon() *
                     (S(1) + std::max(a.vertices[0].cwiseAbs().maxCoeff(), b.vertices[0].cwiseAbs().maxCoeff()));
  // An edge pair's axis replaces a face's only when it is shallower by more
  // than round-off, or, within 1e-3 rad of the face's normal, by more than
  // 1e-5 of the smaller polytope's size (the face's manifold then takes the
  // edges' depth): two edges lying in a face (a box
  // resting on a mesh triangle's edge) span that face's own normal, and a
  // resting box tilted by 1e-10 rad makes them shallower by 1e-11 m, where
  // their one contact point would replace the face's manifold (and a box
  // sliding over a mesh would drop a corner for a step).
  const auto diameter = [](const Polytope& p) {
    Vec3T<S> low = p.vertices[0], high = p.vertices[0];
    for (const Vec3T<S>& v : p.vertices) low = low.cwiseMin(v), high = high.cwiseMax(v);
    return (high - low).norm();
  };
  const S sizeA = diameter(a), sizeB = diameter(b);
  const S faceTolerance = roundOff + S(1e-5) * std::min(sizeA, sizeB);
  // The flush band, from the size of the smaller solid (not of a mesh
  // triangle, which may be far larger or smaller than what rests on it).
  S solidSize = std::min(a.twoSided ? std::numeric_limits<S>::infinity() : sizeA,
                         b.twoSided ? std::numeric_limits<S>::infinity() : sizeB);
  if (!(solidSize < std::numeric_limits<S>::infinity())) solidSize = std::min(sizeA, sizeB);
  const S flush = reach > S(0) ? S(1e-3) * solidSize : S(0);
  const S touching = roundOff + S(kTouchingGap) * solidSize;
  best.touching = touching;
  std::array<Vec3T<S>, 8> flushNormals;
  std::size_t flushCount = 0;
  // An edge pair's axis counts only where both edges are extreme along it
  // (they touch there); for other pairs it may still separate the shapes.
  const auto edgesSupport = [&](const Polytope::Edge& ea, const Polytope::Edge& eb, const Vec3T<S>& n) {
    const auto extreme = [&](const Polytope& p, const Polytope::Edge& e, const Vec3T<S>& d) {
      return std::max(d.dot(p.vertex(e.from)), d.dot(p.vertex(e.to))) >= p.support(d).first - roundOff;
    };
    return extreme(a, ea, n) && extreme(b, eb, -n);
  };
  const auto consider = [&](const Vec3T<S>& n, Kind kind, int first, int second) {
    const S f = overlap(n);
    if (f < -reach) return false;
    best.widestGap = std::min(best.widestGap, f);
    if (kind != Kind::EDGES) {
      if (f <= flush && f >= -touching && flushCount < flushNormals.size()) flushNormals[flushCount++] = n;
      if (f < best.depth) best = {f, n, kind, first, second, best.widestGap, false, touching};
      return true;
    }
    const bool againstFace = best.kind != Kind::EDGES;
    const bool nearFace = againstFace && n.dot(best.n) >= S(1) - S(5e-7);
    const bool faceHeld = againstFace && f >= best.depth - (nearFace ? faceTolerance : roundOff);
    const auto supported = [&] {
      return edgesSupport(a.edges[std::size_t(first)], b.edges[std::size_t(second)], n);
    };
    if (f < best.depth) {
      if (!faceHeld) {
        if (supported()) best = {f, n, kind, first, second, best.widestGap, false, touching};
      } else if (nearFace && supported()) {
        best.depth = f;  // the face's manifold carries the edges' exact depth
      }
    }
    return true;
  };
  for (std::size_t i = 0; i < a.faces.size(); ++i) {
    const Vec3T<S>& n = a.faces[i].normal;
    if (!consider(n, Kind::FACE_OF_A, int(i), -1)) return false;
    if (a.twoSided && !consider(-n, Kind::FACE_OF_A, int(i), -1)) return false;
  }
  for (std::size_t j = 0; j < b.faces.size(); ++j) {
    const Vec3T<S>& m = b.faces[j].normal;
    if (!consider(-m, Kind::FACE_OF_B, int(j), -1)) return false;
    if (b.twoSided && !consider(m, Kind::FACE_OF_B, int(j), -1)) return false;
  }
  // Edge pairs within round-off of parallel span no face of their own.
  const S parallel = S(1e3) * ScalarTraits<S>::epsilon();
  for (std::size_t i = 0; i < a.edges.size(); ++i) {
    const auto& ea = a.edges[i];
    const Vec3T<S> u = a.edgeVector(ea);
    for (std::size_t j = 0; j < b.edges.size(); ++j) {
      const auto& eb = b.edges[j];
      if (ea.right >= 0 && eb.right >= 0 &&
          !arcsCross(a.faces[std::size_t(ea.left)].normal, a.faces[std::size_t(ea.right)].normal,
                        Vec3T<S>(-b.faces[std::size_t(eb.left)].normal),
                        Vec3T<S>(-b.faces[std::size_t(eb.right)].normal)))
        continue;
      const Vec3T<S> v = b.edgeVector(eb);
      Vec3T<S> n = u.cross(v);
      const S length = n.norm();
      if (!(length > parallel * u.norm() * v.norm())) continue;
      n /= length;
      if (!consider(n, Kind::EDGES, int(i), int(j)) || !consider(-n, Kind::EDGES, int(i), int(j))) return false;
    }
  }
  for (std::size_t k = 0; k < flushCount; ++k)
    if (std::abs(flushNormals[k].dot(best.n)) < S(kFlushAcrossCos)) best.flushFace = true;
  return best.depth < std::numeric_limits<S>::infinity();
}

/// The face of `p` whose outward normal points most against `r` (for a
/// two-sided face, the side that does), as a corner loop; a segment gives
/// its two ends.
inline void incidentFeature(const Polytope& p, const Vec3T<double>& r, std::vector<Vec3T<double>>& corners) {
  using S = double;
  corners.clear();
  if (p.faces.empty()) {
    corners = p.vertices;
    return;
  }
  std::size_t best = 0;
  S lowest = std::numeric_limits<S>::infinity();
  for (std::size_t f = 0; f < p.faces.size(); ++f) {
    const S alignment = p.twoSided ? -std::abs(p.faces[f].normal.dot(r)) : p.faces[f].normal.dot(r);
    if (alignment < lowest) lowest = alignment, best = f;
  }
  for (const int k : p.faces[best].loop) corners.push_back(p.vertex(k));
}

/// Clips a polygon (or a segment, two corners) to the half-space
/// s·x <= offset, Sutherland–Hodgman.
inline void clipToHalfSpace(std::vector<Vec3T<double>>& corners, const Vec3T<double>& s, double offset,
                            std::vector<Vec3T<double>>& scratch) {
  using S = double;
  scratch.clear();
  const std::size_t count = corners.size();
  const std::size_t edges = count == 2 ? 1 : count;
  for (std::size_t i = 0; i < edges; ++i) {
    const Vec3T<S>& p = corners[i];
    const Vec3T<S>& q = corners[(i + 1) % count];
    const S dp = s.dot(p) - offset, dq = s.dot(q) - offset;
    if (dp <= S(0)) scratch.push_back(p);
    if ((dp < S(0) && dq > S(0)) || (dp > S(0) && dq < S(0))) scratch.push_back(p + (q - p) * (dp / (dp - dq)));
    if (count == 2 && dq <= S(0)) scratch.push_back(q);
  }
  corners.swap(scratch);
}

/// The face manifold of a reference face (outward normal r, toward the
/// incident polytope): the incident polytope's face most against r (or its
/// segment) is clipped to the reference face's side planes
/// (Sutherland–Hodgman), and each clipped corner below the reference plane
/// is a contact at its own depth (at most `depth`), midway to the plane,
/// with normal n: a full manifold, as for box–box. Where clipping keeps no
/// corner as deep as `depth` (the deepest one hangs over the reference
/// face's rim) a contact at `depth` is added where the clipped feature comes
/// nearest to that corner, so that the deepest contact is always the
/// penetration depth of the pair. Corners above the reference face by less
/// than `reach` (m) are gap points (negative depth).
template <Scalar T>
void faceContacts(const Polytope& reference, const std::vector<int>& loop, const Vec3T<double>& r,
                  const Polytope& incident, const Vec3T<double>& n, double depth, ContactSinkT<T>& sink,
                  double reach = 0.0) {
  using S = double;
  S tolerance = S(0);
  const auto add = [&](const Vec3T<S>& point, S pointDepth) {
    sink.addSpeculative(point.template cast<T>(), n.template cast<T>(), T(pointDepth), T(tolerance));
  };
  const S planeOffset = r.dot(reference.vertex(loop[0]));
  thread_local std::vector<Vec3T<S>> corners, scratch;
  incidentFeature(incident, r, corners);
  Vec3T<S> centroid = Vec3T<S>::Zero();
  for (const int k : loop) centroid += reference.vertex(k);
  centroid /= S(loop.size());
  for (std::size_t k = 0; k < loop.size() && !corners.empty(); ++k) {
    const Vec3T<S>& p = reference.vertex(loop[k]);
    const Vec3T<S> edge = reference.vertex(loop[(k + 1) % loop.size()]) - p;
    Vec3T<S> side = edge.cross(r);
    if (side.dot(centroid - p) > S(0)) side = -side;
    const S length = side.norm();
    if (!(length > S(0))) continue;  // a repeated corner of a degenerate face
    side /= length;
    clipToHalfSpace(corners, side, side.dot(p), scratch);
  }
  S deepest = -std::numeric_limits<S>::infinity();
  tolerance = S(64) * ScalarTraits<S>::epsilon() * (S(1) + std::abs(planeOffset));
  for (const Vec3T<S>& x : corners) {
    const S pointDepth = std::min(planeOffset - r.dot(x), depth);
    if (pointDepth < -tolerance - reach) continue;
    add(x + r * (S(0.5) * pointDepth), pointDepth);
    deepest = std::max(deepest, pointDepth);
  }
  if (deepest < depth - tolerance * S(16)) {
    // The deepest point of the incident polytope is off the reference face:
    // the contact at the least overlap goes where the clipped feature comes
    // nearest to it, on the reference face (never at that point itself,
    // which may lie metres away on a large mesh triangle under a small
    // shape), or at that point when nothing is left after clipping.
    const Vec3T<S>& x = incident.vertex(incident.support(-r).second);
    Vec3T<S> at = x;
    S nearest = std::numeric_limits<S>::infinity();
    for (const Vec3T<S>& c : corners)
      if (const S d = (c - x).squaredNorm(); d < nearest) nearest = d, at = c + r * (planeOffset - r.dot(c));
    add(at - r * (S(0.5) * depth), depth);
  }
}

/// The face of `p` whose outward normal (either side of a two-sided face)
/// lies within the feature angle of `d`, the best aligned; -1 when none.
[[nodiscard]] inline int faceAlong(const Polytope& p, const Vec3T<double>& d, Vec3T<double>& normal) {
  int best = -1;
  double alignment = kSupportingFeatureCos;
  for (std::size_t f = 0; f < p.faces.size(); ++f) {
    const Vec3T<double>& m = p.faces[f].normal;
    const double c = p.twoSided ? std::abs(m.dot(d)) : m.dot(d);
    if (c >= alignment) alignment = c, best = int(f), normal = m.dot(d) >= 0.0 ? m : Vec3T<double>(-m);
  }
  return best;
}

/// Contacts of two overlapping polytopes along their axis of least overlap.
///
/// Face against anything: the face manifold (faceContacts) of that face.
/// Edge against edge: when a face of either solid polytope lies within the
/// feature angle of the axis and its own overlap is the least to within
/// 1e-4 of the thickness (a face resting across the other's edge: a hull
/// across the seam of two boxes) the manifold of that face, with the axis
/// as normal and every depth at most the least overlap; else one point,
/// midway between the two edges' closest points, at the least overlap; two,
/// at the ends of their common range, for edges within the feature angle
/// of parallel.
template <Scalar T>
void polytopeContacts(const Polytope& a, const Polytope& b, const SeparatingAxis& axis, ContactSinkT<T>& sink,
                      double reach = 0.0) {
  using S = double;
  const auto add = [&](const Vec3T<S>& point, S depth) {
    sink.add(point.template cast<T>(), axis.n.template cast<T>(), T(depth));
  };
  const Vec3T<S>& n = axis.n;
  if (axis.kind != SeparatingAxis::EDGES) {
    const bool onA = axis.kind == SeparatingAxis::FACE_OF_A;
    const Polytope& reference = onA ? a : b;
    const Vec3T<S> r = onA ? n : Vec3T<S>(-n);  // the reference face's outward normal, toward the incident polytope
    faceContacts(reference, reference.faces[std::size_t(axis.first)].loop, r, onA ? b : a, n, axis.depth, sink, reach);
    return;
  }
  if (axis.depth < -axis.touching) return;  // apart across edges: no gap points
  // Not for mesh triangles: a box sliding across a mesh's internal edges
  // then bumps harder (|v_z| 0.12 -> 0.5 m/s at 3 m/s on 1 m cells). A
  // face's overlap within 1e-4 of the thinner polytope's thickness of the
  // least is a tilt of ~1e-4 rad across it; further off, the edges touch
  // beside the face and its clipped corners would lie outside the overlap
  // (0.5 m in random poses).
  Vec3T<S> normalA, normalB;
  const bool solids = !a.twoSided && !b.twoSided;
  const auto nearlyLeast = [&](const Vec3T<S>& m) {
    const S thickness = std::min(a.support(m).first + a.support(-m).first, b.support(m).first + b.support(-m).first);
    return a.support(m).first + b.support(-m).first <= axis.depth + S(1e-4) * thickness;
  };
  int faceA = solids ? faceAlong(a, n, normalA) : -1;
  int faceB = solids ? faceAlong(b, Vec3T<S>(-n), normalB) : -1;
  if (faceA >= 0 && !nearlyLeast(normalA)) faceA = -1;
  if (faceB >= 0 && !nearlyLeast(Vec3T<S>(-normalB))) faceB = -1;
  if (faceA >= 0 && (faceB < 0 || normalA.dot(n) >= -normalB.dot(n))) {
    faceContacts(a, a.faces[std::size_t(faceA)].loop, normalA, b, n, axis.depth, sink);
    return;
  }
  if (faceB >= 0) {
    faceContacts(b, b.faces[std::size_t(faceB)].loop, normalB, a, n, axis.depth, sink);
    return;
  }
  const auto& ea = a.edges[std::size_t(axis.first)];
  const auto& eb = b.edges[std::size_t(axis.second)];
  const Vec3T<S> p = a.vertex(ea.from), u = a.vertex(ea.to) - p;
  const Vec3T<S> q = b.vertex(eb.from), v = b.vertex(eb.to) - q;
  if (u.cross(v).norm() <= S(kSupportingFeatureSin) * u.norm() * v.norm()) {
    // Edges within the feature angle of parallel touch along a line (their
    // closest points are undetermined): its two ends, where the edges'
    // ranges along u overlap, midway across to b's edge.
    const S uu = u.squaredNorm(), s0 = u.dot(q - p) / uu, s1 = u.dot(q + v - p) / uu;
    const S from = std::max(S(0), std::min(s0, s1)), to = std::min(S(1), std::max(s0, s1));
    const auto addAt = [&](S s) {
      const Vec3T<S> onA = p + s * u;
      const S t = std::clamp(v.dot(onA - q) / v.squaredNorm(), S(0), S(1));
      add(S(0.5) * (onA + q + t * v), axis.depth);
    };
    if (from < to) {
      addAt(from);
      addAt(to);
    } else {
      addAt(std::clamp(S(0.5) * (from + to), S(0), S(1)));
    }
    return;
  }
  const auto closest = closestPointsBetweenSegments<S>(p, a.vertex(ea.to), q, b.vertex(eb.to));
  add(S(0.5) * (closest.onFirst + closest.onSecond), axis.depth);
}

/// Contacts of two polytopes (from a toward b), none when an axis separates
/// them. With `gapPoints`, polytopes apart by less than the sink's margin
/// across a face give that face's manifold as gap points (negative depth),
/// as box–box does: none across edges (or where an edge axis separates them
/// by 5% more than the face), and none where a face axis meets flush (a
/// seam between level faces, where gap points beside it would be ghost
/// contacts).
template <Scalar T>
void collidePolytopes(const Polytope& a, const Polytope& b, ContactSinkT<T>& sink, bool gapPoints = false) {
  const double reach = gapPoints ? double(sink.margin()) : 0.0;
  SeparatingAxis axis;
  if (!leastOverlap(a, b, axis, reach)) return;
  if (axis.depth < -axis.touching && (axis.flushFace || axis.widestGap < 1.05 * axis.depth - axis.touching)) return;
  polytopeContacts(a, b, axis, sink, reach);
}

}  // namespace spook::detail
