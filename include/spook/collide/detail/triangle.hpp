#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>

#include <spook/collide/bounding_box.hpp>
#include <spook/collide/detail/aabb_tree.hpp>
#include <spook/collide/detail/segment_distance.hpp>
#include <spook/collide/supporting_feature.hpp>
#include <spook/core/math.hpp>

namespace spook::detail {

/// One triangle of a mesh or height field, as a convex shape for the
/// colliders: vertices in the mesh frame, counter-clockwise seen from the
/// outside (the solid side is behind the face).
template <Scalar S>
struct Triangle {
  using Vec3 = spook::Vec3T<S>;
  std::array<Vec3, 3> v;

  [[nodiscard]] Vec3 support(const Vec3& d) const {
    const S a = v[0].dot(d), b = v[1].dot(d), c = v[2].dot(d);
    return a >= b ? (a >= c ? v[0] : v[2]) : (b >= c ? v[1] : v[2]);
  }
  /// The whole triangle when its plane is across `d` within the feature
  /// angle (from either side), else the edge across `d`, else the corner.
  void supportingFeature(const Vec3& d, SupportingFeatureT<S>& out) const {
    out.count = 0;
    const S length = d.norm();
    const Vec3 area = (v[1] - v[0]).cross(v[2] - v[0]);
    if (length > S(0) && std::abs(area.dot(d)) >= S(kSupportingFeatureCos) * area.norm() * length) {
      for (const Vec3& p : v) out.add(p);
      return;
    }
    const Vec3 top = support(d);
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = v[k];
      const Vec3& q = v[(k + 1) % 3];
      if ((p == top || q == top) && std::abs((q - p).dot(d)) <= S(kSupportingFeatureSin) * (q - p).norm() * length) {
        out.add(p);
        out.add(q);
        return;
      }
    }
    out.add(top);
  }
  [[nodiscard]] Vec3 getCenterOfVolume() const { return (v[0] + v[1] + v[2]) / S(3); }
  [[nodiscard]] BoundingBoxT<S> getBoundingBox() const {
    return {v[0].cwiseMin(v[1]).cwiseMin(v[2]), v[0].cwiseMax(v[1]).cwiseMax(v[2])};
  }
  /// Unit outward normal (+z for a degenerate triangle).
  [[nodiscard]] Vec3 normal() const {
    const Vec3 n = (v[1] - v[0]).cross(v[2] - v[0]);
    const S length = n.norm();
    return length > S(0) ? Vec3(n / length) : Vec3::UnitZ();
  }
  /// The edges p lies beside, seen along the unit `front` (the winding's
  /// normal): bit k for edge k (corner k to k + 1); 0 where p is over the
  /// triangle (on an edge counts as over).
  [[nodiscard]] unsigned edgesBeside(const Vec3& p, const Vec3& front) const {
    unsigned edges = 0;
    for (std::size_t k = 0; k < 3; ++k)
      if ((v[(k + 1) % 3] - v[k]).cross(p - v[k]).dot(front) < S(0)) edges |= 1u << k;
    return edges;
  }
};

