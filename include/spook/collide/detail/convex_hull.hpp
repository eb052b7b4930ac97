#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <type_traits>
#include <utility>
#include <vector>

#include <spook/core/math.hpp>

namespace spook::detail {

/// One polygon face of a convex polyhedron: the plane normal·x = offset.
template <Scalar S>
struct ConvexFace {
  std::vector<int> vertices;          ///< corner indices, counter-clockwise seen from outside
  Vec3<S> normal = Vec3<S>::Zero();   ///< unit outward normal (shape frame)
  S offset = S(0);                    ///< normal·x on the face (m); smaller inside
};

/// A convex hull: its corners, its outward triangles and its polygon faces.
template <Scalar S>
struct ConvexHull {
  std::vector<Vec3<S>> vertices;              ///< the hull's corners, in input order (m)
  std::vector<std::array<int, 3>> triangles;  ///< counter-clockwise seen from outside
  std::vector<ConvexFace<S>> faces;           ///< coplanar triangles merged into polygons
};

/// Quickhull in 3D (Barber, Dobkin, Huhdanpaa, "The Quickhull Algorithm for
/// Convex Hulls", ACM TOMS 1996), in double. A point within `tolerance` of a
/// face's plane counts as on it: it never becomes a vertex, and a face it is
/// (nearly) coplanar with is replaced rather than kept beside a sliver.
class QuickHull {
 public:
  using V = Vec3<double>;

  QuickHull(std::vector<V> points, double tolerance)
      : p_(std::move(points)), tol_(tolerance), next_(p_.size(), -1) {}

  /// Builds the triangle hull; false when the points span no volume.
  bool build() {
    if (p_.size() < 4 || !initialSimplex()) return false;
    std::vector<int> work;
    for (int f = 0; f < 4; ++f) work.push_back(f);
    while (!work.empty()) {
      const int f = work.back();
      work.pop_back();
      if (faces_[f].alive && !faces_[f].outside.empty()) addPoint(f, work);
    }
    return true;
  }

  /// Polygon faces as point-index loops (counter-clockwise seen from outside):
  /// coplanar triangles merged, and corners lying on a straight edge dropped.
  [[nodiscard]] std::vector<std::vector<int>> polygons() {
    std::vector<std::vector<int>> loops = mergeCoplanar();
    dropStraightCorners(loops);
    return loops;
  }

  [[nodiscard]] const std::vector<V>& points() const { return p_; }

 private:
  struct Face {
    std::array<int, 3> v{};         // point indices, counter-clockwise from outside
    std::array<int, 3> neighbor{};  // face across the edge v[i] → v[i+1]
    V normal = V::Zero();
    double offset = 0;
    double area = 0;
    std::vector<int> outside;  // points more than tol_ above the plane
    int furthest = -1;
    double furthestDistance = 0;
    int visited = 0;  // stamp of the last flood fill that reached it
    bool visible = false;
    bool alive = true;
  };
  struct Edge {
    int a, b, outer;
  };

  [[nodiscard]] double distance(const Face& f, int i) const { return f.normal.dot(p_[i]) - f.offset; }

  int addFace(int a, int b, int c) {
    Face f;
    f.v = {a, b, c};
    // The cross product of the two shortest edges loses the fewest digits.
    const std::array<V, 3> e = {p_[b] - p_[a], p_[c] - p_[b], p_[a] - p_[c]};
    int longest = 0;
    for (int i = 1; i < 3; ++i)
      if (e[i].squaredNorm() > e[longest].squaredNorm()) longest = i;
    const V n = e[(longest + 1) % 3].cross(-e[(longest + 2) % 3]);
    f.area = 0.5 * n.norm();
    f.normal = f.area > 0 ? V(n / (2 * f.area)) : n;
    f.offset = f.normal.dot(p_[a] + p_[b] + p_[c]) / 3;
    faces_.push_back(std::move(f));
    return static_cast<int>(faces_.size()) - 1;
  }

