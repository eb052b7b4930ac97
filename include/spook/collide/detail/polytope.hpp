#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <utility>
#include <vector>

#include <spook/collide/detail/triangle.hpp>
#include <spook/collide/shapes/box.hpp>
#include <spook/collide/shapes/convex.hpp>
#include <spook/collide/shapes/line.hpp>
#include <spook/core/math.hpp>

namespace spook::detail {

/// A convex polytope placed in the world, as the separating-axis colliders
/// see it: corners, polygon faces and edges. A triangle is flat and
/// two-sided (its one face counts with both normals); a segment has no face.
/// In double whatever the shapes' scalar: the Gauss-map pruning and the
/// clipping decide on signs of small products, which float rounds away
/// (1.8e-4 m errors on hull–height-field pairs).
struct Polytope {
  using S = double;
  struct Face {
    Vec3T<S> normal;         // unit, outward (world)
    std::vector<int> loop;  // corners, counter-clockwise about the normal
  };
  /// An edge and the two faces that meet there; a triangle's or segment's
  /// edges have none (-1), and then no Gauss-map pruning applies to them.
  struct Edge {
    int from, to;
    int left = -1, right = -1;
  };

  std::vector<Vec3T<S>> vertices;  // world (m)
  std::vector<Face> faces;
  std::vector<Edge> edges;
  bool twoSided = false;

  /// The largest n·x over the corners (m) and the corner that reaches it.
  [[nodiscard]] std::pair<S, int> support(const Vec3T<S>& n) const {
    int best = 0;
    S height = n.dot(vertices[0]);
    for (std::size_t i = 1; i < vertices.size(); ++i)
      if (const S h = n.dot(vertices[i]); h > height) height = h, best = static_cast<int>(i);
    return {height, best};
  }
  [[nodiscard]] Vec3T<S> edgeVector(const Edge& e) const {
    return vertices[static_cast<std::size_t>(e.to)] - vertices[static_cast<std::size_t>(e.from)];
  }
  [[nodiscard]] const Vec3T<S>& vertex(int i) const { return vertices[static_cast<std::size_t>(i)]; }
};

/// Edges from the face loops: each undirected loop edge once, with the two
/// faces on either side.
inline void linkEdges(Polytope& polytope) {
  polytope.edges.clear();
  for (std::size_t f = 0; f < polytope.faces.size(); ++f) {
    const auto& loop = polytope.faces[f].loop;
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const int a = loop[k], b = loop[(k + 1) % loop.size()];
      const auto shared = std::find_if(polytope.edges.begin(), polytope.edges.end(),
                                       [&](const auto& e) { return e.from == b && e.to == a; });
      if (shared != polytope.edges.end())
        shared->right = static_cast<int>(f);
      else
        polytope.edges.push_back({a, b, static_cast<int>(f), -1});
    }
  }
}

template <Scalar T>
void makeBoxPolytope(const BoxT<T>& box, const TransformT<T>& X_WT, Polytope& out) {
  using S = double;
  const Vec3T<S> h = box.getHalfExtents().template cast<S>();
  const TransformT<S> X_W = X_WT.template cast<S>();
  out.vertices.resize(8);
  for (int c = 0; c < 8; ++c)
    out.vertices[std::size_t(c)] =
        X_W * Vec3T<S>((c & 1) ? h.x() : -h.x(), (c & 2) ? h.y() : -h.y(), (c & 4) ? h.z() : -h.z());
  // Corner c has bit i set where its coordinate i is +h_i; each loop runs
  // counter-clockwise seen from outside.
  static constexpr std::array<std::array<int, 4>, 6> kLoops = {{{0, 4, 6, 2},    // −x
                                                               {1, 3, 7, 5},    // +x
                                                               {0, 1, 5, 4},    // −y
                                                               {2, 6, 7, 3},    // +y
                                                               {0, 2, 3, 1},    // −z
                                                               {4, 5, 7, 6}}};  // +z
  out.faces.resize(6);
  for (int f = 0; f < 6; ++f) {
    const Vec3T<S> axis = X_W.linear().col(f / 2);
    out.faces[std::size_t(f)].normal = (f % 2) ? axis : Vec3T<S>(-axis);
    out.faces[std::size_t(f)].loop.assign(kLoops[std::size_t(f)].begin(), kLoops[std::size_t(f)].end());
  }
  out.twoSided = false;
  linkEdges(out);
}

template <Scalar T>
void makeConvexPolytope(const ConvexT<T>& convex, const TransformT<T>& X_WT, Polytope& out) {
  const TransformT<double> X_W = X_WT.template cast<double>();
  out.vertices.resize(convex.getVertices().size());
  for (std::size_t i = 0; i < out.vertices.size(); ++i)
    out.vertices[i] = X_W * convex.getVertices()[i].template cast<double>();
  out.faces.resize(convex.getFaces().size());
  for (std::size_t f = 0; f < out.faces.size(); ++f) {
    out.faces[f].normal = (X_W.linear() * convex.getFaces()[f].normal.template cast<double>()).normalized();
    out.faces[f].loop = convex.getFaces()[f].vertices;
  }
  out.twoSided = false;
  out.edges.clear();
  for (const auto& e : convex.getEdges()) out.edges.push_back({e.from, e.to, e.left, e.right});
}

/// A triangle (world corners); a degenerate one keeps its +z normal and
/// its edges, which is all the separating axes need of it.
template <Scalar T>
void makeTrianglePolytope(const Triangle<T>& t_WT, Polytope& out) {
  const Triangle<double> t_W{{t_WT.v[0].template cast<double>(), t_WT.v[1].template cast<double>(),
                              t_WT.v[2].template cast<double>()}};
  out.vertices.assign(t_W.v.begin(), t_W.v.end());
  out.faces.resize(1);
  out.faces[0].normal = t_W.normal();
  out.faces[0].loop = {0, 1, 2};
  out.edges = {{0, 1}, {1, 2}, {2, 0}};
  out.twoSided = true;
}

template <Scalar T>
void makeSegmentPolytope(const Vec3T<T>& p_W, const Vec3T<T>& q_W, Polytope& out) {
  out.vertices = {p_W.template cast<double>(), q_W.template cast<double>()};
  out.faces.clear();
  out.edges = {{0, 1}};
  out.twoSided = false;
}

/// The polytope of a box, a hull or a segment placed at X_W.
template <Scalar T>
void makePolytope(const BoxT<T>& box, const TransformT<T>& X_W, Polytope& out) {
  makeBoxPolytope(box, X_W, out);
}
template <Scalar T>
void makePolytope(const ConvexT<T>& convex, const TransformT<T>& X_W, Polytope& out) {
  makeConvexPolytope(convex, X_W, out);
}
template <Scalar T>
void makePolytope(const LineT<T>& line, const TransformT<T>& X_W, Polytope& out) {
  makeSegmentPolytope<T>(X_W * line.getFirstPoint(), X_W * line.getSecondPoint(), out);
}

}  // namespace spook::detail
