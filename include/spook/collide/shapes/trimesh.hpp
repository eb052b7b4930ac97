#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <spook/collide/detail/aabb_tree.hpp>
#include <spook/collide/detail/polyhedron_mass.hpp>
#include <spook/collide/detail/triangle.hpp>
#include <spook/collide/shapes/shape.hpp>
#include <spook/core/implementation.hpp>

namespace spook {

/// A triangle mesh: vertices in the shape frame (m) and triangles as three
/// vertex indices, counter-clockwise seen from outside. A closed mesh (every
/// edge shared by exactly two triangles of opposite orientation) is a solid
/// with volume and inertia; an open one is a surface with no volume. The
/// triangles are kept in an AabbTree for collision queries.
template <Scalar S>
class TrimeshT : public ShapeT<S> {
 public:
  static constexpr ShapeType kType = ShapeType::TRIMESH;
  using Vec3 = spook::Vec3T<S>;
  using Mat3 = spook::Mat3T<S>;
  using Triangle = std::array<int, 3>;

  /// Throws spook::Error on no triangles, a non-finite vertex, an index out
  /// of range, a triangle repeating an index, or a closed mesh wound inward.
  TrimeshT(std::vector<Vec3> vertices, std::vector<Triangle> triangles);

  /// Vertices, shape frame (m).
  [[nodiscard]] const std::vector<Vec3>& getVertices() const { return vertices_; }
  /// Triangles as vertex indices, counter-clockwise seen from outside.
  [[nodiscard]] const std::vector<Triangle>& getTriangles() const { return triangles_; }
  /// Number of triangles.
  [[nodiscard]] std::size_t getNumTriangles() const { return triangles_.size(); }
  /// Corners of triangle i, shape frame (m), counter-clockwise seen from outside.
  [[nodiscard]] std::array<Vec3, 3> getTriangle(std::size_t i) const {
    const Triangle& t = triangles_[i];
    return {vertices_[static_cast<std::size_t>(t[0])], vertices_[static_cast<std::size_t>(t[1])],
            vertices_[static_cast<std::size_t>(t[2])]};
  }
  /// Unit outward normal of triangle i, shape frame; zero for a triangle of zero area.
  [[nodiscard]] Vec3 getNormal(std::size_t i) const {
    const auto [a, b, c] = getTriangle(i);
    return (b - a).cross(c - a).normalized();
  }
  /// Which edges of triangle i may give a contact a normal of its own
  /// (detail::edgeActivity): bit k for the edge from corner k to corner
  /// k + 1, bits 0-2 seen from the front, 3-5 from behind. An edge shared
  /// by exactly two triangles of opposite orientation is active where the
  /// mesh folds away by more than 5° from the side looking at it; any other
  /// edge (a rim, or shared by more triangles) is active.
  [[nodiscard]] std::uint8_t getActiveEdges(std::size_t i) const { return activeEdges_[i]; }
  /// True when every edge is shared by exactly two triangles with opposite orientation.
  [[nodiscard]] bool isClosed() const { return openEdges_ == 0; }
  /// The tree over the triangle boxes, shape frame; primitive i is triangle i.
  [[nodiscard]] const detail::AabbTree<S>& getTree() const { return tree_; }

  [[nodiscard]] ShapeType getType() const override { return kType; }
  bool collideWithLowerRank(const TransformT<S>& X_WA, const ShapeT<S>& other, const TransformT<S>& X_WB,
                            ContactSinkT<S>& sink) const override {
    return detail::collideWithLowerRank(*this, X_WA, other, X_WB, sink);
  }

  /// Enclosed volume (m³) of a closed mesh, 0 for an open one.
  [[nodiscard]] S getVolume() const override { return volume_; }

  /// Center of volume of a closed mesh, else the center of the vertices' box (shape frame, m).
  [[nodiscard]] Vec3 getCenterOfVolume() const override;

  /// About the shape origin, shape frame (kg·m²): the tensor about the center
  /// of volume c scaled to `mass`, plus m(|c|² 1 − c cᵀ). Throws for a mesh
  /// enclosing no volume.
  [[nodiscard]] SPDMat3T<S> calculateInertia(S mass) const override;

  /// Box around all vertices, shape frame (m).
  [[nodiscard]] BoundingBoxT<S> getBoundingBox() const override { return bounds_; }