  void assign(int point, int first, int last) {
    int best = -1;
    double bestDistance = tol_;
    for (int f = first; f < last; ++f) {
      const double d = distance(faces_[f], point);
      if (d > bestDistance) best = f, bestDistance = d;
    }
    if (best < 0) return;  // inside, or on the hull within the tolerance
    Face& f = faces_[best];
    f.outside.push_back(point);
    if (bestDistance > f.furthestDistance) f.furthest = point, f.furthestDistance = bestDistance;
  }

  // A tetrahedron of extreme points: the widest pair along an axis, the point
  // farthest from their line, the point farthest from their plane.
  bool initialSimplex() {
    const int n = static_cast<int>(p_.size());
    int lo = 0, hi = 0;
    double extent = -1;
    for (int axis = 0; axis < 3; ++axis) {
      int mn = 0, mx = 0;
      for (int i = 1; i < n; ++i) {
        if (p_[i][axis] < p_[mn][axis]) mn = i;
        if (p_[i][axis] > p_[mx][axis]) mx = i;
      }
      if (p_[mx][axis] - p_[mn][axis] > extent) extent = p_[mx][axis] - p_[mn][axis], lo = mn, hi = mx;
    }
    if (!((p_[hi] - p_[lo]).norm() > tol_)) return false;
    const V u = (p_[hi] - p_[lo]).normalized();
    int third = -1, fourth = -1;
    double far = tol_;
    for (int i = 0; i < n; ++i)
      if (const double d = (p_[i] - p_[lo]).cross(u).norm(); d > far) far = d, third = i;
    if (third < 0) return false;
    const V normal = (p_[hi] - p_[lo]).cross(p_[third] - p_[lo]).normalized();
    far = tol_;
    for (int i = 0; i < n; ++i)
      if (const double d = std::abs(normal.dot(p_[i] - p_[lo])); d > far) far = d, fourth = i;
    if (fourth < 0) return false;

    int a = lo, b = hi, c = third;
    const int d = fourth;
    if (normal.dot(p_[d] - p_[a]) > 0) std::swap(b, c);  // d below the base a, b, c
    addFace(a, b, c);
    addFace(a, d, b);
    addFace(b, d, c);
    addFace(c, d, a);
    for (int f = 0; f < 4; ++f)
      for (int i = 0; i < 3; ++i)
        for (int g = 0; g < 4; ++g)
          for (int j = 0; j < 3; ++j)
            if (faces_[g].v[j] == faces_[f].v[(i + 1) % 3] && faces_[g].v[(j + 1) % 3] == faces_[f].v[i])
              faces_[f].neighbor[i] = g;
    for (int i = 0; i < n; ++i)
      if (i != a && i != b && i != c && i != d) assign(i, 0, 4);
    return true;
  }

  // Replaces the faces the furthest point of face `start` sees (or is
  // coplanar with) by a cone from that point to their horizon.
  void addPoint(int start, std::vector<int>& work) {
    const int eye = faces_[start].furthest;
    ++stamp_;
    std::vector<int> visible{start};
    faces_[start].visited = stamp_;
    faces_[start].visible = true;
    for (std::size_t k = 0; k < visible.size(); ++k) {
      for (const int nb : faces_[visible[k]].neighbor) {
        Face& g = faces_[nb];
        if (g.visited == stamp_) continue;
        g.visited = stamp_;
        g.visible = distance(g, eye) > -tol_;
        if (g.visible) visible.push_back(nb);
      }
    }
    std::vector<Edge> horizon;
    for (const int f : visible)
      for (int i = 0; i < 3; ++i)
        if (const int nb = faces_[f].neighbor[i]; !faces_[nb].visible)
          horizon.push_back({faces_[f].v[i], faces_[f].v[(i + 1) % 3], nb});
    const std::vector<int> order = chain(horizon);
    if (order.empty()) {
      // Round-off made the visible region other than a disk; leave this point out.
      discard(start, eye);
      if (!faces_[start].outside.empty()) work.push_back(start);
      return;
    }

    const int first = static_cast<int>(faces_.size());
    const int m = static_cast<int>(order.size());
    for (int j = 0; j < m; ++j) addFace(horizon[order[j]].a, horizon[order[j]].b, eye);
    for (int j = 0; j < m; ++j) {
      const Edge& e = horizon[order[j]];
      faces_[first + j].neighbor = {e.outer, first + (j + 1) % m, first + (j + m - 1) % m};
      Face& outer = faces_[e.outer];
      for (int i = 0; i < 3; ++i)
        if (outer.v[i] == e.b && outer.v[(i + 1) % 3] == e.a) outer.neighbor[i] = first + j;
    }
    for (const int f : visible) {
      Face& old = faces_[f];
      old.alive = false;
      for (const int q : old.outside)
        if (q != eye) assign(q, first, first + m);
      old.outside = {};
    }
    for (int j = first; j < first + m; ++j)
      if (!faces_[j].outside.empty()) work.push_back(j);
  }

