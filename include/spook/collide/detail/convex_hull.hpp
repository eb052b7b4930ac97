#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <set>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include <spook/core/implementation.hpp>
#include <spook/core/math.hpp>

namespace spook::detail {

/// One polygon face of a convex polyhedron: the plane normal·x = offset.
template <Scalar S>
struct ConvexFace {
  std::vector<int> vertices;           ///< corner indices, counter-clockwise seen from outside
  Vec3T<S> normal = Vec3T<S>::Zero();  ///< unit outward normal (shape frame)
  S offset = S(0);                     ///< largest normal·x of its corners and merged points (m)
};

/// A convex hull: its corners, its outward triangles and its polygon faces.
template <Scalar S>
struct ConvexHull {
  std::vector<Vec3T<S>> vertices;             ///< the hull's corners, in input order (m)
  std::vector<std::array<int, 3>> triangles;  ///< counter-clockwise seen from outside
  std::vector<ConvexFace<S>> faces;           ///< coplanar triangles merged into polygons
  S tolerance = S(0);                         ///< distance below which points counted as on a face (m)
};

/// Quickhull in 3D (Barber, Dobkin, Huhdanpaa, "The Quickhull Algorithm for
/// Convex Hulls", ACM TOMS 1996), in double, on "joggled" points as Qhull's
/// option QJ does: each coordinate moved at random by at most a quarter of
/// the tolerance, which puts the cloud in general position, so that
/// visibility can be a plain sign test and the hull stays convex. A point
/// within the tolerance of the hull never becomes a vertex. Coplanar
/// triangles are then merged, and corners on straight edges dropped, by the
/// true points.
class QuickHull {
 public:
  using V = Vec3T<double>;

  /// A polygon of the hull: its loop of point indices (counter-clockwise seen
  /// from outside), every point its triangles used, and its unit normal.
  struct Polygon {
    std::vector<int> loop;
    std::vector<int> points;
    V normal;
  };

  /// `points` in any frame; `tolerance` (m); `attempt` picks the joggle.
  QuickHull(std::vector<V> points, double tolerance, int attempt);

  /// Builds the triangle hull; false when the true points span no volume.
  bool build();

  /// True when round-off left some point out (then try another joggle).
  [[nodiscard]] bool leftPointsOut() const { return leftOut_; }

  /// The polygon faces: coplanar triangles merged, corners on straight edges dropped.
  [[nodiscard]] std::vector<Polygon> polygons();

 private:
  struct Face {
    std::array<int, 3> v{};         // point indices, counter-clockwise from outside
    std::array<int, 3> neighbor{};  // face across the edge v[i] → v[i+1]
    V normal = V::Zero();           // of the joggled points
    double offset = 0;
    std::vector<int> outside;  // points above the plane, not known to be within tol_ of the hull
    int furthest = -1;
    double furthestDistance = 0;
    int visited = 0;  // stamp of the last flood fill that reached it
    bool visible = false;
    bool alive = true;
  };
  struct Edge {
    int a, b, outer;
  };

  // Uniform in [-1, 1) from a splitmix64 stream: the same on every platform.
  static double jiggle(std::uint64_t& state);

  // Unit normal and area of the triangle a, b, c of `x`; the cross product of
  // its two shortest edges loses the fewest digits.
  static std::pair<V, double> plane(const std::vector<V>& x, int a, int b, int c);

  [[nodiscard]] double distance(const Face& f, int i) const { return f.normal.dot(q_[i]) - f.offset; }

  int addFace(int a, int b, int c);

  // Distance from joggled point i to the triangle of face f (Ericson,
  // "Real-Time Collision Detection", 2005, 5.1.5): to its plane when the
  // point projects inside it, else to the nearest edge.
  [[nodiscard]] double triangleDistance(const Face& f, int i) const;

  // Files the point under the new face it is farthest above. A point on or
  // below them all is inside the hull; one within the tolerance of the
  // triangles it is above lies (and stays) within the tolerance of the hull.
  // Both are dropped. A point above the planes by less than the tolerance
  // but farther from their triangles (beyond a sharp edge) is kept.
  void assign(int point, int first, int last);

  // A tetrahedron of extreme true points: the widest pair along an axis, the
  // point farthest from their line, the point farthest from their plane.
  bool initialSimplex();

  // Replaces the faces the furthest point of face `start` is above by a cone
  // from that point to their horizon.
  void addPoint(int start, std::vector<int>& work);

  // The edges in loop order, or nothing when they do not form one loop.
  std::vector<int> chain(const std::vector<Edge>& edges);

  void discard(int face, int point);

  // Grows each polygon from the largest remaining triangle over neighbours
  // whose true corners all lie within the tolerance of its true plane.
  std::vector<Polygon> mergeCoplanar();