  /// Calls visit(index, a, b, c) with the corners (shape frame, m) of each
  /// triangle whose box overlaps `localBox` (shape frame, touching counts).
  template <class F>
  void forEachTriangle(const BoundingBoxT<S>& localBox, F&& visit) const {
    tree_.query(localBox, [&](std::size_t i) {
      const Triangle& t = triangles_[i];
      visit(i, vertices_[static_cast<std::size_t>(t[0])], vertices_[static_cast<std::size_t>(t[1])],
            vertices_[static_cast<std::size_t>(t[2])]);
    });
  }

 protected:
  ~TrimeshT() override = default;

 private:
  void validate() const;

  // A directed edge as one sortable number.
  static std::uint64_t edgeKey(int from, int to) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(from)) << 32) | static_cast<std::uint32_t>(to);
  }

  // Directed edges sorted once: the mesh is closed when no directed edge
  // repeats and each one's reverse is present. Counts the edges that fail.
  [[nodiscard]] std::size_t countOpenEdges() const;

  // Each directed edge's twin (the reverse edge of exactly one other
  // triangle, its own direction unrepeated) by a sorted list of edges.
  void computeActiveEdges();

  void computeMass();

  std::vector<Vec3> vertices_;
  std::vector<Triangle> triangles_;
  detail::AabbTree<S> tree_;
  BoundingBoxT<S> bounds_;
  std::vector<std::uint8_t> activeEdges_;
  std::size_t openEdges_ = 0;
  S enclosed_ = S(0);  ///< signed volume of a closed mesh (m³), as computed
  S volume_ = S(0);    ///< m³; 0 unless closed and enclosing a volume
  Vec3 center_ = Vec3::Zero();
  Mat3 inertia_ = Mat3::Zero();  ///< unit-density inertia about center_ (m⁵)
};

template <Scalar S>
TrimeshT<S>::TrimeshT(std::vector<Vec3> vertices, std::vector<Triangle> triangles)
    : vertices_(std::move(vertices)), triangles_(std::move(triangles)) {
  validate();
  std::vector<BoundingBoxT<S>> boxes(triangles_.size());
  for (std::size_t i = 0; i < triangles_.size(); ++i) {
    const auto [a, b, c] = getTriangle(i);
    boxes[i] = {a.cwiseMin(b).cwiseMin(c), a.cwiseMax(b).cwiseMax(c)};
  }
  tree_ = detail::AabbTree<S>(boxes);
  bounds_ = {vertices_.front(), vertices_.front()};
  for (const Vec3& v : vertices_) bounds_ = {bounds_.min.cwiseMin(v), bounds_.max.cwiseMax(v)};
  openEdges_ = countOpenEdges();
  if (openEdges_ == 0) computeMass();
  computeActiveEdges();
}

template <Scalar S>
auto TrimeshT<S>::getCenterOfVolume() const -> Vec3 {
  return volume_ > S(0) ? center_ : bounds_.center();
}

template <Scalar S>
auto TrimeshT<S>::calculateInertia(S mass) const -> SPDMat3T<S> {
  this->requireMass("Trimesh", mass);
  if (openEdges_ > 0)
    throw detail::makeError("Trimesh", "", "an open Trimesh has no volume, hence no inertia; edges without a twin",
                            openEdges_);
  if (!(volume_ > S(0)))
    throw detail::makeError("Trimesh", "", "a closed Trimesh enclosing no volume has no inertia; volume (m^3)",
                            enclosed_);
  const Mat3 shift = mass * (center_.squaredNorm() * Mat3::Identity() - center_ * center_.transpose());
  return SPDMat3T<S>(Mat3((mass / volume_) * inertia_ + shift));
}

template <Scalar S>
void TrimeshT<S>::validate() const {
  if (triangles_.empty()) throw detail::makeError("Trimesh", "", "needs at least one triangle", triangles_.size());
  for (std::size_t i = 0; i < vertices_.size(); ++i)
    if (!vertices_[i].allFinite())
      throw detail::makeError("Trimesh", "", "vertex " + std::to_string(i) + " must be finite (m)", vertices_[i]);
  const std::size_t n = vertices_.size();
  for (std::size_t i = 0; i < triangles_.size(); ++i) {
    const Triangle& t = triangles_[i];
    for (int k : t)
      if (k < 0 || static_cast<std::size_t>(k) >= n)
        throw detail::makeError(
            "Trimesh", "",
            "triangle " + std::to_string(i) + " has a vertex index outside [0, " + std::to_string(n) + ")", k);
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0])
      throw detail::makeError("Trimesh", "", "triangle " + std::to_string(i) + " must have three distinct vertices", t);
  }
}

