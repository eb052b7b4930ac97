#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include <spook/core/math.hpp>

namespace spook::detail {

/// The contact manifold of two convex shapes in contact along a normal,
/// from their supporting features (the part of each shape that is extreme
/// along the normal: a point, an edge or a face), as Jolt's
/// ManifoldBetweenTwoFaces and Box2D's b2ClipPolygons build it: both
/// features are projected onto the contact plane, one is clipped against
/// the other (Sutherland–Hodgman), and each corner of the overlap is a
/// contact point, its depth the distance between the two features above
/// it. Works in double, in the plane spanned by t1, t2 ⟂ n.
struct FeatureClipping {
  using Vec2 = Eigen::Vector2d;
  using Vec3 = Vec3T<double>;

  /// A round face: the disc about `center` with unit normal `axis`.
  struct Disc {
    Vec3 center = Vec3::Zero();
    Vec3 axis = Vec3::UnitZ();
    double radius = 0.0;  // m; 0: not a disc
  };
  /// A supporting feature: world points on it (m), the size below which
  /// two of them are the same point (the spread that sampling a curved
  /// surface leaves), and for a round face its disc (the points then an
  /// inscribed polygon of its rim).
  struct Feature {
    std::vector<Vec3> points;
    double merge = 0.0;
    Disc disc = {};
  };
  struct Contact {
    Vec3 point;    // world, halfway between the features (m)
    double depth;  // m
  };

  Vec3 n, t1, t2;

  explicit FeatureClipping(const Vec3& normal)
      : n(normal), t1(normal.unitOrthogonal()), t2(normal.cross(normal.unitOrthogonal())) {}

  /// The overlap's corners as contacts, for features `top` (of the shape
  /// behind the normal, its points highest along n) and `bottom` (of the
  /// shape ahead, lowest along n) and the penetration depth along n, which
  /// bounds every contact's. A corner apart by less than `touching` (m)
  /// touches (depth 0): a resting body tilted by round-off keeps its whole
  /// manifold, where dropping the corner that lifted by 1e-7 m would let
  /// that end fall freely for a step. Empty when the projections do not
  /// overlap (the caller then places one contact by itself).
  [[nodiscard]] std::vector<Contact> contacts(const Feature& top, const Feature& bottom, double depth,
                                              double touching = 0.0) const {
    const double merge = std::min(top.merge, bottom.merge);
    const std::vector<Vec2> a = hull(project(top.points), top.merge);
    const std::vector<Vec2> b = hull(project(bottom.points), bottom.merge);
    std::vector<Vec2> overlap;
    if (b.size() >= 3)
      overlap = clip(a, b);
    else if (a.size() >= 3)
      overlap = clip(b, a);
    else
      overlap = crossing(a, b, merge);
    // A round face's polygon is inscribed in its rim: the other feature's
    // corners inside the disc, and its edges' crossings with the rim, are
    // part of the overlap too.
    addInsideDisc(top.disc, b, overlap);
    addInsideDisc(bottom.disc, a, overlap);
    overlap = hull(overlap, merge);
    // Depths from the heights of the features over each corner, shifted so
    // that the deepest is the penetration depth (the features are sampled,
    // their heights fitted); a deepest corner farther than the sampling
    // size from it means the overlap is not where the shapes penetrate most
    // (sampled features that miss a part of the true ones): no manifold.
    const HeightPlane topHeight(top.points, *this), bottomHeight(bottom.points, *this);
    std::vector<Contact> out;
    double deepest = -std::numeric_limits<double>::infinity();
    for (const Vec2& v : overlap) {
      const double high = topHeight.at(v), low = bottomHeight.at(v);
      out.push_back({v.x() * t1 + v.y() * t2 + 0.5 * (high + low) * n, high - low});
      deepest = std::max(deepest, high - low);
    }
    if (!(std::abs(deepest - depth) <= std::max(top.merge, bottom.merge))) return {};
    for (Contact& c : out) c.depth = std::min(c.depth + (depth - deepest), depth);
    std::erase_if(out, [&](const Contact& c) { return !(c.depth >= -touching); });
    for (Contact& c : out) c.depth = std::max(c.depth, 0.0);
    return out;
  }