  // The horizon's edges in loop order, or nothing when they do not form one loop.
  std::vector<int> chain(const std::vector<Edge>& edges) {
    std::vector<int> order;
    bool simple = true;
    for (std::size_t k = 0; k < edges.size(); ++k) {
      if (next_[edges[k].a] != -1) simple = false;
      next_[edges[k].a] = static_cast<int>(k);
    }
    if (simple && !edges.empty()) {
      int k = 0;
      do {
        order.push_back(k);
        k = next_[edges[k].b];
      } while (k > 0 && order.size() < edges.size());
      if (k != 0 || order.size() != edges.size()) order.clear();
    }
    for (const Edge& e : edges) next_[e.a] = -1;
    return order;
  }

  void discard(int face, int point) {
    Face& f = faces_[face];
    std::erase(f.outside, point);
    f.furthest = -1;
    f.furthestDistance = 0;
    for (const int q : f.outside)
      if (const double d = distance(f, q); d > f.furthestDistance) f.furthest = q, f.furthestDistance = d;
  }

  // Grows each polygon from its largest triangle over neighbours whose
  // corners all lie within the tolerance of that triangle's plane.
  std::vector<std::vector<int>> mergeCoplanar() {
    std::vector<int> alive;
    for (int f = 0; f < static_cast<int>(faces_.size()); ++f)
      if (faces_[f].alive) alive.push_back(f);
    std::stable_sort(alive.begin(), alive.end(), [&](int a, int b) { return faces_[a].area > faces_[b].area; });
    std::vector<int> group(faces_.size(), -1);
    std::vector<std::vector<int>> loops;
    int id = 0;
    for (const int seed : alive) {
      if (group[seed] != -1) continue;
      const Face& s = faces_[seed];
      std::vector<int> members{seed};
      group[seed] = id;
      for (std::size_t k = 0; k < members.size(); ++k) {
        for (const int nb : faces_[members[k]].neighbor) {
          const Face& g = faces_[nb];
          if (group[nb] != -1 || !(g.normal.dot(s.normal) > 0)) continue;
          bool flat = true;
          for (const int v : g.v) flat = flat && std::abs(s.normal.dot(p_[v]) - s.offset) <= tol_;
          if (flat) group[nb] = id, members.push_back(nb);
        }
      }
      std::vector<Edge> boundary;
      for (const int f : members)
        for (int i = 0; i < 3; ++i)
          if (group[faces_[f].neighbor[i]] != id) boundary.push_back({faces_[f].v[i], faces_[f].v[(i + 1) % 3], -1});
      const std::vector<int> order = chain(boundary);
      if (!order.empty()) {
        std::vector<int> loop;
        for (const int k : order) loop.push_back(boundary[k].a);
        loops.push_back(std::move(loop));
      } else {
        for (const int f : members) loops.push_back({faces_[f].v[0], faces_[f].v[1], faces_[f].v[2]});
      }
      ++id;
    }
    return loops;
  }

