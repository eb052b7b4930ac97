#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <utility>

#include <spook/collide/all_shapes.hpp>
#include <spook/collide/collider.hpp>
#include <spook/collide/colliders.hpp>
#include <spook/collide/shape_list.hpp>
#include <spook/collide/shapes/composite.hpp>
#include <spook/collide/shapes/shape_type.hpp>

namespace spook {

template <Scalar S, class List>
class ColliderMatrixT;

/// The narrow phase of one shape list: a constexpr N×N table of collider
/// entry points, generated at compile time from the list, so that only the
/// colliders between listed shapes are instantiated. A pair without a
/// collider is a hole (nullptr). Composites are taken apart into their
/// children, which go through the same table.
template <Scalar S, template <Scalar> class... Shapes>
class ColliderMatrixT<S, ShapeList<Shapes...>> {
 public:
  using List = ShapeList<Shapes...>;
  using Shape = ShapeT<S>;
  using Transform = spook::TransformT<S>;
  using Sink = ContactSinkT<S>;
  using Function = void (*)(const Shape&, const Transform&, const Shape&, const Transform&, Sink&);
  static constexpr std::size_t N = sizeof...(Shapes);

  /// True when a and b are both listed and their pair has a collider.
  [[nodiscard]] static constexpr bool supports(ShapeType a, ShapeType b) {
    const int i = kIndex[static_cast<std::size_t>(a)], j = kIndex[static_cast<std::size_t>(b)];
    return i >= 0 && j >= 0 && kSupported[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
  }

  /// Contacts between a at X_WA and b at X_WB (shape → world), through the
  /// table. Returns false, writing nothing, for a pair the table lacks.
  static bool collide(const Shape& a, const Transform& X_WA, const Shape& b, const Transform& X_WB, Sink& sink);

  /// The same with both types known at compile time: no table, and a
  /// compile-time error for a shape outside the list.
  template <class A, class B>
  static void collide(const A& a, const Transform& X_WA, const B& b, const Transform& X_WB, Sink& sink) {
    static_assert(List::contains(A::kType), "the first shape's type is not in this shape list");
    static_assert(List::contains(B::kType), "the second shape's type is not in this shape list");
    static_assert(pairSupported<A, B>(), "this shape pair has no collider (a hole in the collider matrix)");
    entry<A, B>(a, X_WA, b, X_WB, sink);
  }

  /// The matrix as a markdown table, rows and columns in list order: X
  /// where a collider exists, - where the pair is a hole.
  [[nodiscard]] static std::string describe();

 private:
  static constexpr std::array<ShapeType, N> kTypes = {Shapes<S>::kType...};

  static constexpr std::array<int, kNumShapeTypes> makeIndex() {
    std::array<int, kNumShapeTypes> index{};
    index.fill(-1);
    for (std::size_t i = 0; i < N; ++i) index[static_cast<std::size_t>(kTypes[i])] = static_cast<int>(i);
    return index;
  }
  static constexpr std::array<int, kNumShapeTypes> kIndex = makeIndex();

  template <class A>
  static constexpr bool kIsComposite = A::kType == ShapeType::COMPOSITE;

  // A composite pairs with everything listed; its children are dispatched
  // at run time and skipped where the table has a hole.
  template <class A, class B>
  static constexpr bool pairSupported() {
    if constexpr (kIsComposite<A> || kIsComposite<B>)
      return true;
    else if constexpr (A::kType <= B::kType)
      return HasCollider<A, B>;
    else
      return HasCollider<B, A>;
  }

  template <class A, class B>
  static void entry(const Shape& a, const Transform& X_WA, const Shape& b, const Transform& X_WB, Sink& sink) {
    if constexpr (kIsComposite<A>) {
      for (const auto& child : static_cast<const A&>(a).getChildren())
        collide(*child.shape, X_WA * child.transform, b, X_WB, sink);
    } else if constexpr (kIsComposite<B>) {
      for (const auto& child : static_cast<const B&>(b).getChildren())
        collide(a, X_WA, *child.shape, X_WB * child.transform, sink);
    } else {
      spook::collide(static_cast<const A&>(a), X_WA, static_cast<const B&>(b), X_WB, sink);
    }
  }

  template <class A, class B>
  static constexpr Function make() {
    if constexpr (pairSupported<A, B>())
      return &entry<A, B>;
    else
      return nullptr;
  }
  template <class A>
  static constexpr std::array<Function, N> makeRow() {
    return {make<A, Shapes<S>>()...};
  }
  static constexpr std::array<std::array<Function, N>, N> kTable = {makeRow<Shapes<S>>()...};
  // The same holes without the entry points, for the queries: asking which
  // pairs are supported compiles no collider.
  template <class A>
  static constexpr std::array<bool, N> supportedRow() {
    return {pairSupported<A, Shapes<S>>()...};
  }
  static constexpr std::array<std::array<bool, N>, N> kSupported = {supportedRow<Shapes<S>>()...};
};

template <Scalar S, template <Scalar> class... Shapes>
bool ColliderMatrixT<S, ShapeList<Shapes...>>::collide(const Shape& a, const Transform& X_WA, const Shape& b,
                                                       const Transform& X_WB, Sink& sink) {
  const int i = kIndex[static_cast<std::size_t>(a.getType())], j = kIndex[static_cast<std::size_t>(b.getType())];
  if (i < 0 || j < 0) return false;
  const Function entry = kTable[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
  if (!entry) return false;
  entry(a, X_WA, b, X_WB, sink);
  return true;
}

template <Scalar S, template <Scalar> class... Shapes>
std::string ColliderMatrixT<S, ShapeList<Shapes...>>::describe() {
  std::string text = "|";
  for (std::size_t j = 0; j < N; ++j) text += std::string(" | ") + std::string(shapeTypeName(kTypes[j]));
  text += " |\n|---";
  for (std::size_t j = 0; j < N; ++j) text += "|---";
  text += "|\n";
  for (std::size_t i = 0; i < N; ++i) {
    text += "| " + std::string(shapeTypeName(kTypes[i]));
    for (std::size_t j = 0; j < N; ++j) text += kSupported[i][j] ? " | X" : " | -";
    text += " |\n";
  }
  return text;
}

// The full shape list's matrix (its table and every collider behind it) is
// compiled once with the collider parts (collide/collide_through.hpp) where
// spook is compiled once: a file that calls a typed entry, or a composite's,
// compiles only the colliders of its own pairs.
#if defined(SPOOK_EXTERN_TEMPLATES) && !defined(SPOOK_IMPLEMENT_COLLIDERS_DOUBLE)
extern template class ColliderMatrixT<double, AllShapes>;
#endif
#if defined(SPOOK_EXTERN_TEMPLATES) && !defined(SPOOK_IMPLEMENT_COLLIDERS_FLOAT)
extern template class ColliderMatrixT<float, AllShapes>;
#endif

}  // namespace spook
