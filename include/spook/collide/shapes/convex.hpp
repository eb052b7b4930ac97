#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <tuple>
#include <utility>
#include <vector>

#include <spook/collide/detail/convex_hull.hpp>
#include <spook/collide/detail/polyhedron_mass.hpp>
#include <spook/collide/shapes/shape.hpp>
#include <spook/core/implementation.hpp>

namespace spook {

/// The convex hull of a point cloud, in the shape frame of the points (m).
/// Only the hull's corners are kept: points inside it, or on its faces and
/// edges within getTolerance() (about 1e-7 of the cloud's size for double,
/// 16 ulps for float), are dropped, and coplanar triangles form one face.
template <Scalar S>
class ConvexT : public ShapeT<S> {
 public:
  static constexpr ShapeType kType = ShapeType::CONVEX;
  using Vec3 = spook::Vec3T<S>;
  using Mat3 = spook::Mat3T<S>;
  using Triangle = std::array<int, 3>;
  using Face = detail::ConvexFace<S>;
  /// A hull edge from corner `from` to corner `to`, as it runs in the loop
  /// of face `left`; face `right` is on its other side (-1 should the
  /// merged faces not share it whole).
  struct Edge {
    int from, to, left, right;
  };

  /// Hull of `points` (shape frame, m). Throws on a non-finite point, and
  /// unless the points span a volume (not all coplanar within the tolerance).
  explicit ConvexT(const std::vector<Vec3>& points);

  /// Hull corners, shape frame (m).
  [[nodiscard]] const std::vector<Vec3>& getVertices() const { return vertices_; }
  /// Triangles as vertex indices, counter-clockwise seen from outside.
  [[nodiscard]] const std::vector<Triangle>& getTriangles() const { return triangles_; }
  /// Polygon faces (coplanar triangles merged): corner loop, unit outward normal, offset (m).
  [[nodiscard]] const std::vector<Face>& getFaces() const { return faces_; }

  /// The edges between polygon faces (none inside a merged face).
  [[nodiscard]] const std::vector<Edge>& getEdges() const { return edges_; }

  /// Distance within which input points were taken as lying on a face (m);
  /// every input point is inside the hull or at most about twice this outside.
  [[nodiscard]] S getTolerance() const { return tolerance_; }

  /// Which kind of shape this is.
  [[nodiscard]] ShapeType getType() const override { return kType; }
  bool collideWithLowerRank(const TransformT<S>& X_WA, const ShapeT<S>& other, const TransformT<S>& X_WB,
                            ContactSinkT<S>& sink) const override {
    return detail::collideWithLowerRank(*this, X_WA, other, X_WB, sink);
  }

  /// Volume of the hull (m³).
  [[nodiscard]] S getVolume() const override { return volume_; }

  /// Center of volume, shape frame (m).
  [[nodiscard]] Vec3 getCenterOfVolume() const override { return center_; }

  /// About the shape origin: I = m/V · I_c + m (|c|² 1 − c cᵀ), with I_c the
  /// unit-density tensor about the center c (kg·m²).
  [[nodiscard]] SPDMat3T<S> calculateInertia(S mass) const override;

  /// Box around the corners, shape frame (m).
  [[nodiscard]] BoundingBoxT<S> getBoundingBox() const override;

  /// The corner farthest along `direction`, shape frame (m): a scan of the
  /// corners for small hulls, a climb along the hull's edges for large ones.
  [[nodiscard]] Vec3 support(const Vec3& direction) const { return vertices_[supportIndex(direction)]; }

