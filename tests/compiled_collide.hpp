#pragma once

// The collider tests collide through the narrow phase compiled once in
// spook::spook_compiled (detail::collideThrough over AllShapes, the entry
// every Space uses): a pair runs as it does in a simulation, and these
// programs do not compile the colliders a second time.

#include <doctest/doctest.h>

#include <spook/collide/all_shapes.hpp>
#include <spook/collide/space.hpp>

namespace spook::test {

template <class A, class B>
void collideCompiled(const A& a, const TransformT<typename A::Vec3::Scalar>& X_WA, const B& b,
                     const TransformT<typename A::Vec3::Scalar>& X_WB,
                     ContactSinkT<typename A::Vec3::Scalar>& sink) {
  using S = typename A::Vec3::Scalar;
  if (!detail::collideThrough<S, AllShapes>(a, X_WA, b, X_WB, sink))
    FAIL("the collider matrix has no collider for shape types ", int(A::kType), " and ", int(B::kType));
}

}  // namespace spook::test