  /// One contact of the given depth where two features that do not overlap
  /// on the contact plane come nearest there: midway between the closest
  /// points of their projected hulls, and between their heights over it.
  [[nodiscard]] Contact nearest(const Feature& top, const Feature& bottom, double depth) const {
    const std::vector<Vec2> a = hull(project(top.points), top.merge);
    const std::vector<Vec2> b = hull(project(bottom.points), bottom.merge);
    Vec2 onA = a.front(), onB = b.front();
    double closest = std::numeric_limits<double>::infinity();
    const auto consider = [&](const Vec2& p, const std::vector<Vec2>& polygon, bool pOnA) {
      for (std::size_t k = 0; k < polygon.size(); ++k) {
        const Vec2 q = polygon[k], edge = polygon[(k + 1) % polygon.size()] - q;
        const double length2 = edge.squaredNorm();
        const double t = length2 > 0.0 ? std::clamp(edge.dot(p - q) / length2, 0.0, 1.0) : 0.0;
        const Vec2 x = q + t * edge;
        if (const double d = (x - p).squaredNorm(); d < closest) {
          closest = d;
          onA = pOnA ? p : x;
          onB = pOnA ? x : p;
        }
      }
    };
    for (const Vec2& p : a) consider(p, b, true);
    for (const Vec2& p : b) consider(p, a, false);
    const Vec2 v = 0.5 * (onA + onB);
    const double high = HeightPlane(top.points, *this).at(v), low = HeightPlane(bottom.points, *this).at(v);
    return {v.x() * t1 + v.y() * t2 + 0.5 * (high + low) * n, depth};
  }

 private:
  [[nodiscard]] Vec2 flat(const Vec3& p) const { return {t1.dot(p), t2.dot(p)}; }

  /// Appends the points of `polygon` (a point, a segment or a polygon on the
  /// contact plane) inside the projection of `disc`, and the crossings of
  /// its edges with the rim's, each lifted along n onto the disc's plane.
  void addInsideDisc(const Disc& disc, const std::vector<Vec2>& polygon, std::vector<Vec2>& out) const {
    const double across = disc.axis.dot(n);
    if (!(disc.radius > 0.0) || polygon.empty() || !(std::abs(across) > 0.5)) return;
    const auto lifted = [&](const Vec2& v) {  // from the disc's center, in its plane
      const Vec3 p = v.x() * t1 + v.y() * t2 - disc.center;
      return Vec3(p - (disc.axis.dot(p) / across) * n);
    };
    const double r2 = disc.radius * disc.radius;
    for (const Vec2& v : polygon)
      if (lifted(v).squaredNorm() <= r2) out.push_back(v);
    const std::size_t edges = polygon.size() == 1 ? 0 : polygon.size() == 2 ? 1 : polygon.size();
    for (std::size_t k = 0; k < edges; ++k) {
      const Vec2 p = polygon[k], q = polygon[(k + 1) % polygon.size()];
      const Vec3 d = lifted(p), e = lifted(q) - d;
      // |d + t e|² = r²: e·e t² + 2 d·e t + d·d − r² = 0.
      const double a = e.squaredNorm(), b = d.dot(e), c = d.squaredNorm() - r2, discriminant = b * b - a * c;
      if (!(a > 0.0) || discriminant < 0.0) continue;
      for (const double sign : {-1.0, 1.0})
        if (const double t = (-b + sign * std::sqrt(discriminant)) / a; t > 0.0 && t < 1.0) out.push_back(p + t * (q - p));
    }
  }

  [[nodiscard]] std::vector<Vec2> project(const std::vector<Vec3>& points) const {
    std::vector<Vec2> out;
    out.reserve(points.size());
    for (const Vec3& p : points) out.push_back(flat(p));
    return out;
  }

  static double cross(const Vec2& o, const Vec2& a, const Vec2& b) {
    return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
  }

  /// Counter-clockwise convex hull (Andrew's monotone chain) without points
  /// within `merge` of one kept and without corners within `merge` of the
  /// line through their neighbours: 1 point, 2 (a segment) or a polygon.
  static std::vector<Vec2> hull(std::vector<Vec2> points, double merge) {
    std::sort(points.begin(), points.end(),
              [](const Vec2& p, const Vec2& q) { return p.x() < q.x() || (p.x() == q.x() && p.y() < q.y()); });
    std::vector<Vec2> unique;
    for (const Vec2& p : points)
      if (std::none_of(unique.begin(), unique.end(), [&](const Vec2& q) { return (p - q).norm() <= merge; }))
        unique.push_back(p);
    if (unique.size() < 3) return unique;
    std::vector<Vec2> chain(2 * unique.size());
    std::size_t k = 0;
    const auto turnsLeft = [&](const Vec2& p) {
      return cross(chain[k - 2], chain[k - 1], p) > merge * (chain[k - 1] - chain[k - 2]).norm();
    };
    for (const Vec2& p : unique) {
      while (k >= 2 && !turnsLeft(p)) --k;
      chain[k++] = p;
    }
    const std::size_t lower = k + 1;
    for (std::size_t i = unique.size() - 1; i-- > 0;) {
      while (k >= lower && !turnsLeft(unique[i])) --k;
      chain[k++] = unique[i];
    }
    chain.resize(k - 1);
    return chain;
  }

