#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace spook::detail {

// Sizing of the step's scratch vectors, kept from step to step. A vector
// resized to the size of one island, or assigned n copies, takes exactly n
// when n passes its capacity (libstdc++ grows from the size, not the
// capacity); in a scene whose largest island gains a few rows every step it
// was given fresh memory every step, and the fresh pages' faults cost more
// than the work done in them (a 10,000-sphere pile: about a fifth of the
// step). These grow the capacity at least twofold.

template <class T, class A>
void reserveGrowing(std::vector<T, A>& v, std::size_t n) {
  if (n > v.capacity()) v.reserve(std::max(n, 2 * v.capacity()));
}

template <class T, class A>
void resizeGrowing(std::vector<T, A>& v, std::size_t n) {
  reserveGrowing(v, n);
  v.resize(n);
}

template <class T, class A>
void resizeGrowing(std::vector<T, A>& v, std::size_t n, const T& value) {
  reserveGrowing(v, n);
  v.resize(n, value);
}

template <class T, class A>
void assignGrowing(std::vector<T, A>& v, std::size_t n, const T& value) {
  reserveGrowing(v, n);
  v.assign(n, value);
}

}  // namespace spook::detail
