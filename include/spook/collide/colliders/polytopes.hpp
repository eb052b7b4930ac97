#pragma once

#include <spook/collide/collider.hpp>
#include <spook/collide/detail/polytope_sat.hpp>
#include <spook/collide/shapes/box.hpp>
#include <spook/collide/shapes/convex.hpp>
#include <spook/collide/shapes/line.hpp>

namespace spook {

// Pairs of polytopes (boxes, hulls, segments) by the separating axis theorem
// over face normals and Gauss-map-pruned edge pairs (detail/polytope_sat.hpp):
// the exact penetration depth, and a clipped manifold where a face touches;
// two solids apart by less than the sink's margin across a face give that
// manifold as gap points.
// Box–box and box–line have their own, leaner colliders.

namespace detail {
template <class A, class B>
struct PolytopeCollider {
  using S = typename A::Vec3::Scalar;
  static void collide(const A& a, const TransformT<S>& X_WA, const B& b, const TransformT<S>& X_WB,
                      ContactSinkT<S>& sink) {
    thread_local Polytope pa, pb;
    makePolytope(a, X_WA, pa);
    makePolytope(b, X_WB, pb);
    // Solids give gap points; a segment (a line) has no face to give them.
    collidePolytopes(pa, pb, sink, !pa.faces.empty() && !pb.faces.empty());
  }
};
}  // namespace detail

template <Scalar S>
struct Collider<BoxT<S>, ConvexT<S>> : detail::PolytopeCollider<BoxT<S>, ConvexT<S>> {};
template <Scalar S>
struct Collider<ConvexT<S>, ConvexT<S>> : detail::PolytopeCollider<ConvexT<S>, ConvexT<S>> {};
template <Scalar S>
struct Collider<ConvexT<S>, LineT<S>> : detail::PolytopeCollider<ConvexT<S>, LineT<S>> {};

}  // namespace spook
