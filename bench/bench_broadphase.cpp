// Broadphase cost: find the overlapping bounding-box pairs of
//   - 1,000 and 10,000 spheres (r = 0.5 m) moving in a cube sized for about
//     one neighbour each, every sphere moving every step;
//   - 210 boxes stacked in a pyramid (20 rows), all touching;
//   - a settled pile: 1,000 and 10,000 spheres (r = 0.1 m) 0.2 m apart on a
//     grid, 13 layers, each box touching its neighbours, in a box of four
//     walls on a ground (the pile of bench/contact_study's scaling).
// Candidates: sweep and prune (what Space uses), an AABB tree rebuilt from
// scratch each step and queried once per box (the tree alternative, with
// no refit bookkeeping), and all pairs (the baseline).
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include <spook/collide/broadphase/sweep_and_prune.hpp>
#include <spook/collide/detail/aabb_tree.hpp>

namespace {

using Box = spook::BoundingBoxT<double>;
using Vec3 = spook::Vec3;

struct MovingSpheres {
  std::vector<Vec3> centers, velocities;
  std::vector<Box> boxes;
  double side;
  explicit MovingSpheres(int count) : side(std::cbrt(double(count)) * 2.0) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int i = 0; i < count; ++i) {
      centers.emplace_back(side * u(rng), side * u(rng), side * u(rng));
      velocities.emplace_back(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
    }
    boxes.resize(centers.size());
  }
  void step() {
    for (std::size_t i = 0; i < centers.size(); ++i) {
      centers[i] += velocities[i] / 60.0;
      for (int k = 0; k < 3; ++k)
        if (centers[i][k] < 0 || centers[i][k] > side) velocities[i][k] = -velocities[i][k];
      boxes[i] = {centers[i] - Vec3::Constant(0.5), centers[i] + Vec3::Constant(0.5)};
    }
  }
};

std::vector<Box> pyramid() {
  std::vector<Box> boxes;
  for (int row = 0; row < 20; ++row)
    for (int k = 0; k < 20 - row; ++k) {
      const Vec3 c(1.0 * k + 0.5 * row, 0, 0.5 + 1.0 * row);
      boxes.push_back({c - Vec3::Constant(0.5), c + Vec3::Constant(0.5)});
    }
  return boxes;
}

std::size_t sweep(const std::vector<Box>& boxes, spook::detail::SweepAndPrune<double>& sap) {
  std::size_t pairs = 0;
  sap.findPairs(boxes, [&](std::size_t, std::size_t) { ++pairs; });
  return pairs;
}
std::size_t tree(const std::vector<Box>& boxes) {
  const spook::detail::AabbTree<double> t(boxes);
  std::size_t pairs = 0;
  for (std::size_t i = 0; i < boxes.size(); ++i) t.query(boxes[i], [&](std::size_t j) { pairs += j > i ? 1 : 0; });
  return pairs;
}
std::size_t allPairs(const std::vector<Box>& boxes) {
  std::size_t pairs = 0;
  for (std::size_t i = 0; i < boxes.size(); ++i)
    for (std::size_t j = i + 1; j < boxes.size(); ++j)
      pairs += spook::detail::SweepAndPrune<double>::overlap(boxes[i], boxes[j]) ? 1 : 0;
  return pairs;
}

template <int Method>
void movingSpheres(benchmark::State& state) {
  MovingSpheres scene(static_cast<int>(state.range(0)));
  spook::detail::SweepAndPrune<double> sap;
  std::size_t pairs = 0;
  for (auto _ : state) {
    scene.step();
    pairs = Method == 0 ? sweep(scene.boxes, sap) : Method == 1 ? tree(scene.boxes) : allPairs(scene.boxes);
    benchmark::DoNotOptimize(pairs);
  }
  state.counters["pairs"] = double(pairs);
}

template <int Method>
void pyramidBoxes(benchmark::State& state) {
  const auto boxes = pyramid();
  spook::detail::SweepAndPrune<double> sap;
  std::size_t pairs = 0;
  for (auto _ : state) {
    pairs = Method == 0 ? sweep(boxes, sap) : Method == 1 ? tree(boxes) : allPairs(boxes);
    benchmark::DoNotOptimize(pairs);
  }
  state.counters["pairs"] = double(pairs);
}

std::vector<Box> pile(int count) {
  constexpr double r = 0.1, pitch = 0.2;
  const int grid = int(std::ceil(std::sqrt(count / 13.0)));
  const double side = grid * pitch;
  std::vector<Box> boxes;
  boxes.push_back({Vec3(-side, -side, -1), Vec3(side, side, 0)});
  for (double sign : {-1.0, 1.0}) {
    boxes.push_back({Vec3(sign * side / 2 - 0.1, -side, 0), Vec3(sign * side / 2 + 0.1, side, 4)});
    boxes.push_back({Vec3(-side, sign * side / 2 - 0.1, 0), Vec3(side, sign * side / 2 + 0.1, 4)});
  }
  for (int i = 0; i < count; ++i) {
    const int layer = i / (grid * grid), column = i % grid, row = (i / grid) % grid;
    const Vec3 c((column - grid / 2.0) * pitch, (row - grid / 2.0) * pitch, r + layer * pitch);
    boxes.push_back({c - Vec3::Constant(r), c + Vec3::Constant(r)});
  }
  return boxes;
}

template <int Method>
void pileBoxes(benchmark::State& state) {
  const auto boxes = pile(static_cast<int>(state.range(0)));
  spook::detail::SweepAndPrune<double> sap;
  std::size_t pairs = 0;
  for (auto _ : state) {
    pairs = Method == 0 ? sweep(boxes, sap) : tree(boxes);
    benchmark::DoNotOptimize(pairs);
  }
  state.counters["pairs"] = double(pairs);
}

}  // namespace

BENCHMARK(movingSpheres<0>)->Name("spheres/sweep_and_prune")->Arg(1000)->Arg(10000)->Unit(benchmark::kMicrosecond);
BENCHMARK(movingSpheres<1>)->Name("spheres/aabb_tree_rebuilt")->Arg(1000)->Arg(10000)->Unit(benchmark::kMicrosecond);
BENCHMARK(movingSpheres<2>)->Name("spheres/all_pairs")->Arg(1000)->Arg(10000)->Unit(benchmark::kMicrosecond);
BENCHMARK(pyramidBoxes<0>)->Name("pyramid210/sweep_and_prune")->Unit(benchmark::kMicrosecond);
BENCHMARK(pyramidBoxes<1>)->Name("pyramid210/aabb_tree_rebuilt")->Unit(benchmark::kMicrosecond);
BENCHMARK(pyramidBoxes<2>)->Name("pyramid210/all_pairs")->Unit(benchmark::kMicrosecond);
BENCHMARK(pileBoxes<0>)->Name("pile/sweep_and_prune")->Arg(1000)->Arg(10000)->Unit(benchmark::kMicrosecond);
BENCHMARK(pileBoxes<1>)->Name("pile/aabb_tree_rebuilt")->Arg(1000)->Arg(10000)->Unit(benchmark::kMicrosecond);
BENCHMARK_MAIN();
