#pragma once

#include <cstddef>
#include <functional>
#include <utility>

namespace spook::detail {

/// Hash of an ordered pair of pointers, for maps keyed by pairs of objects
/// (materials, geometries): the two pointer hashes mixed as Boost's
/// hash_combine does.
struct PointerPairHash {
  template <class A, class B>
  std::size_t operator()(const std::pair<A*, B*>& key) const noexcept {
    const std::size_t a = std::hash<const void*>()(key.first), b = std::hash<const void*>()(key.second);
    return a ^ (b + std::size_t(0x9e3779b97f4a7c15ull) + (a << 6) + (a >> 2));
  }
};

}  // namespace spook::detail