  // A corner shared by only two polygons lies on the straight edge between
  // them (a closed convex surface meets at least three faces at a true corner).
  static void dropStraightCorners(std::vector<std::vector<int>>& loops) {
    int top = 0;
    for (const auto& loop : loops)
      for (const int v : loop) top = std::max(top, v + 1);
    std::vector<int> count(static_cast<std::size_t>(top), 0);
    for (const auto& loop : loops)
      for (const int v : loop) ++count[v];
    for (const auto& loop : loops) {
      const auto kept = std::count_if(loop.begin(), loop.end(), [&](int v) { return count[v] > 2; });
      if (kept < 3) return;  // would leave a degenerate polygon: keep every corner
    }
    for (auto& loop : loops) std::erase_if(loop, [&](int v) { return count[v] <= 2; });
  }

  std::vector<V> p_;
  double tol_;
  std::vector<Face> faces_;
  std::vector<int> next_;  // horizon chaining scratch, -1 between uses
  int stamp_ = 0;
};

/// Relative tolerance of the hull: coordinates of S carry round-off of a few
/// ulps, and for double a floor keeps sliver faces from steering the normals.
template <Scalar S>
inline constexpr double kHullRelativeTolerance = std::is_same_v<S, float> ? 32 * 1.1920929e-7 : 1e-12;

/// Convex hull of `points` (finite, in any frame), or nothing when they are
/// (within the tolerance) coplanar, collinear, coincident or fewer than 4.
/// The tolerance is kHullRelativeTolerance times the larger of the cloud's
/// bounding-box diagonal and its largest coordinate.
template <Scalar S>
[[nodiscard]] std::optional<ConvexHull<S>> convexHull(const std::vector<Vec3<S>>& points) {
  using V = Vec3<double>;
  if (points.size() < 4) return std::nullopt;
  V lo = points.front().template cast<double>(), hi = lo;
  for (const auto& p : points) {
    lo = lo.cwiseMin(p.template cast<double>());
    hi = hi.cwiseMax(p.template cast<double>());
  }
  const double scale = std::max((hi - lo).norm(), std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff()));
  const V center = 0.5 * (lo + hi);
  std::vector<V> shifted;
  shifted.reserve(points.size());
  for (const auto& p : points) shifted.push_back(p.template cast<double>() - center);

  QuickHull hull(std::move(shifted), kHullRelativeTolerance<S> * scale);
  if (!hull.build()) return std::nullopt;
  const std::vector<std::vector<int>> loops = hull.polygons();

  ConvexHull<S> result;
  std::vector<int> index(points.size(), -1);
  for (const auto& loop : loops)
    for (const int v : loop) index[v] = 0;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (index[i] == 0) {
      index[i] = static_cast<int>(result.vertices.size());
      result.vertices.push_back(points[i]);
    }
  for (const auto& loop : loops) {
    // Twice the loop's area vector (a fan of cross products): its direction is
    // the polygon's normal whatever the corner it starts from.
    V area = V::Zero();
    const V& origin = hull.points()[loop[0]];
    for (std::size_t k = 1; k + 1 < loop.size(); ++k)
      area += (hull.points()[loop[k]] - origin).cross(hull.points()[loop[k + 1]] - origin);
    ConvexFace<S> face;
    face.normal = area.normalized().template cast<S>();
    face.offset = std::numeric_limits<S>::lowest();
    for (const int v : loop) {
      face.vertices.push_back(index[v]);
      face.offset = std::max(face.offset, face.normal.dot(points[v]));
    }
    for (std::size_t k = 1; k + 1 < face.vertices.size(); ++k)
      result.triangles.push_back({face.vertices[0], face.vertices[k], face.vertices[k + 1]});
    result.faces.push_back(std::move(face));
  }
  return result;
}

}  // namespace spook::detail