/// The point of triangle t closest to p: by Voronoi regions (Ericson,
/// Real-Time Collision Detection, §5.1.5) for a proper triangle; over its
/// three edges for a degenerate one (repeated or collinear corners), where
/// the region tests would divide round-off by round-off.
template <Scalar S>
[[nodiscard]] Vec3T<S> closestOnTriangle(const Triangle<S>& t, const Vec3T<S>& p, bool& onFace) {
  const Vec3T<S>&a = t.v[0], &b = t.v[1], &c = t.v[2];
  const Vec3T<S> ab = b - a, ac = c - a;
  const S longest2 = std::max({ab.squaredNorm(), ac.squaredNorm(), (c - b).squaredNorm()});
  onFace = false;
  if (!(ab.cross(ac).norm() > S(64) * ScalarTraits<S>::epsilon() * longest2)) {
    Vec3T<S> best = closestPointOnSegment<S>(a, b, p);
    for (const Vec3T<S>& q : {closestPointOnSegment<S>(b, c, p), closestPointOnSegment<S>(c, a, p)})
      if ((q - p).squaredNorm() < (best - p).squaredNorm()) best = q;
    return best;
  }
  const Vec3T<S> ap = p - a, bp = p - b, cp = p - c;
  const S d1 = ab.dot(ap), d2 = ac.dot(ap), d3 = ab.dot(bp), d4 = ac.dot(bp), d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d1 <= S(0) && d2 <= S(0)) return a;
  if (d3 >= S(0) && d4 <= d3) return b;
  if (d6 >= S(0) && d5 <= d6) return c;
  const S vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
  if (vc <= S(0) && d1 >= S(0) && d3 <= S(0)) return a + ab * (d1 / (d1 - d3));
  if (vb <= S(0) && d2 >= S(0) && d6 <= S(0)) return a + ac * (d2 / (d2 - d6));
  if (va <= S(0) && (d4 - d3) >= S(0) && (d5 - d6) >= S(0)) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  onFace = true;
  const S denominator = va + vb + vc;
  return a + ab * (vb / denominator) + ac * (vc / denominator);
}

/// Folds flatter than this between two triangles of a mesh make an inactive
/// edge (radians, 5°, as Jolt's default active-edge threshold).
inline constexpr double kActiveEdgeAngle = 0.087266462599716474;

/// Contacts that two triangles of a mesh find with normals closer than this
/// (radians, 1°) and points closer than 4·kFeatureTilt of the shape's size
/// are one contact on their shared edge, kept once.
inline constexpr double kAlikeNormalAngle = 0.017453292519943295;

/// Whether the edge from `from` to `to` of a triangle with unit normal n1,
/// shared with a neighbour of unit normal n2, is active: a contact found on
/// an active edge keeps its own normal; one on an inactive edge takes the
/// face's (activeEdgeNormals). Two bits: seen from the front (bit 0) and
/// from behind (bit 1). An edge is active from a side where the surface
/// folds away (convex seen from that side) by more than kActiveEdgeAngle;
/// a back-to-back pair (a sheet's rim) is active from both; a fold toward
/// the viewer (concave) or a flat one is not, since the neighbour's own face
/// carries that contact. A zero normal (a degenerate triangle) makes the
/// edge active.
template <Scalar S>
[[nodiscard]] unsigned edgeActivity(const Vec3T<S>& n1, const Vec3T<S>& from, const Vec3T<S>& to,
                                    const Vec3T<S>& n2) {
  if (!(n1.squaredNorm() > S(0.5) && n2.squaredNorm() > S(0.5))) return 0b11;
  const S cosine = n1.dot(n2);
  if (cosine > S(std::cos(kActiveEdgeAngle))) return 0b00;
  if (cosine < -S(std::cos(kActiveEdgeAngle))) return 0b11;
  const Vec3T<S> outward = (to - from).cross(n1);  // in the face's plane, away from the face
  return n2.dot(outward) > S(0) ? 0b01 : 0b10;
}

/// The three edges' activity (edgeActivity; edge k runs from corner k to
/// corner k + 1) of a triangle with unit normal n, from its neighbours' unit
/// normals (null: no neighbour, an active rim): bits 0-2 seen from the
/// front, bits 3-5 from behind.
template <Scalar S>
[[nodiscard]] std::uint8_t activeEdges(const std::array<Vec3T<S>, 3>& v, const Vec3T<S>& n,
                                       const std::array<const Vec3T<S>*, 3>& neighbours) {
  unsigned mask = 0;
  for (unsigned k = 0; k < 3; ++k) {
    const unsigned bits = neighbours[k] ? edgeActivity<S>(n, v[k], v[(k + 1) % 3], *neighbours[k]) : 0b11u;
    mask |= (bits & 1u) << k | (bits >> 1) << (k + 3);
  }
  return static_cast<std::uint8_t>(mask);
}

