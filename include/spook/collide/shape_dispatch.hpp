#pragma once

// The default narrow phase (every shape type): a pair goes to the shape of
// the higher dispatchRank, whose ShapeT::collideWithLowerRank holds the
// colliders with the types ranked at or below its own. That member is
// compiled where the shape type's virtual table is, with its constructor:
// a header-only program compiles the colliders among the shape types it
// constructs (and those ranked below them) instead of every pair. Included
// with collide/collide_through.hpp.

#include <spook/collide/all_shapes.hpp>
#include <spook/collide/collider.hpp>
#include <spook/collide/colliders.hpp>

namespace spook::detail {

/// The contacts of a at X_WA with b at X_WB (normals from a toward b),
/// asked of the higher-ranked shape. False, writing nothing, for a pair
/// without a collider. A composite is taken apart first (a's before b's),
/// so that each pair of children meets its collider in the order the
/// collider matrix hands it over (a collider of two shapes of one type
/// need not be symmetric to the bit).
template <Scalar S>
bool collideShapes(const ShapeT<S>& a, const TransformT<S>& X_WA, const ShapeT<S>& b, const TransformT<S>& X_WB,
                   ContactSinkT<S>& sink) {
  // A composite pairs with every shape; a child without a collider for
  // the other shape is skipped.
  if (a.getType() == ShapeType::COMPOSITE) {
    for (const auto& child : static_cast<const CompositeT<S>&>(a).getChildren())
      collideShapes<S>(*child.shape, X_WA * child.transform, b, X_WB, sink);
    return true;
  }
  if (b.getType() == ShapeType::COMPOSITE) {
    for (const auto& child : static_cast<const CompositeT<S>&>(b).getChildren())
      collideShapes<S>(a, X_WA, *child.shape, X_WB * child.transform, sink);
    return true;
  }
  if (dispatchRank(a.getType()) >= dispatchRank(b.getType())) return a.collideWithLowerRank(X_WA, b, X_WB, sink);
  ContactSinkT<S> reversed = sink.reversed();
  return b.collideWithLowerRank(X_WB, a, X_WA, reversed);
}

/// The pair (A, B) for a B ranked at or below A, else nothing: the pair is
/// then the other shape's to collide.
template <class A, class B>
bool collideRankedPair(const A& a, const TransformT<typename A::Vec3::Scalar>& X_WA,
                       const ShapeT<typename A::Vec3::Scalar>& b, const TransformT<typename A::Vec3::Scalar>& X_WB,
                       ContactSinkT<typename A::Vec3::Scalar>& sink) {
  if constexpr (dispatchRank(B::kType) > dispatchRank(A::kType)) {
    return false;
  } else if constexpr (A::kType <= B::kType ? HasCollider<A, B> : HasCollider<B, A>) {
    spook::collide(a, X_WA, static_cast<const B&>(b), X_WB, sink);
    return true;
  } else {
    return false;
  }
}

template <class A>
bool collideWithLowerRank(const A& a, const TransformT<typename A::Vec3::Scalar>& X_WA,
                          const ShapeT<typename A::Vec3::Scalar>& b, const TransformT<typename A::Vec3::Scalar>& X_WB,
                          ContactSinkT<typename A::Vec3::Scalar>& sink) {
  using S = typename A::Vec3::Scalar;
  if constexpr (A::kType == ShapeType::COMPOSITE) {
    return collideShapes<S>(a, X_WA, b, X_WB, sink);  // taken apart there
  } else {
    switch (b.getType()) {
      case ShapeType::BOX:
        return collideRankedPair<A, BoxT<S>>(a, X_WA, b, X_WB, sink);
      case ShapeType::CAPSULE:
        return collideRankedPair<A, CapsuleT<S>>(a, X_WA, b, X_WB, sink);
      case ShapeType::CONVEX:
        return collideRankedPair<A, ConvexT<S>>(a, X_WA, b, X_WB, sink);
      case ShapeType::CYLINDER:
        return collideRankedPair<A, CylinderT<S>>(a, X_WA, b, X_WB, sink);
      case ShapeType::LINE:
        return collideRankedPair<A, LineT<S>>(a, X_WA, b, X_WB, sink);
      case ShapeType::PLANE:
        return collideRankedPair<A, PlaneT<S>>(a, X_WA, b, X_WB, sink);
      case ShapeType::SPHERE:
        return collideRankedPair<A, SphereT<S>>(a, X_WA, b, X_WB, sink);
      case ShapeType::TRIMESH:
        return collideRankedPair<A, TrimeshT<S>>(a, X_WA, b, X_WB, sink);
      case ShapeType::COMPOSITE:
        return false;  // taken apart by collideShapes
      case ShapeType::HEIGHTFIELD:
        return collideRankedPair<A, HeightFieldT<S>>(a, X_WA, b, X_WB, sink);
    }
    return false;
  }
}

}  // namespace spook::detail