  /// The face or edge at the support corner that is across `direction`
  /// within the feature angle (SupportingFeatureT), else that corner. A
  /// face of more corners than the feature holds keeps every k-th.
  void supportingFeature(const Vec3& direction, SupportingFeatureT<S>& out) const {
    out.count = 0;
    const std::size_t top = supportIndex(direction);
    const S length = direction.norm();
    if (length > S(0)) {
      const int face = nearestFaceAt(top, direction);
      if (face >= 0 &&
          faces_[static_cast<std::size_t>(face)].normal.dot(direction) >= S(kSupportingFeatureCos) * length) {
        const auto& loop = faces_[static_cast<std::size_t>(face)].vertices;
        const std::size_t n = loop.size(), kept = std::min(n, SupportingFeatureT<S>::kCapacity);
        for (std::size_t k = 0; k < kept; ++k) out.add(vertices_[static_cast<std::size_t>(loop[k * n / kept])]);
        return;
      }
      int edge = -1;
      S flattest = S(kSupportingFeatureSin);
      for (int k = adjacencyStart_[top]; k < adjacencyStart_[top + 1]; ++k) {
        const Vec3 along = vertices_[static_cast<std::size_t>(adjacency_[k])] - vertices_[top];
        const S along_length = along.norm();
        if (!(along_length > S(0))) continue;
        if (const S slope = std::abs(along.dot(direction)) / (along_length * length); slope <= flattest)
          flattest = slope, edge = adjacency_[k];
      }
      if (edge >= 0) {
        out.add(vertices_[top]);
        out.add(vertices_[static_cast<std::size_t>(edge)]);
        return;
      }
    }
    out.add(vertices_[top]);
  }

  /// Of the faces at the corner farthest along `direction`, the one whose
  /// normal is nearest to it: an index into getFaces() (-1 without faces).
  [[nodiscard]] int supportingFace(const Vec3& direction) const {
    return nearestFaceAt(supportIndex(direction), direction);
  }

 protected:
  ~ConvexT() override = default;

 private:
  static constexpr std::size_t kScanLimit = 64;

  [[nodiscard]] std::size_t supportIndex(const Vec3& direction) const {
    std::size_t best = 0;
    S bestDot = vertices_[0].dot(direction);
    if (vertices_.size() <= kScanLimit) {
      for (std::size_t i = 1; i < vertices_.size(); ++i)
        if (const S d = vertices_[i].dot(direction); d > bestDot) best = i, bestDot = d;
      return best;
    }
    // On a convex polyhedron a corner no neighbour beats is the farthest.
    for (bool climbed = true; climbed;) {
      climbed = false;
      for (int k = adjacencyStart_[best]; k < adjacencyStart_[best + 1]; ++k) {
        const auto j = static_cast<std::size_t>(adjacency_[k]);
        if (const S d = vertices_[j].dot(direction); d > bestDot) best = j, bestDot = d, climbed = true;
      }
    }
    return best;
  }

  // Of the faces around corner `corner`, the one whose normal is nearest to
  // `direction` (-1: none).
  [[nodiscard]] int nearestFaceAt(std::size_t corner, const Vec3& direction) const {
    int face = -1;
    S nearest = -std::numeric_limits<S>::infinity();
    for (int k = vertexFacesStart_[corner]; k < vertexFacesStart_[corner + 1]; ++k)
      if (const S c = faces_[static_cast<std::size_t>(vertexFaces_[k])].normal.dot(direction); c > nearest)
        nearest = c, face = vertexFaces_[k];
    return face;
  }

  // The polygon faces around each corner, in compressed rows.
  void buildVertexFaces();

  // Neighbours of each corner along the triangles' edges, in compressed rows.
  void buildAdjacency();

  // Each face loop edge meets the reversed edge of exactly one other face.
  void buildEdges();

