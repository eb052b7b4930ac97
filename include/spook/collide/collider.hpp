#pragma once

#include <concepts>

#include <spook/collide/contact_sink.hpp>
#include <spook/collide/detail/ccd_bridge.hpp>
#include <spook/collide/shapes/shape.hpp>

namespace spook {

/// A shape with a support function `support(direction)` in its own frame:
/// every convex shape, which libccd can then collide with any other.
template <class T>
concept ConvexShape = requires(const T& shape, const typename T::Vec3& direction) {
  { shape.support(direction) } -> std::convertible_to<typename T::Vec3>;
};

/// The collider of an ordered shape pair (A, B) with A::kType <= B::kType:
/// `Collider<A, B>::collide(a, X_WA, b, X_WB, sink)` writes the contact
/// points of a placed at X_WA and b placed at X_WB (shape frame → world).
/// Analytic pairs specialize it, one file per pair in colliders/; a pair of
/// convex shapes without one goes through libccd; any other pair has none
/// (a hole in the collider matrix). The colliders of spheres, boxes,
/// capsules, cylinders and hulls with planes, of spheres and capsules with
/// each other, and of those five shapes with a box's, a hull's and a mesh
/// triangle's faces (round shapes with a hull in colliders/convex_round.hpp)
/// also write the gap points within the sink's speculative margin (where
/// the gap closes at its linear rate, up to the curvature of two round
/// shapes); the others (a cylinder with a sphere, a capsule or a cylinder,
/// lines, two meshes) write touching points only. Off a face's edge, or
/// beside a face flush with it, a gap point would stop a body that slides
/// or rolls over the seam of two flush boxes (a ghost contact).
template <class A, class B>
struct Collider {};

template <ConvexShape A, ConvexShape B>
struct Collider<A, B> {
  using S = typename A::Vec3::Scalar;
  static void collide(const A& a, const TransformT<S>& X_WA, const B& b, const TransformT<S>& X_WB,
                      ContactSinkT<S>& sink) {
    detail::collideByCcd<S>(a, X_WA, b, X_WB, sink);
  }
};

/// True when the ordered pair (A, B) has a collider.
template <class A, class B>
concept HasCollider = requires(const A& a, const B& b, const TransformT<typename A::Vec3::Scalar>& X,
                               ContactSinkT<typename A::Vec3::Scalar>& sink) {
  Collider<A, B>::collide(a, X, b, X, sink);
};

/// Collides a and b in either order: the pair is handed to its collider with
/// the lower ShapeType first, and the sink flips the normals back. This is
/// the one place where a reversed pair is handled.
template <class A, class B>
  requires(A::kType <= B::kType ? HasCollider<A, B> : HasCollider<B, A>)
void collide(const A& a, const TransformT<typename A::Vec3::Scalar>& X_WA, const B& b,
             const TransformT<typename A::Vec3::Scalar>& X_WB, ContactSinkT<typename A::Vec3::Scalar>& sink) {
  if constexpr (A::kType <= B::kType) {
    Collider<A, B>::collide(a, X_WA, b, X_WB, sink);
  } else {
    ContactSinkT<typename A::Vec3::Scalar> reversed = sink.reversed();
    Collider<B, A>::collide(b, X_WB, a, X_WA, reversed);
  }
}

}  // namespace spook
