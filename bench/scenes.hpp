#pragma once

// Shapes and scenes shared by the collision benchmarks.
#include <array>
#include <random>
#include <vector>

#include <spook/collide/all_shapes.hpp>

namespace spook::bench {

/// A flat, gently rippled grid of cells × cells squares of side `cell`
/// (two triangles each) at z ≈ 0, centered on the origin.
inline ref_ptr<Trimesh> gridMesh(int cells, double cell) {
  std::vector<Vec3T<double>> vertices;
  std::vector<std::array<int, 3>> triangles;
  const double half = 0.5 * cells * cell;
  for (int j = 0; j <= cells; ++j)
    for (int i = 0; i <= cells; ++i)
      vertices.emplace_back(i * cell - half, j * cell - half, 0.01 * std::sin(i * 0.7) * std::cos(j * 0.5));
  const auto index = [&](int i, int j) { return i + (cells + 1) * j; };
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i) {
      triangles.push_back({index(i, j), index(i + 1, j), index(i + 1, j + 1)});
      triangles.push_back({index(i, j), index(i + 1, j + 1), index(i, j + 1)});
    }
  return new Trimesh(vertices, triangles);
}

/// One shape of every type, each about a meter across, centered on its
/// origin (the plane, the mesh and the height field face +z at z = 0).
inline std::vector<ref_ptr<ShapeT<double>>> oneOfEach() {
  std::mt19937 rng(5);
  std::normal_distribution<double> n(0.0, 1.0);
  std::vector<Vec3T<double>> cloud;
  for (int i = 0; i < 32; ++i) cloud.push_back(Vec3T<double>(n(rng), n(rng), n(rng)).normalized() * 0.5);
  ref_ptr<Composite> composite = new Composite();
  composite->add(new Box(Vec3T<double>(0.25, 0.25, 0.25)), makeTransform<double>(Vec3T<double>(-0.25, 0, 0), QuatT<double>::Identity()));
  composite->add(new Sphere(0.25), makeTransform<double>(Vec3T<double>(0.25, 0, 0), QuatT<double>::Identity()));
  std::vector<double> heights(16 * 16);
  for (std::size_t k = 0; k < heights.size(); ++k) heights[k] = 0.02 * std::sin(0.9 * double(k));
  return {new Box(Vec3T<double>(0.5, 0.4, 0.3)),
          new Capsule(0.3, 0.6),
          new Convex(cloud),
          new Cylinder(0.4, 0.8),
          new Line(Vec3T<double>(-0.5, 0, 0), Vec3T<double>(0.5, 0, 0)),
          new Plane(Vec3T<double>::UnitZ()),
          new Sphere(0.5),
          gridMesh(16, 0.125),
          composite,
          new HeightField(16, 16, 2.0, 2.0, heights)};
}

}  // namespace spook::bench