  std::vector<Vec3> vertices_;
  std::vector<Edge> edges_;
  std::vector<Triangle> triangles_;
  std::vector<Face> faces_;
  S tolerance_ = S(0);
  S volume_ = S(0);
  Vec3 center_ = Vec3::Zero();
  Mat3 unitInertia_ = Mat3::Zero();  // unit density, about center_ (m⁵)
  std::vector<int> adjacency_;
  std::vector<int> adjacencyStart_;
  std::vector<int> vertexFaces_;
  std::vector<int> vertexFacesStart_;
};

template <Scalar S>
ConvexT<S>::ConvexT(const std::vector<Vec3>& points) {
  for (const Vec3& p : points)
    if (!p.allFinite()) throw detail::makeError("Convex", "", "points must be finite (m)", p);
  auto hull = detail::convexHull<S>(points);
  if (!hull) throw detail::makeError("Convex", "", "needs at least 4 non-coplanar points", points.size());
  vertices_ = std::move(hull->vertices);
  triangles_ = std::move(hull->triangles);
  faces_ = std::move(hull->faces);
  tolerance_ = hull->tolerance;

  // Mass properties in double, whatever S, from the exact corner positions.
  std::vector<spook::Vec3T<double>> corners;
  for (const Vec3& v : vertices_) corners.push_back(v.template cast<double>());
  const auto mass = detail::polyhedronMass<double>(corners, triangles_);
  volume_ = S(mass.volume);
  center_ = mass.center.template cast<S>();
  unitInertia_ = mass.inertia.template cast<S>();
  buildAdjacency();
  buildEdges();
  buildVertexFaces();
}

template <Scalar S>
auto ConvexT<S>::calculateInertia(S mass) const -> SPDMat3T<S> {
  this->requireMass("Convex", mass);
  const Vec3& c = center_;
  return SPDMat3T<S>(
      Mat3((mass / volume_) * unitInertia_ + mass * (c.squaredNorm() * Mat3::Identity() - c * c.transpose())));
}

template <Scalar S>
auto ConvexT<S>::getBoundingBox() const -> BoundingBoxT<S> {
  BoundingBoxT<S> box{vertices_.front(), vertices_.front()};
  for (const Vec3& v : vertices_) {
    box.min = box.min.cwiseMin(v);
    box.max = box.max.cwiseMax(v);
  }
  return box;
}

template <Scalar S>
void ConvexT<S>::buildVertexFaces() {
  std::vector<std::vector<int>> around(vertices_.size());
  for (std::size_t f = 0; f < faces_.size(); ++f)
    for (const int v : faces_[f].vertices) around[static_cast<std::size_t>(v)].push_back(static_cast<int>(f));
  vertexFacesStart_.assign(1, 0);
  for (const auto& list : around) {
    vertexFaces_.insert(vertexFaces_.end(), list.begin(), list.end());
    vertexFacesStart_.push_back(static_cast<int>(vertexFaces_.size()));
  }
}

template <Scalar S>
void ConvexT<S>::buildAdjacency() {
  std::vector<std::vector<int>> neighbours(vertices_.size());
  for (const Triangle& t : triangles_)
    for (int i = 0; i < 3; ++i) {
      auto& list = neighbours[static_cast<std::size_t>(t[i])];
      const int other = t[(i + 1) % 3];
      if (std::find(list.begin(), list.end(), other) == list.end()) list.push_back(other);
      auto& back = neighbours[static_cast<std::size_t>(other)];
      if (std::find(back.begin(), back.end(), t[i]) == back.end()) back.push_back(t[i]);
    }
  adjacencyStart_.assign(1, 0);
  for (const auto& list : neighbours) {
    adjacency_.insert(adjacency_.end(), list.begin(), list.end());
    adjacencyStart_.push_back(static_cast<int>(adjacency_.size()));
  }
}

template <Scalar S>
void ConvexT<S>::buildEdges() {
  struct HalfEdge {
    int low, high, from, to, face;
  };
  std::vector<HalfEdge> halves;
  for (std::size_t f = 0; f < faces_.size(); ++f) {
    const auto& loop = faces_[f].vertices;
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const int a = loop[k], b = loop[(k + 1) % loop.size()];
      halves.push_back({std::min(a, b), std::max(a, b), a, b, static_cast<int>(f)});
    }
  }
  std::sort(halves.begin(), halves.end(),
            [](const HalfEdge& x, const HalfEdge& y) { return std::tie(x.low, x.high) < std::tie(y.low, y.high); });
  for (std::size_t k = 0; k < halves.size();) {
    const bool paired =
        k + 1 < halves.size() && halves[k + 1].low == halves[k].low && halves[k + 1].high == halves[k].high;
    edges_.push_back({halves[k].from, halves[k].to, halves[k].face, paired ? halves[k + 1].face : -1});
    k += paired ? 2 : 1;
  }
}

SPOOK_COMPILED_WITH_COLLIDERS(class, ConvexT)

using Convex = ConvexT<double>;
using ConvexRef = ref_ptr<Convex>;
namespace f32 {
using Convex = ConvexT<float>;
using ConvexRef = ref_ptr<Convex>;
}  // namespace f32

}  // namespace spook
