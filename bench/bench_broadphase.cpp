// Broadphase cost: find the overlapping bounding-box pairs of
//   - 1,000 and 10,000 spheres (r = 0.5 m) moving in a cube sized for about
//     one neighbour each, every sphere moving every step;
//   - 210 boxes stacked in a pyramid (20 rows), all touching.
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
  for (std::size_t i = 0; i < boxes.size(); ++i)
    t.query(boxes[i], [&](std::size_t j) { pairs += j > i ? 1 : 0; });
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

}  // namespace

BENCHMARK(movingSpheres<0>)->Name("spheres/sweep_and_prune")->Arg(1000)->Arg(10000)->Unit(benchmark::kMicrosecond);
BENCHMARK(movingSpheres<1>)->Name("spheres/aabb_tree_rebuilt")->Arg(1000)->Arg(10000)->Unit(benchmark::kMicrosecond);
BENCHMARK(movingSpheres<2>)->Name("spheres/all_pairs")->Arg(1000)->Arg(10000)->Unit(benchmark::kMicrosecond);
BENCHMARK(pyramidBoxes<0>)->Name("pyramid210/sweep_and_prune")->Unit(benchmark::kMicrosecond);
BENCHMARK(pyramidBoxes<1>)->Name("pyramid210/aabb_tree_rebuilt")->Unit(benchmark::kMicrosecond);
BENCHMARK(pyramidBoxes<2>)->Name("pyramid210/all_pairs")->Unit(benchmark::kMicrosecond);
BENCHMARK_MAIN();