template <Scalar S>
std::size_t TrimeshT<S>::countOpenEdges() const {
  std::vector<std::uint64_t> edges;
  edges.reserve(3 * triangles_.size());
  for (const Triangle& t : triangles_)
    for (int k = 0; k < 3; ++k) edges.push_back(edgeKey(t[k], t[(k + 1) % 3]));
  std::sort(edges.begin(), edges.end());
  std::size_t open = 0;
  for (std::size_t k = 0; k < edges.size(); ++k) {
    const bool repeated = (k > 0 && edges[k] == edges[k - 1]) || (k + 1 < edges.size() && edges[k] == edges[k + 1]);
    const std::uint64_t reverse = (edges[k] << 32) | (edges[k] >> 32);
    if (repeated || !std::binary_search(edges.begin(), edges.end(), reverse)) ++open;
  }
  return open;
}

template <Scalar S>
void TrimeshT<S>::computeActiveEdges() {
  struct Edge {
    std::uint64_t key;
    std::size_t triangle;
    bool operator<(const Edge& other) const { return key < other.key; }
  };
  std::vector<Edge> edges;
  edges.reserve(3 * triangles_.size());
  for (std::size_t i = 0; i < triangles_.size(); ++i)
    for (int k = 0; k < 3; ++k) edges.push_back({edgeKey(triangles_[i][k], triangles_[i][(k + 1) % 3]), i});
  std::sort(edges.begin(), edges.end());
  const auto count = [&](std::uint64_t k) {
    const auto [first, last] = std::equal_range(edges.begin(), edges.end(), Edge{k, 0});
    return std::pair{first, static_cast<std::size_t>(last - first)};
  };
  std::vector<Vec3> normals(triangles_.size());
  for (std::size_t i = 0; i < triangles_.size(); ++i) {
    const auto [a, b, c] = getTriangle(i);
    const Vec3 n = (b - a).cross(c - a);
    normals[i] = n.norm() > S(0) ? Vec3(n.normalized()) : Vec3::Zero();
  }
  activeEdges_.resize(triangles_.size());
  for (std::size_t i = 0; i < triangles_.size(); ++i) {
    std::array<const Vec3*, 3> neighbours{};
    for (int k = 0; k < 3; ++k) {
      const int from = triangles_[i][k], to = triangles_[i][(k + 1) % 3];
      const auto [twin, twins] = count(edgeKey(to, from));
      if (twins == 1 && count(edgeKey(from, to)).second == 1) neighbours[k] = &normals[twin->triangle];
    }
    activeEdges_[i] = detail::activeEdges<S>(getTriangle(i), normals[i], neighbours);
  }
}

template <Scalar S>
void TrimeshT<S>::computeMass() {
  const detail::PolyhedronMass<S> mass = detail::polyhedronMass<S>(vertices_, triangles_);
  enclosed_ = mass.volume;
  // Round-off leaves a flat, two-sided mesh a volume of a few ulps of its box.
  const S extent = (bounds_.max - bounds_.min).maxCoeff();
  const S noise = S(64) * std::numeric_limits<S>::epsilon() * extent * extent * extent;
  if (enclosed_ < -noise)
    throw detail::makeError(
        "Trimesh", "", "a closed Trimesh must be wound counter-clockwise seen from outside; volume (m^3)", enclosed_);
  if (enclosed_ <= noise) return;
  volume_ = mass.volume;
  center_ = mass.center;
  inertia_ = mass.inertia;
}

SPOOK_COMPILED_WITH_COLLIDERS(class, TrimeshT)

using Trimesh = TrimeshT<double>;
using TrimeshRef = ref_ptr<Trimesh>;
namespace f32 {
using Trimesh = TrimeshT<float>;
using TrimeshRef = ref_ptr<Trimesh>;
}  // namespace f32

}  // namespace spook