  /// The part of `subject` (a point, a segment or a convex polygon) inside
  /// the counter-clockwise convex polygon `window` (Sutherland–Hodgman).
  static std::vector<Vec2> clip(std::vector<Vec2> subject, const std::vector<Vec2>& window) {
    for (std::size_t e = 0; e < window.size() && !subject.empty(); ++e) {
      const Vec2 a = window[e], edge = window[(e + 1) % window.size()] - a;
      const Vec2 inward(-edge.y(), edge.x());
      std::vector<Vec2> kept;
      for (std::size_t i = 0; i < subject.size(); ++i) {
        const Vec2 p = subject[i], q = subject[(i + 1) % subject.size()];
        const double dp = inward.dot(p - a), dq = inward.dot(q - a);
        if (dp >= 0.0) kept.push_back(p);
        if ((dp > 0.0 && dq < 0.0) || (dp < 0.0 && dq > 0.0)) kept.push_back(p + (q - p) * (dp / (dp - dq)));
      }
      subject = std::move(kept);
    }
    return subject;
  }

  /// Two features that are points or segments: a point meets anything where
  /// it is; two segments meet at their closest points, or along the
  /// overlap of their ranges when they are parallel.
  static std::vector<Vec2> crossing(const std::vector<Vec2>& a, const std::vector<Vec2>& b, double merge) {
    if (a.empty() || b.empty()) return {};
    if (a.size() == 1) return a;
    if (b.size() == 1) return b;
    const Vec2 u = a[1] - a[0], v = b[1] - b[0];
    const double lu = u.norm(), lv = v.norm();
    if (std::abs(cross(Vec2::Zero(), u, v)) <= merge * std::max(lu, lv)) {
      const Vec2 d = u / lu;
      const double s0 = std::max(0.0, std::min(d.dot(b[0] - a[0]), d.dot(b[1] - a[0])));
      const double s1 = std::min(lu, std::max(d.dot(b[0] - a[0]), d.dot(b[1] - a[0])));
      const Vec2 offset = 0.5 * ((b[0] - a[0]) - d.dot(b[0] - a[0]) * d);  // halfway across to b's line
      if (s0 > s1) return {a[0] + 0.5 * (s0 + s1) * d + offset};
      return {a[0] + s0 * d + offset, a[0] + s1 * d + offset};
    }
    // Closest points of the segments a[0] + s u and b[0] + t v, s, t in [0, 1].
    const Vec2 w = a[0] - b[0];
    const double uu = u.dot(u), uv = u.dot(v), vv = v.dot(v), uw = u.dot(w), vw = v.dot(w);
    const double denominator = uu * vv - uv * uv;
    double s = std::clamp((uv * vw - vv * uw) / denominator, 0.0, 1.0);
    const double t = std::clamp((uv * s + vw) / vv, 0.0, 1.0);
    s = std::clamp((uv * t - uw) / uu, 0.0, 1.0);
    return {0.5 * (a[0] + s * u + b[0] + t * v)};
  }

  /// A feature's height along n over the contact plane: the least-squares
  /// affine fit h(x) = h̄ + g·(x − x̄) to its points, with a tiny ridge on g
  /// so that a point or a segment (no slope across it) stays level.
  struct HeightPlane {
    Vec2 center = Vec2::Zero();
    double mean = 0.0;
    Vec2 slope = Vec2::Zero();

    HeightPlane(const std::vector<Vec3>& points, const FeatureClipping& frame) {
      for (const Vec3& p : points) {
        center += frame.flat(p);
        mean += frame.n.dot(p);
      }
      center /= double(points.size());
      mean /= double(points.size());
      Eigen::Matrix2d normal = Eigen::Matrix2d::Zero();
      Vec2 right = Vec2::Zero();
      for (const Vec3& p : points) {
        const Vec2 d = frame.flat(p) - center;
        normal += d * d.transpose();
        right += d * (frame.n.dot(p) - mean);
      }
      const double ridge = 1e-12 * normal.trace();
      if (!(ridge > 0.0)) return;  // a single point: level
      normal += ridge * Eigen::Matrix2d::Identity();
      const double determinant = normal(0, 0) * normal(1, 1) - normal(0, 1) * normal(1, 0);
      slope = Vec2(normal(1, 1) * right.x() - normal(0, 1) * right.y(),
                   normal(0, 0) * right.y() - normal(1, 0) * right.x()) /
              determinant;
    }
    [[nodiscard]] double at(const Vec2& x) const { return mean + slope.dot(x - center); }
  };
};

}  // namespace spook::detail
