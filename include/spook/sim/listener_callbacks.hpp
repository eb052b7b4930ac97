#pragma once

#include <type_traits>

namespace spook::detail {

/// What `&L::name` says about a listener callback `name` of class L.
enum class CallbackState {
  INHERITED,   ///< L does not redeclare it: the base's empty callback runs
  OVERRIDDEN,  ///< L (or a class between) declares it with the base's signature
  MISMATCHED,  ///< L declares a `name` with another signature, or static, or const: it hides the callback and is never called
  UNKNOWN      ///< not inspectable from here (overloaded, or not public): the compiler's own rules apply
};

template <class Pointer>
struct MemberFunctionOf {
  static constexpr bool known = false;
};
template <class R, class C, class... A>
struct MemberFunctionOf<R (C::*)(A...)> {
  static constexpr bool known = true;
  using Class = C;
  using Type = R(A...);
};
// An override may add noexcept.
template <class R, class C, class... A>
struct MemberFunctionOf<R (C::*)(A...) noexcept> : MemberFunctionOf<R (C::*)(A...)> {};

/// The state of a callback of `Base` with `Signature`, seen through
/// `Pointer` = decltype(&L::name).
template <class Base, class Signature, class Pointer>
consteval CallbackState callbackState() {
  using F = MemberFunctionOf<Pointer>;
  if constexpr (!F::known)
    return CallbackState::MISMATCHED;
  else if constexpr (!std::is_same_v<typename F::Type, Signature>)
    return CallbackState::MISMATCHED;
  else if constexpr (std::is_same_v<typename F::Class, Base>)
    return CallbackState::INHERITED;
  else
    return CallbackState::OVERRIDDEN;
}

}  // namespace spook::detail
