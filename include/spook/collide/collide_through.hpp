#pragma once

// The narrow phase of a space for a shape list (detail::collideThrough,
// declared in collide/space.hpp) with all its colliders. Included by
// space.hpp in a header-only program and where a collider part is compiled
// (core/implementation.hpp); a program that compiles spook once includes it
// itself to build a Space or Simulation for a shape list of its own. The
// full list goes through the shapes (collide/shape_dispatch.hpp), any
// other through its collider matrix.

#include <type_traits>

#include <spook/collide/collider_matrix.hpp>
#include <spook/collide/shape_dispatch.hpp>
#include <spook/collide/space.hpp>

namespace spook {

namespace detail {

template <Scalar S, class List>
bool collideThrough(const ShapeT<S>& a, const TransformT<S>& X_WA, const ShapeT<S>& b, const TransformT<S>& X_WB,
                    ContactSinkT<S>& sink) {
  if constexpr (std::is_same_v<List, AllShapes>)
    return collideShapes<S>(a, X_WA, b, X_WB, sink);
  else
    return ColliderMatrixT<S, List>::collide(a, X_WA, b, X_WB, sink);
}

template <class List>
struct CollidersDefined {};

}  // namespace detail

#if defined(SPOOK_IMPLEMENT_COLLIDERS_DOUBLE)
template class ColliderMatrixT<double, AllShapes>;
template bool detail::collideThrough<double, AllShapes>(const ShapeT<double>&, const TransformT<double>&,
                                                        const ShapeT<double>&, const TransformT<double>&,
                                                        ContactSinkT<double>&);
#endif
#if defined(SPOOK_IMPLEMENT_COLLIDERS_FLOAT)
template class ColliderMatrixT<float, AllShapes>;
template bool detail::collideThrough<float, AllShapes>(const ShapeT<float>&, const TransformT<float>&,
                                                       const ShapeT<float>&, const TransformT<float>&,
                                                       ContactSinkT<float>&);
#endif

}  // namespace spook
