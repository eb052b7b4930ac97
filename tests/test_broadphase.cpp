// The sweep and prune finds exactly the overlapping pairs, each once, on
// scenes below and above the size at which it sweeps in strips: sparse
// and dense piles, boxes of mixed sizes, walls and a ground spanning
// every strip, unbounded and non-finite bounds, touching and identical
// boxes. Reference: every pair tested.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include <spook/collide/broadphase/sweep_and_prune.hpp>

namespace {

template <class S>
using Box = spook::BoundingBoxT<S>;

// SweepAndPrune::overlap written out (this file runs unoptimized).
template <class S>
bool overlap(const Box<S>& a, const Box<S>& b) {
  for (int k = 0; k < 3; ++k)
    if (!(a.min[k] <= b.max[k] && b.min[k] <= a.max[k])) return false;
  return true;
}

template <class S>
std::set<std::pair<std::size_t, std::size_t>> allPairs(const std::vector<Box<S>>& boxes) {
  std::set<std::pair<std::size_t, std::size_t>> pairs;
  for (std::size_t i = 0; i < boxes.size(); ++i)
    for (std::size_t j = i + 1; j < boxes.size(); ++j)
      if (overlap(boxes[i], boxes[j])) pairs.emplace(i, j);
  return pairs;
}

// The sweep's pairs; fails on a pair found twice or out of order.
template <class S>
std::set<std::pair<std::size_t, std::size_t>> swept(spook::detail::SweepAndPrune<S>& sap,
                                                    const std::vector<Box<S>>& boxes) {
  std::set<std::pair<std::size_t, std::size_t>> pairs;
  std::size_t repeated = 0, unordered = 0;
  sap.findPairs(boxes, [&](std::size_t i, std::size_t j) {
    unordered += i < j ? 0 : 1;
    repeated += pairs.emplace(i, j).second ? 0 : 1;
  });
  CHECK(repeated == 0);
  CHECK(unordered == 0);
  return pairs;
}

template <class S>
Box<S> around(const spook::Vec3T<S>& center, const spook::Vec3T<S>& half) {
  return {center - half, center + half};
}

// Spheres of radius r on a grid `pitch` apart (a pile when pitch < 2r),
// jittered, in a box of walls and a ground that span it.
template <class S>
std::vector<Box<S>> pile(int count, double r, double pitch, std::mt19937& rng) {
  using Vec3 = spook::Vec3T<S>;
  std::uniform_real_distribution<double> jitter(-0.1 * r, 0.1 * r);
  const int grid = int(std::ceil(std::sqrt(count / 10.0)));
  const double side = grid * pitch;
  std::vector<Box<S>> boxes;
  boxes.push_back(around<S>(Vec3(0, 0, -0.5), Vec3(S(side), S(side), S(0.5))));
  for (double sign : {-1.0, 1.0}) {
    boxes.push_back(around<S>(Vec3(S(sign * side / 2), 0, S(side)), Vec3(S(0.1), S(side), S(side))));
    boxes.push_back(around<S>(Vec3(0, S(sign * side / 2), S(side)), Vec3(S(side), S(0.1), S(side))));
  }
  for (int i = 0; i < count; ++i) {
    const int layer = i / (grid * grid), column = i % grid, row = (i / grid) % grid;
    const Vec3 c(S((column - grid / 2.0) * pitch + jitter(rng)), S((row - grid / 2.0) * pitch + jitter(rng)),
                 S(r + layer * pitch + jitter(rng)));
    boxes.push_back(around<S>(c, Vec3::Constant(S(r))));
  }
  return boxes;
}

}  // namespace

TEST_CASE_TEMPLATE("sweep and prune finds every overlapping pair once, below and above its strips", S, double, float) {
  using Vec3 = spook::Vec3T<S>;
  constexpr S kInf = std::numeric_limits<S>::infinity();
  std::mt19937 rng(7);
  spook::detail::SweepAndPrune<S> sap;  // one instance: its storage is reused from pass to pass
  for (const int count : {50, 300, 1500, 3000}) {
    for (const double pitch : {0.15, 0.5}) {
      std::vector<Box<S>> boxes = pile<S>(count, 0.1, pitch, rng);
      // Mixed sizes, a few long rods, an unbounded plane, a slab unbounded
      // across, boxes with NaN and infinite bounds, a degenerate box and
      // identical and touching neighbours.
      std::uniform_real_distribution<double> at(-3.0, 3.0), size(0.0, 1.5);
      for (int k = 0; k < 40; ++k)
        boxes.push_back(around<S>(Vec3(S(at(rng)), S(at(rng)), S(at(rng))), Vec3(S(size(rng)), S(0.05), S(size(rng)))));
      boxes.push_back({Vec3(-kInf, -kInf, -kInf), Vec3(kInf, kInf, S(0))});
      boxes.push_back({Vec3(S(-1), -kInf, S(-1)), Vec3(S(1), kInf, S(1))});
      boxes.push_back({Vec3(-kInf, S(-1), S(0.5)), Vec3(kInf, S(1), S(0.6))});
      const S nan = std::numeric_limits<S>::quiet_NaN();
      boxes.push_back({Vec3(S(0), nan, S(0)), Vec3(S(1), S(1), S(1))});
      boxes.push_back({Vec3(S(0.2), S(0.2), S(0.2)), Vec3(S(0.2), S(0.2), S(0.2))});
      boxes.push_back(boxes[10]);
      boxes.push_back({boxes[11].max, boxes[11].max + Vec3::Constant(S(0.3))});  // touches one corner
      CAPTURE(count);
      CAPTURE(pitch);
      const auto expected = allPairs(boxes);
      const auto found = swept(sap, boxes);
      CHECK(found.size() == expected.size());
      CHECK(found == expected);
    }
  }
}
