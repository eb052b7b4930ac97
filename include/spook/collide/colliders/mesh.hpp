#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <spook/collide/collider.hpp>
#include <spook/collide/contact_point.hpp>
#include <spook/collide/detail/capsule_triangle.hpp>
#include <spook/collide/detail/ccd_bridge.hpp>
#include <spook/collide/detail/cylinder_triangle.hpp>
#include <spook/collide/detail/polytope_sat.hpp>
#include <spook/collide/detail/triangle.hpp>
#include <spook/collide/shapes/box.hpp>
#include <spook/collide/shapes/convex.hpp>
#include <spook/collide/shapes/height_field.hpp>
#include <spook/collide/shapes/line.hpp>
#include <spook/collide/shapes/plane.hpp>
#include <spook/collide/shapes/sphere.hpp>
#include <spook/collide/shapes/trimesh.hpp>

namespace spook {

namespace detail {

/// A triangle soup: a Trimesh or a HeightField, both of which visit the
/// triangles overlapping a box of their own frame.
template <class T>
concept TriangleSoup = T::kType == ShapeType::TRIMESH || T::kType == ShapeType::HEIGHTFIELD;

/// Sphere against one triangle: a contact when the triangle's closest point
/// to the center lies within the radius. The normal, from the sphere toward
/// the mesh, is the face normal when that point is inside the face (exact,
/// where c − q is all round-off for a center near the face) and along
/// c − q otherwise; a center on an edge or corner pushes along the face
/// normal. A trimesh's face pushes the sphere out on the side of its center;
/// a height field is solid below its surface (`solidBehind`): a center
/// behind a face is pushed back out the front, by r plus its distance
/// behind, and a center behind the face's plane beside the face is left to
/// the face it lies under. Apart by up to the sink's margin over the face
/// (the center above the triangle, on its front), the sphere's lowest point
/// is a gap point; over an edge or a corner none (a ghost contact where a
/// ball rolls from one triangle onto the next). Without them a ball set 1
/// cm above a height field fell a step of free fall into it (8.8 cm at
/// h = 0.1 s), as onto a box it did not.
template <Scalar S>
void collideSphereTriangle(const SphereT<S>& sphere, const Vec3T<S>& c_W, const Triangle<S>& t_W,
                           ContactSinkT<S>& sink, bool solidBehind = false) {
  bool onFace = false;
  const Vec3T<S> q = closestOnTriangle<S>(t_W, c_W, onFace);
  const Vec3T<S> toCenter = c_W - q;
  const S distance = toCenter.norm();
  const S r = sphere.getRadius();
  if (distance > r) {
    if (!sink.accepts(r - distance)) return;
    const Vec3T<S> front = t_W.normal();
    const S height = front.dot(toCenter);
    // Over the face: q is the center's foot (on an edge, to round-off).
    if (!(height > S(0)) || (!onFace && (toCenter - height * front).norm() > S(1e-6) * distance)) return;
    sink.addSpeculative(q + front * ((height - r) * S(0.5)), Vec3T<S>(-front), r - height);
    return;
  }
  const Vec3T<S> faceNormal = t_W.normal();
  const bool behind = toCenter.dot(faceNormal) < S(0);
  if (solidBehind && behind && !onFace) return;
  Vec3T<S> n;
  S depth = r - distance;
  if (solidBehind && behind) {
    n = -faceNormal;
    depth = r + distance;
  } else if (onFace)
    n = behind ? faceNormal : Vec3T<S>(-faceNormal);
  else
    n = distance > ScalarTraits<S>::epsilon() * r ? Vec3T<S>(-toCenter / distance) : Vec3T<S>(-faceNormal);
  sink.add(q + n * (depth * S(0.5)), n, depth);  // midway: q and c + n r bound the overlap
}

template <class A>
inline constexpr bool kIsPolytope =
    A::kType == ShapeType::BOX || A::kType == ShapeType::CONVEX || A::kType == ShapeType::LINE;

/// What collideWithTriangles reports: the surface's contacts (the
/// colliders' choice), or each triangle's own, as a convex shape alone.
enum class TriangleContacts { SURFACE, PER_TRIANGLE };

/// Adds the points `found` against a soup's triangles to the sink, of two
/// alike (closer than `alike` (m), normals within kAlikeNormalAngle) the
/// deeper only (the first found on a tie); every point for alike < 0. Found
/// along the points sorted by x. (Not per shape pair: one copy per scalar.)
template <Scalar S>
void addDistinctSurfaceContacts(const std::vector<ContactPointT<S>>& found, S alike, ContactSinkT<S>& sink) {
  thread_local std::vector<std::size_t> order;
  thread_local std::vector<char> kept;
  kept.assign(found.size(), 1);
  if (alike >= S(0)) {
    const S parallel = S(std::cos(kAlikeNormalAngle));
    order.resize(found.size());
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
    std::sort(order.begin(), order.end(),
              [&](std::size_t i, std::size_t j) { return found[i].point.x() < found[j].point.x(); });
    for (std::size_t m = 0; m < order.size(); ++m)
      for (std::size_t l = m + 1; l < order.size() && found[order[l]].point.x() - found[order[m]].point.x() <= alike;
           ++l) {
        const std::size_t i = std::min(order[m], order[l]), j = std::max(order[m], order[l]);
        const ContactPointT<S>&p = found[i], &q = found[j];
        if ((p.point - q.point).norm() <= alike && p.normal.dot(q.normal) >= parallel)
          kept[q.depth > p.depth ? i : j] = 0;
      }
  }
  for (std::size_t k = 0; k < found.size(); ++k) {
    if (!kept[k]) continue;
    const ContactPointT<S>& c = found[k];
    sink.setFaceIndices(0, c.faceIndex2);
    sink.addSpeculative(c.point, c.normal, c.depth);
  }
  sink.setFaceIndices(0, 0);
}

/// A Trimesh or a HeightField as collideWithTriangles sees it: the
/// triangles near a box of its frame, their active edges, and whether it is
/// solid below its surface (a height field). One copy of the per-triangle
/// work per shape then serves both kinds of soup.
template <Scalar S>
struct TriangleSoupView {
  /// Called with `context`, the triangle's index and its corners (soup frame).
  using Visit = void (*)(void* context, std::size_t i, const Vec3T<S>& p0, const Vec3T<S>& p1, const Vec3T<S>& p2);
  const void* soup;
  void (*forEachTriangle)(const void* soup, const BoundingBoxT<S>& localBox, Visit visit, void* context);
  std::uint8_t (*activeEdges)(const void* soup, std::size_t i);
  bool heightField;
};

template <Scalar S, class Soup>
[[nodiscard]] TriangleSoupView<S> triangleSoupOf(const Soup& soup) {
  using Visit = typename TriangleSoupView<S>::Visit;
  return {&soup,
          [](const void* s, const BoundingBoxT<S>& box, Visit visit, void* context) {
            static_cast<const Soup*>(s)->forEachTriangle(
                box, [&](std::size_t i, const Vec3T<S>& p0, const Vec3T<S>& p1, const Vec3T<S>& p2) {
                  visit(context, i, p0, p1, p2);
                });
          },
          [](const void* s, std::size_t i) { return static_cast<const Soup*>(s)->getActiveEdges(i); },
          Soup::kType == ShapeType::HEIGHTFIELD};
}

/// Contacts of a shape against the triangles of a soup near it, each
/// triangle a convex shape of its own: boxes, hulls and segments by the
/// separating axes with a clipped manifold (polytope_sat.hpp), spheres and
/// capsules in closed form (capsule_triangle.hpp), cylinders over the
/// candidate normals (cylinder_triangle.hpp). For the SURFACE, each
/// triangle's normals are then held to its active edges
/// (activeEdgeNormals), and a point that two triangles found alike (on the
/// edge they share: closer than the spread of a sampled feature, normals
/// within 1°) is kept once, so that a flat region of many triangles pushes
/// like one face.
template <Scalar S, class A>
void collideWithSoup(const A& a, const TransformT<S>& X_WA, const TriangleSoupView<S>& soup, const TransformT<S>& X_WM,
                     ContactSinkT<S>& sink, TriangleContacts report) {
  const BoundingBoxT<S> boxA = a.getBoundingBox();
  BoundingBoxT<S> grown = boxA.grownBy(S(kTouchingGap));
  // The gap points of spheres (collideSphereTriangle), capsules
  // (collideCapsuleTriangle), cylinders (collideCylinderTriangle), boxes and
  // hulls (collidePolytopes).
  if constexpr (A::kType == ShapeType::CYLINDER || A::kType == ShapeType::BOX || A::kType == ShapeType::CONVEX ||
                A::kType == ShapeType::SPHERE || A::kType == ShapeType::CAPSULE) {
    grown.min.array() -= sink.margin();
    grown.max.array() += sink.margin();
  }
  const BoundingBoxT<S> box_M = transformBox<S>(grown, X_WM.inverse() * X_WA);
  thread_local Polytope shape, triangle;
  thread_local std::vector<ContactPointT<S>> points, found;
  found.clear();
  if constexpr (kIsPolytope<A>) makePolytope(a, X_WA, shape);
  auto visit = [&](std::size_t i, const Vec3T<S>& p0, const Vec3T<S>& p1, const Vec3T<S>& p2) {
    const Triangle<S> t_W{{X_WM * p0, X_WM * p1, X_WM * p2}};
    points.clear();
    ContactSinkT<S> staged = sink.staging(points);
    staged.setFaceIndices(0, i);
    if constexpr (A::kType == ShapeType::SPHERE) {
      collideSphereTriangle<S>(a, X_WA.translation(), t_W, staged, soup.heightField);
    } else if constexpr (kIsPolytope<A>) {
      makeTrianglePolytope<S>(t_W, triangle);
      collidePolytopes(shape, triangle, staged, !shape.faces.empty());
    } else if constexpr (A::kType == ShapeType::CAPSULE) {
      collideCapsuleTriangle<S>(a, X_WA, Triangle<S>{{p0, p1, p2}}, X_WM, staged);
    } else if constexpr (A::kType == ShapeType::CYLINDER) {
      collideCylinderTriangle<S>(a, X_WA, Triangle<S>{{p0, p1, p2}}, X_WM, staged,
                                 report == TriangleContacts::SURFACE ? soup.activeEdges(soup.soup, i) : 0b111111);
    } else {
      const Triangle<S> t_M{{p0, p1, p2}};
      collideByCcd<S>(a, X_WA, t_M, X_WM, staged);
    }
    if (points.empty()) return;
    if (report == TriangleContacts::SURFACE)
      activeEdgeNormals<S>(t_W, soup.activeEdges(soup.soup, i), points, soup.heightField, X_WA.translation());
    found.insert(found.end(), points.begin(), points.end());
  };
  soup.forEachTriangle(
      soup.soup, box_M,
      [](void* context, std::size_t i, const Vec3T<S>& p0, const Vec3T<S>& p1, const Vec3T<S>& p2) {
        (*static_cast<decltype(visit)*>(context))(i, p0, p1, p2);
      },
      &visit);
  addDistinctSurfaceContacts<S>(
      found, report == TriangleContacts::SURFACE ? S(4.0 * kFeatureTilt) * boxA.halfExtents().norm() : S(-1), sink);
}

/// collideWithSoup against a Trimesh or a HeightField.
template <Scalar S, class A, class Soup>
void collideWithTriangles(const A& a, const TransformT<S>& X_WA, const Soup& soup, const TransformT<S>& X_WM,
                          ContactSinkT<S>& sink, TriangleContacts report = TriangleContacts::SURFACE) {
  collideWithSoup<S>(a, X_WA, triangleSoupOf<S>(soup), X_WM, sink, report);
}

/// Triangle pairs of two soups whose boxes overlap, each collided by libccd
/// (one contact per pair: the deepest).
template <Scalar S, class SoupA, class SoupB>
void collideSoups(const SoupA& a, const TransformT<S>& X_WA, const SoupB& b, const TransformT<S>& X_WB,
                  ContactSinkT<S>& sink) {
  const TransformT<S> X_BA = X_WB.inverse() * X_WA;
  const BoundingBoxT<S> a_B = transformBox<S>(a.getBoundingBox(), X_BA);
  b.forEachTriangle(a_B, [&](std::size_t j, const Vec3T<S>& q0, const Vec3T<S>& q1, const Vec3T<S>& q2) {
    const Triangle<S> t_B{{q0, q1, q2}};
    const BoundingBoxT<S> t_A = transformBox<S>(t_B.getBoundingBox(), X_BA.inverse());
    a.forEachTriangle(t_A, [&](std::size_t i, const Vec3T<S>& p0, const Vec3T<S>& p1, const Vec3T<S>& p2) {
      const Triangle<S> t_A2{{p0, p1, p2}};
      sink.setFaceIndices(i, j);
      collideByCcd<S>(t_A2, X_WA, t_B, X_WB, sink, false);
    });
  });
  sink.setFaceIndices(0, 0);
}

/// Every vertex of `points` (frame A) at or below the plane is a contact,
/// with the normal from the points' shape into the plane (−n); one above it
/// by less than the sink's margin is a gap point.
template <Scalar S, class Points>
void collideVerticesWithPlane(const Points& vertices, const TransformT<S>& X_WA, const PlaneT<S>& plane,
                              const TransformT<S>& X_WP, ContactSinkT<S>& sink, bool planeFirst) {
  const Vec3T<S> n = X_WP.linear() * plane.getNormal();
  const Vec3T<S> o = X_WP * plane.getPoint();
  for (const auto& v : vertices) {
    const Vec3T<S> p = X_WA * v;
    const S height = n.dot(p - o);
    if (!sink.accepts(-height)) continue;
    const Vec3T<S> mid = p - n * (height * S(0.5));
    sink.addSpeculative(mid, planeFirst ? n : Vec3T<S>(-n), -height);
  }
}

}  // namespace detail

/// A convex shape against a triangle mesh or a height field, triangle by
/// triangle among those the mesh's hierarchy (or grid) finds near it.
template <ConvexShape A, detail::TriangleSoup B>
requires(A::kType < B::kType) struct Collider<A, B> {
  using S = typename A::Vec3::Scalar;
  static void collide(const A& a, const TransformT<S>& X_WA, const B& b, const TransformT<S>& X_WB,
                      ContactSinkT<S>& sink) {
    detail::collideWithTriangles<S>(a, X_WA, b, X_WB, sink);
  }
};

/// Plane–trimesh: the mesh vertices at or below the plane (gap points above
/// it within the margin).
template <Scalar S>
struct Collider<PlaneT<S>, TrimeshT<S>> {
  static void collide(const PlaneT<S>& a, const TransformT<S>& X_WA, const TrimeshT<S>& b, const TransformT<S>& X_WB,
                      ContactSinkT<S>& sink) {
    detail::collideVerticesWithPlane<S>(b.getVertices(), X_WB, a, X_WA, sink, true);
  }
};

/// Convex–plane: the hull vertices at or below the plane; apart, the
/// corners within the margin of the face at its lowest corner most against
/// the plane (gap points), as the separating-axis colliders clip the
/// incident face: every vertex of a curved hull within the margin would
/// give the contact reduction a ring of high points to choose from.
template <Scalar S>
struct Collider<ConvexT<S>, PlaneT<S>> {
  static void collide(const ConvexT<S>& a, const TransformT<S>& X_WA, const PlaneT<S>& b, const TransformT<S>& X_WB,
                      ContactSinkT<S>& sink) {
    const Vec3T<S> n = X_WB.linear() * b.getNormal();
    const Vec3T<S> o = X_WB * b.getPoint();
    const auto& vertices = a.getVertices();
    const auto heightOf = [&](const Vec3T<S>& v) { return n.dot(X_WA * v - o); };
    const auto emit = [&](const Vec3T<S>& v, S height) {
      sink.addSpeculative(Vec3T<S>(X_WA * v - n * (height * S(0.5))), Vec3T<S>(-n), -height);
    };
    for (const auto& v : vertices)
      if (const S height = heightOf(v); height <= S(0)) emit(v, height);
    if (sink.margin() == S(0)) return;
    // Among the faces at the lowest corner (the most against the plane of
    // all faces need not be one of them).
    const int face = a.supportingFace(Vec3T<S>(-(X_WA.linear().transpose() * n)));
    if (face < 0) return;
    const auto* against = &a.getFaces()[static_cast<std::size_t>(face)];
    for (const int k : against->vertices) {
      const Vec3T<S>& v = vertices[static_cast<std::size_t>(k)];
      if (const S height = heightOf(v); height > S(0) && sink.accepts(-height)) emit(v, height);
    }
  }
};

/// Trimesh–trimesh and trimesh–height field: triangle pairs.
template <Scalar S>
struct Collider<TrimeshT<S>, TrimeshT<S>> {
  static void collide(const TrimeshT<S>& a, const TransformT<S>& X_WA, const TrimeshT<S>& b, const TransformT<S>& X_WB,
                      ContactSinkT<S>& sink) {
    detail::collideSoups<S>(a, X_WA, b, X_WB, sink);
  }
};
template <Scalar S>
struct Collider<TrimeshT<S>, HeightFieldT<S>> {
  static void collide(const TrimeshT<S>& a, const TransformT<S>& X_WA, const HeightFieldT<S>& b,
                      const TransformT<S>& X_WB, ContactSinkT<S>& sink) {
    detail::collideSoups<S>(a, X_WA, b, X_WB, sink);
  }
};

}  // namespace spook