  // Drops each corner that only two polygons share and that lies within the
  // tolerance of the line through its remaining neighbours: it sits on the
  // edge between them (at a true corner three faces or more meet).
  void dropStraightCorners(std::vector<Polygon>& polygons) const;

  std::vector<V> p_;  // the true points
  std::vector<V> q_;  // the joggled points the hull is built on
  double tol_;
  std::vector<Face> faces_;
  std::vector<int> next_;  // edge chaining scratch, -1 between uses
  int stamp_ = 0;
  bool leftOut_ = false;
};

#if defined(SPOOK_DEFINES_NON_TEMPLATES)
SPOOK_INLINE QuickHull::QuickHull(std::vector<V> points, double tolerance, int attempt)
    : p_(std::move(points)), tol_(tolerance), next_(p_.size(), -1) {
  q_.reserve(p_.size());
  std::uint64_t state = 0x9E3779B97F4A7C15ull * static_cast<std::uint64_t>(attempt + 1);
  for (const V& p : p_) q_.push_back(p + 0.25 * tol_ * V(jiggle(state), jiggle(state), jiggle(state)));
}

SPOOK_INLINE bool QuickHull::build() {
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

SPOOK_INLINE auto QuickHull::polygons() -> std::vector<Polygon> {
  std::vector<Polygon> polygons = mergeCoplanar();
  dropStraightCorners(polygons);
  for (Polygon& polygon : polygons) {
    // Twice the loop's area vector (a fan of cross products).
    V area = V::Zero();
    const V& origin = p_[polygon.loop[0]];
    for (std::size_t k = 1; k + 1 < polygon.loop.size(); ++k)
      area += (p_[polygon.loop[k]] - origin).cross(p_[polygon.loop[k + 1]] - origin);
    if (area.norm() > 0) polygon.normal = area.normalized();
  }
  return polygons;
}

SPOOK_INLINE double QuickHull::jiggle(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * 0x1.0p-52 - 1.0;
}

SPOOK_INLINE auto QuickHull::plane(const std::vector<V>& x, int a, int b, int c) -> std::pair<V, double> {
  const std::array<V, 3> e = {x[b] - x[a], x[c] - x[b], x[a] - x[c]};
  int longest = 0;
  for (int i = 1; i < 3; ++i)
    if (e[i].squaredNorm() > e[longest].squaredNorm()) longest = i;
  const V n = e[(longest + 2) % 3].cross(-e[(longest + 1) % 3]);
  const double twiceArea = n.norm();
  return {twiceArea > 0 ? V(n / twiceArea) : n, 0.5 * twiceArea};
}

SPOOK_INLINE int QuickHull::addFace(int a, int b, int c) {
  Face f;
  f.v = {a, b, c};
  f.normal = plane(q_, a, b, c).first;
  f.offset = f.normal.dot(q_[a] + q_[b] + q_[c]) / 3;
  faces_.push_back(std::move(f));
  return static_cast<int>(faces_.size()) - 1;
}

SPOOK_INLINE double QuickHull::triangleDistance(const Face& f, int i) const {
  const V& x = q_[i];
  bool inside = true;
  double nearest = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    const V& a = q_[f.v[k]];
    const V edge = q_[f.v[(k + 1) % 3]] - a;
    inside = inside && edge.cross(x - a).dot(f.normal) >= 0;
    const double t = std::clamp((x - a).dot(edge) / edge.squaredNorm(), 0.0, 1.0);
    nearest = std::min(nearest, (x - a - t * edge).norm());
  }
  return inside ? std::abs(distance(f, i)) : nearest;
}

SPOOK_INLINE void QuickHull::assign(int point, int first, int last) {
  int best = -1;
  double bestDistance = 0;
  for (int f = first; f < last; ++f) {
    const double d = distance(faces_[f], point);
    if (d > bestDistance) best = f, bestDistance = d;
  }
  if (best < 0) return;
  if (bestDistance <= tol_)
    for (int f = first; f < last; ++f)
      if (distance(faces_[f], point) > 0 && triangleDistance(faces_[f], point) <= tol_) return;
  Face& f = faces_[best];
  f.outside.push_back(point);
  if (bestDistance > f.furthestDistance) f.furthest = point, f.furthestDistance = bestDistance;
}

SPOOK_INLINE bool QuickHull::initialSimplex() {
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
  if (plane(q_, a, b, c).first.dot(q_[d] - q_[a]) > 0) std::swap(b, c);  // d below the base a, b, c
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

SPOOK_INLINE void QuickHull::addPoint(int start, std::vector<int>& work) {
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
      g.visible = distance(g, eye) > 0;
      if (g.visible) visible.push_back(nb);
    }
  }
  // The hull's nearest point to the eye lies on a face the eye sees.
  double gap = std::numeric_limits<double>::infinity();
  for (const int f : visible) gap = std::min(gap, triangleDistance(faces_[f], eye));
  if (!(gap > tol_)) {
    discard(start, eye);
    if (!faces_[start].outside.empty()) work.push_back(start);
    return;
  }
  std::vector<Edge> horizon;
  for (const int f : visible)
    for (int i = 0; i < 3; ++i)
      if (const int nb = faces_[f].neighbor[i]; !faces_[nb].visible)
        horizon.push_back({faces_[f].v[i], faces_[f].v[(i + 1) % 3], nb});
  const std::vector<int> order = chain(horizon);
  if (order.empty()) {
    // Round-off made the visible region other than a disk: leave the point out.
    leftOut_ = true;
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

SPOOK_INLINE std::vector<int> QuickHull::chain(const std::vector<Edge>& edges) {
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

SPOOK_INLINE void QuickHull::discard(int face, int point) {
  Face& f = faces_[face];
  std::erase(f.outside, point);
  f.furthest = -1;
  f.furthestDistance = 0;
  for (const int q : f.outside)
    if (const double d = distance(f, q); d > f.furthestDistance) f.furthest = q, f.furthestDistance = d;
}

SPOOK_INLINE auto QuickHull::mergeCoplanar() -> std::vector<Polygon> {
  std::vector<int> alive;
  std::vector<V> normal(faces_.size(), V::Zero());
  std::vector<double> offset(faces_.size(), 0), area(faces_.size(), 0);
  for (int f = 0; f < static_cast<int>(faces_.size()); ++f) {
    const Face& face = faces_[f];
    if (!face.alive) continue;
    alive.push_back(f);
    std::tie(normal[f], area[f]) = plane(p_, face.v[0], face.v[1], face.v[2]);
    if (!(area[f] > 0)) normal[f] = face.normal;  // a sliver flattened by the true points
    offset[f] = normal[f].dot(p_[face.v[0]] + p_[face.v[1]] + p_[face.v[2]]) / 3;
  }
  std::stable_sort(alive.begin(), alive.end(), [&](int a, int b) { return area[a] > area[b]; });
  std::vector<int> group(faces_.size(), -1);
  std::vector<Polygon> polygons;
  int id = 0;
  for (const int seed : alive) {
    if (group[seed] != -1) continue;
    std::vector<int> members{seed};
    group[seed] = id;
    for (std::size_t k = 0; k < members.size(); ++k) {
      for (const int nb : faces_[members[k]].neighbor) {
        if (group[nb] != -1 || !(faces_[nb].normal.dot(faces_[seed].normal) > 0)) continue;
        bool flat = true;
        for (const int v : faces_[nb].v) flat = flat && std::abs(normal[seed].dot(p_[v]) - offset[seed]) <= tol_;
        if (flat) group[nb] = id, members.push_back(nb);
      }
    }
    std::vector<Edge> boundary;
    for (const int f : members)
      for (int i = 0; i < 3; ++i)
        if (group[faces_[f].neighbor[i]] != id) boundary.push_back({faces_[f].v[i], faces_[f].v[(i + 1) % 3], -1});
    const std::vector<int> order = chain(boundary);
    if (!order.empty()) {
      Polygon polygon{{}, {}, normal[seed]};
      for (const int k : order) polygon.loop.push_back(boundary[k].a);
      for (const int f : members) polygon.points.insert(polygon.points.end(), faces_[f].v.begin(), faces_[f].v.end());
      polygons.push_back(std::move(polygon));
    } else {
      for (const int f : members) {
        const std::vector<int> corners(faces_[f].v.begin(), faces_[f].v.end());
        polygons.push_back({corners, corners, normal[f]});
      }
    }
    ++id;
  }
  return polygons;
}

SPOOK_INLINE void QuickHull::dropStraightCorners(std::vector<Polygon>& polygons) const {
  std::vector<std::array<int, 2>> owner(p_.size(), {-1, -1});
  std::vector<int> count(p_.size(), 0);
  for (int k = 0; k < static_cast<int>(polygons.size()); ++k)
    for (const int v : polygons[k].loop)
      if (++count[v] <= 2) owner[v][count[v] - 1] = k;
  std::vector<char> dropped(p_.size(), 0);
  std::vector<std::size_t> left(polygons.size());
  for (std::size_t k = 0; k < polygons.size(); ++k) left[k] = polygons[k].loop.size();
  for (const Polygon& polygon : polygons) {
    const std::vector<int>& loop = polygon.loop;
    const std::size_t n = loop.size();
    for (std::size_t i = 0; i < n; ++i) {
      const int v = loop[i];
      if (count[v] != 2 || dropped[v] || left[owner[v][0]] <= 3 || left[owner[v][1]] <= 3) continue;
      std::size_t before = i, after = i;
      do before = (before + n - 1) % n;
      while (dropped[loop[before]]);
      do after = (after + 1) % n;
      while (dropped[loop[after]]);
      const V& a = p_[loop[before]];
      const V line = p_[loop[after]] - a;
      if ((p_[v] - a).cross(line).norm() <= tol_ * line.norm()) {
        dropped[v] = 1;
        --left[owner[v][0]];
        --left[owner[v][1]];
      }
    }
  }
  for (Polygon& polygon : polygons) std::erase_if(polygon.loop, [&](int v) { return dropped[v] != 0; });
}
#endif

/// Tolerance of the hull, relative to the cloud's half bounding-box diagonal.
/// The hull is built in double on points moved to their box center, where a
/// sliver face of height h has a normal good to about ε·size/h: features
/// below some √ε·size cannot be decided, hence 1e-7 for double. For float,
/// 16 ulps of the input's own round-off is the larger. convexHull adds 16
/// ulps of S of the largest coordinate, for round-off in the input.
template <Scalar S>
inline constexpr double kHullRelativeTolerance = std::is_same_v<S, float> ? 16 * 1.1920929e-7 : 1e-7;

/// Convex hull of `points` (finite, in any frame), or nothing when they are
/// (within the tolerance) coplanar, collinear, coincident or fewer than 4.
template <Scalar S>
[[nodiscard]] std::optional<ConvexHull<S>> convexHull(const std::vector<Vec3T<S>>& points) {
  using V = Vec3T<double>;
  if (points.size() < 4) return std::nullopt;
  V lo = points.front().template cast<double>(), hi = lo;
  for (const auto& p : points) {
    lo = lo.cwiseMin(p.template cast<double>());
    hi = hi.cwiseMax(p.template cast<double>());
  }
  const double largest = std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff());
  const double tolerance =
      kHullRelativeTolerance<S> * 0.5 * (hi - lo).norm() + 16 * double(std::numeric_limits<S>::epsilon()) * largest;
  const V center = 0.5 * (lo + hi);
  std::vector<V> shifted;
  shifted.reserve(points.size());
  for (const auto& p : points) shifted.push_back(p.template cast<double>() - center);

  // A point left out by round-off is rare; another joggle almost surely
  // keeps it (Qhull retries likewise).
  constexpr int kAttempts = 4;
  std::vector<QuickHull::Polygon> polygons;
  for (int attempt = 0; attempt < kAttempts; ++attempt) {
    QuickHull hull(shifted, tolerance, attempt);
    if (!hull.build()) return std::nullopt;
    if (hull.leftPointsOut() && attempt + 1 < kAttempts) continue;
    polygons = hull.polygons();
    break;
  }

  ConvexHull<S> result;
  result.tolerance = S(tolerance);
  std::vector<int> index(points.size(), -1);
  for (const auto& polygon : polygons)
    for (const int v : polygon.loop) index[v] = 0;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (index[i] == 0) {
      index[i] = static_cast<int>(result.vertices.size());
      result.vertices.push_back(points[i]);
    }
  std::set<std::pair<int, int>> edges;  // polygon sides and fan diagonals, as (low, high) index
  for (const auto& polygon : polygons)
    for (std::size_t k = 0; k < polygon.loop.size(); ++k) {
      const int a = index[polygon.loop[k]], b = index[polygon.loop[(k + 1) % polygon.loop.size()]];
      edges.insert(std::minmax(a, b));
    }
  for (const auto& polygon : polygons) {
    ConvexFace<S> face;
    face.normal = polygon.normal.template cast<S>();
    face.offset = std::numeric_limits<S>::lowest();
    for (const int v : polygon.loop) face.vertices.push_back(index[v]);
    for (const int v : polygon.points) face.offset = std::max(face.offset, face.normal.dot(points[v]));
    // A fan from the first corner whose diagonals are no edge yet (two
    // polygons bent within the tolerance could share one): a closed surface.
    const std::size_t n = face.vertices.size();
    for (std::size_t root = 0; root < n; ++root) {
      bool clear = true;
      for (std::size_t k = 2; k + 1 < n && clear; ++k)
        clear = !edges.contains(std::minmax(face.vertices[root], face.vertices[(root + k) % n]));
      if (clear) {
        std::rotate(face.vertices.begin(), face.vertices.begin() + static_cast<std::ptrdiff_t>(root),
                    face.vertices.end());
        break;
      }
    }
    for (std::size_t k = 2; k + 1 < n; ++k) edges.insert(std::minmax(face.vertices[0], face.vertices[k]));
    for (std::size_t k = 1; k + 1 < n; ++k)
      result.triangles.push_back({face.vertices[0], face.vertices[k], face.vertices[k + 1]});
    result.faces.push_back(std::move(face));
  }
  return result;
}

}  // namespace spook::detail