/// Contact normals on a mesh triangle held to its active edges (Jolt's
/// active edges, Bullet's btAdjustInternalEdgeContacts solve the same):
/// a contact whose normal is not the face's keeps it only where it lies on
/// an active edge, seen from the side the shape is on; else, inside the
/// face or on an edge between two triangles of a flat region, it takes the
/// face's normal and keeps its depth (the overlap along the face's normal
/// is the larger one, so the depth errs low). Otherwise a body sliding over
/// a flat mesh meets each triangle's edge sideways and bumps. A contact
/// lies midway between the surfaces, so one within its depth of an edge
/// counts as on that edge. `points` hold normals from the shape toward the
/// mesh; `active` is activeEdges()' mask. A surface solid behind its faces
/// (a height field) is always seen from the front: a shape sunk through a
/// face is pushed back out of the solid, never on through it. Where a
/// normal runs along the face, the side of the shape's center
/// (`shapeCenter`, world) is the side it is seen from. A gap point (negative
/// depth) whose normal lies nearer the face's plane than its normal (more
/// than 45° off it) is dropped instead: its gap runs along the face, beside
/// the triangle, and the triangle the shape lies over gives the gap there
/// (the triangles beside a box over a fine mesh claimed 3-9 cm along the
/// face normal where the box was 1 cm above it).
template <Scalar S, class Points>
void activeEdgeNormals(const Triangle<S>& t_W, std::uint8_t active, Points& points, bool solidBehind,
                       const Vec3T<S>& shapeCenter) {
  if (active == 0b111111) return;
  const Vec3T<S> e[3] = {t_W.v[1] - t_W.v[0], t_W.v[2] - t_W.v[1], t_W.v[0] - t_W.v[2]};
  const Vec3T<S> area = e[0].cross(-e[2]);
  const S longest = std::sqrt(std::max({e[0].squaredNorm(), e[1].squaredNorm(), e[2].squaredNorm()}));
  if (!(area.norm() > S(64) * ScalarTraits<S>::epsilon() * longest * longest)) return;
  const Vec3T<S> f = area.normalized();
  std::size_t kept = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    auto& c = points[i];
    // Even a normal 0.5° off the face's makes a body sliding at v over the
    // edge approach it at v·sin(0.5°), and the contact kicks it up.
    S front = solidBehind ? S(1) : -c.normal.dot(f);
    // A normal along the face (a cap against the triangle's edge, a side
    // against its corner) tells the side by the sign of round-off: the
    // shape's center does. A cylinder lying on a fine flat trimesh, its cap
    // over a corner, got a point pushing it into the mesh and fell 6 cm
    // deep at h = 0.1 s.
    if (std::abs(front) < S(kSupportingFeatureSin)) front = f.dot(shapeCenter - t_W.v[0]);
    const unsigned seen = front >= S(0) ? active & 7u : active >> 3;
    if (seen == 0b111) {
      points[kept++] = c;
      continue;
    }
    S distance[3];
    bool inside = true;
    for (int k = 0; k < 3; ++k) {
      const Vec3T<S> toPoint = c.point - t_W.v[k];
      const S along = std::clamp(toPoint.dot(e[k]) / e[k].squaredNorm(), S(0), S(1));
      distance[k] = (toPoint - e[k] * along).norm();
      if (e[k].cross(toPoint).dot(f) < S(0)) inside = false;
    }
    const S nearest = std::min({distance[0], distance[1], distance[2]});
    const S slack = c.depth + S(1e-4) * longest;
    unsigned on = 0;
    if (!inside || nearest <= slack)
      for (unsigned k = 0; k < 3; ++k)
        if (distance[k] <= nearest + slack) on |= 1u << k;
    if ((on & seen) == 0) {
      if (c.depth < S(0) && std::abs(c.normal.dot(f)) < S(std::numbers::sqrt2 / 2)) continue;
      c.normal = front >= S(0) ? Vec3T<S>(-f) : f;
    }
    points[kept++] = c;
  }
  points.resize(kept);
}

}  // namespace spook::detail
