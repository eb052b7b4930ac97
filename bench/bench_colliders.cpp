// Nanoseconds per narrow-phase query for every pair of the collider
// matrix, through the run-time table of the full shape list compiled once
// (detail::collideThrough in spook_compiled, as a Space calls it): the second
// shape sits 0.3 m above the first, turned a little, so that every pair
// overlaps (mesh and height-field queries visit the triangles under it).
// And per swept query of continuous collision detection: each shape that
// CCD sweeps falls 2 m onto every shape, ending 0.3 m above it as above, so
// that every sweep hits (the costly case: bisection and contact normal).
#include <benchmark/benchmark.h>

#include <cmath>
#include <string>
#include <vector>

#include <spook/collide/all_shapes.hpp>
#include <spook/collide/collider_matrix.hpp>
#include <spook/collide/continuous.hpp>
#include <spook/collide/space.hpp>

#include "scenes.hpp"

namespace {

using Matrix = spook::ColliderMatrixT<double, spook::AllShapes>;

void query(benchmark::State& state, const spook::ShapeT<double>* a, const spook::ShapeT<double>* b) {
  const spook::Transform X_WA = spook::Transform::Identity();
  const spook::Quat tilt(Eigen::AngleAxis<double>(0.2, spook::Vec3(1, 2, 0).normalized()));
  const spook::Transform X_WB = spook::makeTransform<double>(spook::Vec3(0.05, -0.03, 0.3), tilt);
  std::vector<spook::ContactPointT<double>> points;
  std::size_t found = 0;
  for (auto _ : state) {
    points.clear();
    spook::ContactSinkT<double> sink(points);
    spook::detail::collideThrough<double, spook::AllShapes>(*a, X_WA, *b, X_WB, sink);
    found += points.size();
    benchmark::DoNotOptimize(points.data());
  }
  state.counters["points"] = double(found) / double(state.iterations());
}

void sweep(benchmark::State& state, const spook::ShapeT<double>* a, const spook::ShapeT<double>* b) {
  const spook::Transform X_WB = spook::Transform::Identity();
  const spook::Quat tilt(Eigen::AngleAxis<double>(0.2, spook::Vec3(1, 2, 0).normalized()));
  const spook::Transform X_end = spook::makeTransform<double>(spook::Vec3(0.05, -0.03, 0.3), tilt);
  const spook::Vec3 motion(0, 0, -2);
  const double halfWidth = spook::detail::sweptHalfWidth<double>(*a);
  std::size_t hits = 0;
  for (auto _ : state) {
    spook::detail::BodySweep<double> swept(motion, halfWidth, halfWidth);  // reach: nothing touched yet
    swept.sweep(*a, X_end, *b, X_WB);
    hits += swept.hit().found ? 1 : 0;
    benchmark::DoNotOptimize(swept.hit().fraction);
  }
  state.counters["hits"] = double(hits) / double(state.iterations());
}

const std::vector<spook::ref_ptr<spook::ShapeT<double>>>& shapes() {
  static const auto all = spook::bench::oneOfEach();
  return all;
}

const bool registered = [] {
  for (std::size_t i = 0; i < shapes().size(); ++i)
    for (std::size_t j = i; j < shapes().size(); ++j) {
      const spook::ShapeT<double>* a = shapes()[i].get();
      const spook::ShapeT<double>* b = shapes()[j].get();
      if (!Matrix::supports(a->getType(), b->getType())) continue;
      const std::string name = "collide/" + std::string(spook::shapeTypeName(a->getType())) + "/" +
                               std::string(spook::shapeTypeName(b->getType()));
      benchmark::RegisterBenchmark(name.c_str(), query, a, b);
    }
  for (const auto& a : shapes())
    if (std::isfinite(spook::detail::sweptHalfWidth<double>(*a)))
      for (const auto& b : shapes()) {
        const std::string name = "sweep/" + std::string(spook::shapeTypeName(a->getType())) + "/" +
                                 std::string(spook::shapeTypeName(b->getType()));
        benchmark::RegisterBenchmark(name.c_str(), sweep, a.get(), b.get());
      }
  return true;
}();

}  // namespace

BENCHMARK_MAIN();
