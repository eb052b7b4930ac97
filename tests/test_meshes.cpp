#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <spook/collide/detail/aabb_tree.hpp>
#include <spook/collide/shapes/height_field.hpp>
#include <spook/collide/shapes/trimesh.hpp>

#include "shape_helpers.hpp"
#include "tolerance.hpp"

using spook::test::checkRejects;

using spook::test::pick;

namespace {

template <class S>
using Mesh = spook::ref_ptr<spook::TrimeshT<S>>;
template <class S>
using Field = spook::ref_ptr<spook::HeightFieldT<S>>;
template <class S>
using Box = spook::BoundingBoxT<S>;
using Triangles = std::vector<std::array<int, 3>>;
using Pairs = std::vector<std::pair<std::size_t, std::size_t>>;


// A box with corners center ± half, wound counter-clockwise seen from outside.
template <class S>
Mesh<S> boxMesh(const spook::Vec3T<S>& center, const spook::Vec3T<S>& half) {
  std::vector<spook::Vec3T<S>> vertices;
  for (int k = 0; k < 8; ++k)
    vertices.push_back(center + spook::Vec3T<S>((k & 1) ? half.x() : -half.x(), (k & 2) ? half.y() : -half.y(),
                                               (k & 4) ? half.z() : -half.z()));
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  Triangles triangles;
  for (const auto& q : quads) {
    triangles.push_back({q[0], q[1], q[2]});
    triangles.push_back({q[0], q[2], q[3]});
  }
  return new spook::TrimeshT<S>(vertices, triangles);
}

// Vertices on a sphere of radius r about the origin: `stacks` bands of
// latitude, `slices` of longitude, one vertex at each pole.
template <class S>
std::pair<std::vector<spook::Vec3T<S>>, Triangles> uvSphere(double r, int stacks, int slices) {
  std::vector<spook::Vec3T<S>> vertices{{S(0), S(0), S(r)}};
  for (int k = 1; k < stacks; ++k)
    for (int s = 0; s < slices; ++s) {
      const double theta = std::numbers::pi * k / stacks, phi = 2 * std::numbers::pi * s / slices;
      vertices.emplace_back(S(r * std::sin(theta) * std::cos(phi)), S(r * std::sin(theta) * std::sin(phi)),
                            S(r * std::cos(theta)));
    }
  const int south = static_cast<int>(vertices.size());
  vertices.emplace_back(S(0), S(0), S(-r));
  const auto ring = [&](int k, int s) { return 1 + (k - 1) * slices + (s % slices); };
  Triangles triangles;
  for (int s = 0; s < slices; ++s) {
    triangles.push_back({0, ring(1, s), ring(1, s + 1)});
    for (int k = 1; k + 1 < stacks; ++k) {
      triangles.push_back({ring(k, s), ring(k + 1, s), ring(k + 1, s + 1)});
      triangles.push_back({ring(k, s), ring(k + 1, s + 1), ring(k, s + 1)});
    }
    triangles.push_back({ring(stacks - 1, s), south, ring(stacks - 1, s + 1)});
  }
  return {vertices, triangles};
}

// `count` small random triangles inside the cube [-extent, extent]³.
template <class S>
Mesh<S> triangleSoup(int count, double extent, double size, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> where(-extent, extent), offset(-size, size);
  std::vector<spook::Vec3T<S>> vertices;
  Triangles triangles;
  for (int t = 0; t < count; ++t) {
    const spook::Vec3T<S> c(S(where(rng)), S(where(rng)), S(where(rng)));
    for (int k = 0; k < 3; ++k) vertices.push_back(c + spook::Vec3T<S>(S(offset(rng)), S(offset(rng)), S(offset(rng))));
    triangles.push_back({3 * t, 3 * t + 1, 3 * t + 2});
  }
  return new spook::TrimeshT<S>(vertices, triangles);
}

// A flat floor at z = 0 of cells × cells unit squares, two triangles each.
template <class S>
Mesh<S> floorMesh(int cells) {
  std::vector<spook::Vec3T<S>> vertices;
  for (int j = 0; j <= cells; ++j)
    for (int i = 0; i <= cells; ++i) vertices.emplace_back(S(i - cells / 2), S(j - cells / 2), S(0));
  Triangles triangles;
  const auto at = [&](int i, int j) { return i + (cells + 1) * j; };
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i) {
      triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return new spook::TrimeshT<S>(vertices, triangles);
}

template <class S>
Box<S> boxOf(const std::array<spook::Vec3T<S>, 3>& t) {
  return {t[0].cwiseMin(t[1]).cwiseMin(t[2]), t[0].cwiseMax(t[1]).cwiseMax(t[2])};
}

template <class S>
std::vector<Box<S>> triangleBoxes(const spook::TrimeshT<S>& mesh) {
  std::vector<Box<S>> boxes;
  for (std::size_t i = 0; i < mesh.getNumTriangles(); ++i) boxes.push_back(boxOf<S>(mesh.getTriangle(i)));
  return boxes;
}

// Random boxes up to `size` wide, cornered in [-extent, extent]² × [-zExtent, zExtent];
// with `snap`, corners are rounded to whole meters so that they touch grid lines.
template <class S>
std::vector<Box<S>> randomBoxes(int count, double extent, double zExtent, double size, bool snap, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> where(-extent, extent), height(-zExtent, zExtent), width(0.0, size);
  std::vector<Box<S>> boxes;
  for (int q = 0; q < count; ++q) {
    spook::Vec3T<S> lo(S(where(rng)), S(where(rng)), S(height(rng)));
    spook::Vec3T<S> hi = lo + spook::Vec3T<S>(S(width(rng)), S(width(rng)), S(width(rng)));
    if (snap) {
      lo = lo.array().round().matrix();
      hi = hi.array().round().matrix();
      lo.z() = S(q % 3 == 0 ? 0.0 : -0.5);   // resting exactly on the floor, or straddling it
      hi.z() = S(q % 3 == 2 ? -0.25 : 0.5);  // or just below it
    }
    boxes.push_back({lo, hi});
  }
  return boxes;
}

template <class S>
std::vector<std::size_t> visited(const spook::TrimeshT<S>& mesh, const Box<S>& query) {
  std::vector<std::size_t> hits;
  mesh.forEachTriangle(query,
                       [&](std::size_t i, const spook::Vec3T<S>& a, const spook::Vec3T<S>&, const spook::Vec3T<S>&) {
                         CHECK(a == mesh.getTriangle(i)[0]);
                         hits.push_back(i);
                       });
  std::sort(hits.begin(), hits.end());
  return hits;
}

template <class S>
void checkQueriesMatchBruteForce(const spook::TrimeshT<S>& mesh, const std::vector<Box<S>>& queries) {
  const std::vector<Box<S>> boxes = triangleBoxes(mesh);
  std::size_t mismatches = 0, total = 0;
  for (const Box<S>& q : queries) {
    std::vector<std::size_t> expected;
    for (std::size_t i = 0; i < boxes.size(); ++i)
      if (spook::detail::overlaps(boxes[i], q)) expected.push_back(i);
    mismatches += visited(mesh, q) != expected;
    total += expected.size();
  }
  CHECK(mismatches == 0);
  CHECK(total > queries.size());  // the queries did find something
}

template <class S>
Pairs pairsOf(const spook::detail::AabbTree<S>& a, const spook::detail::AabbTree<S>& b, const spook::TransformT<S>& X) {
  Pairs pairs;
  a.queryPairs(b, X, [&](std::size_t i, std::size_t j) { pairs.emplace_back(i, j); });
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

template <class S>
Pairs bruteForcePairs(const std::vector<Box<S>>& a, const std::vector<Box<S>>& b, const spook::TransformT<S>& X) {
  Pairs pairs;
  for (std::size_t j = 0; j < b.size(); ++j) {
    const Box<S> moved = spook::detail::transformBox(b[j], X);
    for (std::size_t i = 0; i < a.size(); ++i)
      if (spook::detail::overlaps(a[i], moved)) pairs.emplace_back(i, j);
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

}  // namespace

TEST_CASE_TEMPLATE("a closed box mesh off the origin has the box's volume and parallel-axis inertia", S, float,
                   double) {
  const S tol = pick<S>(1e-12, 1e-5);
  const spook::Vec3T<S> half(S(0.5), S(1), S(1.5)), d(S(2), S(-1), S(0.5));
  const Mesh<S> mesh = boxMesh<S>(d, half);
  CHECK((mesh->getType() == spook::ShapeType::TRIMESH));  // parenthesized: doctest would stringify via spook::toString
  CHECK(mesh->isClosed());
  CHECK(std::abs(mesh->getVolume() - S(6)) <= tol * S(6));
  CHECK((mesh->getCenterOfVolume() - d).norm() <= tol * d.norm());
  // m/3 (b² + c², a² + c², a² + b²) about the center, plus m (|d|² 1 − d dᵀ).
  const S m = S(3);
  const spook::Vec3T<S> sq = half.cwiseAbs2();
  const spook::Mat3T<S> expected =
      spook::Mat3T<S>(spook::Vec3T<S>(sq.y() + sq.z(), sq.x() + sq.z(), sq.x() + sq.y()).asDiagonal()) * (m / S(3)) +
      m * (d.squaredNorm() * spook::Mat3T<S>::Identity() - d * d.transpose());
  const spook::Mat3T<S> inertia = mesh->calculateInertia(m).matrix();
  CHECK((inertia - expected).norm() <= tol * expected.norm());
  const Box<S> bounds = mesh->getBoundingBox();
  CHECK(bounds.min == d - half);
  CHECK(bounds.max == d + half);
  for (std::size_t i = 0; i < mesh->getNumTriangles(); ++i) {
    const auto t = mesh->getTriangle(i);
    const spook::Vec3T<S> outward = (t[0] + t[1] + t[2]) / S(3) - d;
    CHECK(mesh->getNormal(i).dot(outward) > S(0));
    CHECK(std::abs(mesh->getNormal(i).norm() - S(1)) <= tol);
  }
  CHECK(visited(*mesh, bounds).size() == 12);
}

TEST_CASE_TEMPLATE("a UV sphere's volume approaches 4/3 π r³ from below; removing a triangle opens it", S, float,
                   double) {
  const double r = 0.75, exact = 4.0 / 3.0 * std::numbers::pi * r * r * r;
  double previous = 0;
  for (int stacks : {8, 16, 32, 64}) {
    const auto [vertices, triangles] = uvSphere<S>(r, stacks, 2 * stacks);
    const Mesh<S> sphere = new spook::TrimeshT<S>(vertices, triangles);
    CHECK(sphere->isClosed());
    const double volume = double(sphere->getVolume());
    CHECK(volume > previous);
    CHECK(volume < exact);
    previous = volume;
  }
  CHECK(1 - previous / exact < 0.01);

  const auto [vertices, triangles] = uvSphere<S>(r, 64, 128);
  const Mesh<S> sphere = new spook::TrimeshT<S>(vertices, triangles);
  CHECK(sphere->getCenterOfVolume().norm() <= pick<S>(1e-12, 1e-5));
  const spook::Vec3T<S> moments = sphere->calculateInertia(S(1)).diagonal();
  CHECK((moments / S(0.4 * r * r) - spook::Vec3T<S>::Ones()).cwiseAbs().maxCoeff() < S(0.01));

  Triangles open = triangles;
  open.erase(open.begin() + 100);
  const Mesh<S> cup = new spook::TrimeshT<S>(vertices, open);
  CHECK_FALSE(cup->isClosed());
  CHECK(cup->getVolume() == S(0));
  CHECK(cup->getCenterOfVolume() == cup->getBoundingBox().center());
  checkRejects([&] { (void)cup->calculateInertia(S(1)); }, "Trimesh", "3");  // the hole's three edges
}

TEST_CASE_TEMPLATE("tree queries over 20,000 triangles find exactly the brute-force set", S, float, double) {
  const Mesh<S> soup = triangleSoup<S>(20000, 20.0, 0.5, 3);
  CHECK(soup->getTree().size() == 20000);
  CHECK(soup->getTree().getDepth() <= 14);  // log2(20000 / 4) + 2
  checkQueriesMatchBruteForce(*soup, randomBoxes<S>(300, 20.0, 20.0, 4.0, false, 5));
  CHECK(visited(*soup, soup->getBoundingBox()).size() == 20000);

  const Mesh<S> floor = floorMesh<S>(100);
  CHECK(floor->getNumTriangles() == 20000);
  checkQueriesMatchBruteForce(*floor, randomBoxes<S>(300, 50.0, 1.0, 6.0, true, 7));
  CHECK(visited(*floor, Box<S>{spook::Vec3T<S>(S(-2), S(-2), S(1e-3)), spook::Vec3T<S>(S(2), S(2), S(1))}).empty());

  const Box<S> unit{spook::Vec3T<S>::Zero(), spook::Vec3T<S>::Ones()};
  CHECK(spook::detail::overlaps(unit, Box<S>{spook::Vec3T<S>::Ones(), spook::Vec3T<S>::Constant(S(2))}));  // touching
  CHECK_FALSE(
      spook::detail::overlaps(unit, Box<S>{spook::Vec3T<S>(S(0), S(0), S(1.5)), spook::Vec3T<S>::Constant(S(2))}));

  const spook::detail::AabbTree<S> empty;
  std::size_t calls = 0;
  empty.query(soup->getBoundingBox(), [&](std::size_t) { ++calls; });
  empty.queryPairs(soup->getTree(), spook::TransformT<S>::Identity(), [&](std::size_t, std::size_t) { ++calls; });
  CHECK(calls == 0);
}

TEST_CASE_TEMPLATE("tree-vs-tree pairs under a rigid transform match the brute-force set", S, float, double) {
  const Mesh<S> soup = triangleSoup<S>(20000, 20.0, 0.5, 11);
  const Mesh<S> probe = triangleSoup<S>(600, 6.0, 0.8, 13);
  const Mesh<S> floor = floorMesh<S>(100);
  std::mt19937 rng(17);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int trial = 0; trial < 3; ++trial) {
    const spook::QuatT<S> q(S(n(rng)), S(n(rng)), S(n(rng)), S(n(rng)));
    const spook::TransformT<S> X =
        spook::makeTransform<S>(spook::Vec3T<S>(S(3 * n(rng)), S(3 * n(rng)), S(0.5 * n(rng))), q);
    const Pairs pairs = pairsOf(soup->getTree(), probe->getTree(), X);
    CHECK(std::adjacent_find(pairs.begin(), pairs.end()) == pairs.end());
    CHECK(pairs.size() > 100);
    CHECK(pairs == bruteForcePairs(triangleBoxes(*soup), triangleBoxes(*probe), X));
    const Pairs onFloor = pairsOf(floor->getTree(), probe->getTree(), X);
    CHECK(!onFloor.empty());
    CHECK(onFloor == bruteForcePairs(triangleBoxes(*floor), triangleBoxes(*probe), X));
  }
}

TEST_CASE_TEMPLATE("a plane-shaped height field interpolates the plane and its normals point up", S, float, double) {
  const S a = S(0.3), b = S(-0.7), c = S(1.2), sizeX = S(4), sizeY = S(2.5);
  const std::size_t nx = 9, ny = 6;
  std::vector<S> heights;
  for (std::size_t j = 0; j < ny; ++j)
    for (std::size_t i = 0; i < nx; ++i) {
      const S x = -sizeX / 2 + S(i) * sizeX / S(nx - 1), y = -sizeY / 2 + S(j) * sizeY / S(ny - 1);
      heights.push_back(a * x + b * y + c);
    }
  const Field<S> field = new spook::HeightFieldT<S>(nx, ny, sizeX, sizeY, heights);
  CHECK((field->getType() == spook::ShapeType::HEIGHTFIELD));
  CHECK(field->getVolume() == S(0));
  CHECK(field->getSpacing().x() == S(0.5));
  const S tol = pick<S>(1e-14, 1e-6) * S(4);
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  S worst = S(0);
  for (int k = 0; k < 1000; ++k) {
    const S x = S(u(rng)) * sizeX, y = S(u(rng)) * sizeY;
    worst = std::max(worst, std::abs(field->heightAt(x, y) - (a * x + b * y + c)));
  }
  CHECK(worst <= tol);
  CHECK(std::abs(field->heightAt(S(10), S(0)) - (a * sizeX / 2 + c)) <= tol);  // clamped onto the edge

  const spook::Vec3T<S> up = spook::Vec3T<S>(-a, -b, S(1)).normalized();
  CHECK(field->getNumTriangles() == 2 * 8 * 5);
  for (std::size_t t = 0; t < field->getNumTriangles(); ++t) CHECK((field->getNormal(t) - up).norm() <= tol);

  const Box<S> bounds = field->getBoundingBox();
  CHECK(bounds.min.x() == -sizeX / 2);
  CHECK(bounds.max.y() == sizeY / 2);
  CHECK(bounds.min.z() == *std::min_element(heights.begin(), heights.end()));
  CHECK(bounds.max.z() == *std::max_element(heights.begin(), heights.end()));
  checkRejects([&] { (void)field->calculateInertia(S(2)); }, "HeightField", "2");
}

TEST_CASE_TEMPLATE("height-field triangle queries match brute force; setHeight moves the z range", S, float, double) {
  const std::size_t nx = 40, ny = 30;
  std::mt19937 rng(29);
  std::uniform_real_distribution<double> h(-1.0, 1.0);
  std::vector<S> heights(nx * ny);
  for (S& value : heights) value = S(h(rng));
  const Field<S> field = new spook::HeightFieldT<S>(nx, ny, S(39), S(29), heights);
  std::size_t mismatches = 0, found = 0;
  for (const Box<S>& q : randomBoxes<S>(400, 21.0, 2.0, 5.0, false, 31)) {
    std::vector<std::size_t> expected, hits;
    for (std::size_t t = 0; t < field->getNumTriangles(); ++t)
      if (spook::detail::overlaps(boxOf<S>(field->getTriangle(t)), q)) expected.push_back(t);
    field->forEachTriangle(
        q, [&](std::size_t t, const spook::Vec3T<S>& a, const spook::Vec3T<S>& b, const spook::Vec3T<S>& c) {
          CHECK(field->getTriangle(t) == std::array<spook::Vec3T<S>, 3>{a, b, c});
          CHECK((b - a).cross(c - a).z() > S(0));
          hits.push_back(t);
        });
    std::sort(hits.begin(), hits.end());
    mismatches += hits != expected;
    found += hits.size();
  }
  CHECK(mismatches == 0);
  CHECK(found > 400);

  const S top = field->getMaxHeight();
  field->setHeight(3, 4, S(5));
  CHECK(field->getBoundingBox().max.z() == S(5));
  CHECK(field->getHeight(3, 4) == S(5));
  field->setHeight(3, 4, S(0));
  CHECK(field->getBoundingBox().max.z() == top);
  field->setHeight(0, 0, S(-7));
  CHECK(field->getBoundingBox().min.z() == S(-7));
}

// 2^32 × 2^32 samples wrap the sample count to 0 in 64 bits: an empty
// heights vector then matched it, and the constructor read the minimum of
// no heights (a null dereference under ASan).
TEST_CASE_TEMPLATE("a height field refuses a sample count that overflows or a cell spacing that underflows", S, float,
                   double) {
  const auto field = [](std::size_t nx, std::size_t ny, S sx, S sy, std::vector<S> h) {
    return [=] { Field<S> f = new spook::HeightFieldT<S>(nx, ny, sx, sy, h); };
  };
  const std::size_t n32 = std::size_t(1) << 32;
  checkRejects(field(n32, n32, S(1), S(1), {}), "HeightField", "(4294967296, 4294967296)");
  checkRejects(field(n32 + 1, n32, S(1), S(1), {}), "triangles", "(4294967297, 4294967296)");
  // 2 (2^31 + 1 − 1)(2 − 1) = 2^32 triangles: one more than a 32-bit face index numbers.
  checkRejects(field((std::size_t(1) << 31) + 1, 2, S(1), S(1), {}), "triangles", "(2147483649, 2)");
  const S tiny = std::numeric_limits<S>::denorm_min();
  checkRejects(field(3, 2, tiny, S(1), std::vector<S>(6)), "spacing", "(0, 1)");
  checkRejects(field(2, 2, S(1), S(-0.0), std::vector<S>(4)), "sizeY", "-0");
  checkRejects(field(2, 2, std::numeric_limits<S>::quiet_NaN(), S(1), std::vector<S>(4)), "sizeX", "nan");
  // The largest finite extent is still a field: one cell spanning it.
  const S big = std::numeric_limits<S>::max();
  const Field<S> wide = new spook::HeightFieldT<S>(2, 2, big, big, {S(0), S(1), S(2), S(3)});
  CHECK(wide->getSpacing().x() == big);
  CHECK(wide->heightAt(S(0), S(0)) == S(1.5));
  CHECK(wide->getBoundingBox().max.allFinite());
}

// Heights of ±0.6·max are each finite, but the field's height range (its
// bounding box, the depth a contact can have) is not: refused on
// construction and by setHeight, which keeps the field as it was.
TEST_CASE_TEMPLATE("a height field refuses heights whose range overflows, on construction and in setHeight", S, float,
                   double) {
  const S high = S(0.6) * std::numeric_limits<S>::max();
  checkRejects([&] { Field<S> f = new spook::HeightFieldT<S>(2, 2, S(1), S(1), {-high, S(0), S(0), high}); },
               "HeightField", "(-");
  const Field<S> field = new spook::HeightFieldT<S>(2, 2, S(1), S(1), {-high, S(0), S(0), S(1)});
  checkRejects([&] { field->setHeight(1, 1, high); }, "HeightField", "(-");
  CHECK(field->getHeight(1, 1) == S(1));
  CHECK(field->getMaxHeight() == S(1));
  CHECK(field->getMinHeight() == -high);
  field->setHeight(0, 0, S(-2));  // the lowest sample raised: the range shrinks
  CHECK(field->getMinHeight() == S(-2));
  field->setHeight(1, 1, high);  // now within range
  CHECK(field->getMaxHeight() == high);
  CHECK(std::isfinite(field->getBoundingBox().max.z() - field->getBoundingBox().min.z()));
}

TEST_CASE_TEMPLATE("meshes and height fields reject bad input, naming the value", S, float, double) {
  const S inf = std::numeric_limits<S>::infinity();
  const std::vector<spook::Vec3T<S>> corners{{S(0), S(0), S(0)}, {S(1), S(0), S(0)}, {S(0), S(1), S(0)}};
  const auto trimesh = [](std::vector<spook::Vec3T<S>> v, Triangles t) { Mesh<S> m = new spook::TrimeshT<S>(v, t); };
  checkRejects([&] { trimesh(corners, {}); }, "Trimesh", "0");
  checkRejects(
      [&] {
        trimesh({{S(0), S(0), S(0)}, {S(1), inf, S(0)}, {S(0), S(1), S(0)}}, {{0, 1, 2}});
      },
      "Trimesh", "(1, inf, 0)");
  checkRejects([&] { trimesh(corners, {{0, 1, 3}}); }, "Trimesh", "3");
  checkRejects([&] { trimesh(corners, {{0, 1, 3}}); }, "[0, 3)", "3");
  checkRejects([&] { trimesh(corners, {{-1, 1, 2}}); }, "Trimesh", "-1");
  checkRejects([&] { trimesh(corners, {{0, 2, 2}}); }, "Trimesh", "(0, 2, 2)");
  // A box wound inside out is closed but encloses a negative volume.
  const Mesh<S> box = boxMesh<S>(spook::Vec3T<S>::Zero(), spook::Vec3T<S>::Ones());
  Triangles inward = box->getTriangles();
  for (auto& t : inward) std::swap(t[1], t[2]);
  checkRejects([&] { trimesh(box->getVertices(), inward); }, "Trimesh", "-8");
  // Two-sided and flat: closed, but no volume.
  const Mesh<S> sheet = new spook::TrimeshT<S>(corners, Triangles{{0, 1, 2}, {0, 2, 1}});
  CHECK(sheet->isClosed());
  CHECK(sheet->getVolume() == S(0));
  checkRejects([&] { (void)sheet->calculateInertia(S(1)); }, "Trimesh", "0");
  checkRejects([&] { (void)box->calculateInertia(S(-1)); }, "Trimesh", "-1");

  const auto field = [](std::size_t nx, std::size_t ny, S sx, S sy, std::vector<S> h) {
    Field<S> f = new spook::HeightFieldT<S>(nx, ny, sx, sy, h);
  };
  checkRejects([&] { field(1, 5, S(1), S(1), std::vector<S>(5)); }, "HeightField", "(1, 5)");
  checkRejects([&] { field(4, 5, S(1), S(1), std::vector<S>(19)); }, "HeightField", "19");
  checkRejects([&] { field(2, 2, S(1), S(1), {S(0), S(0), inf, S(0)}); }, "HeightField", "inf");
  checkRejects([&] { field(2, 2, S(-1), S(1), std::vector<S>(4)); }, "HeightField", "-1");
  checkRejects([&] { field(2, 2, S(1), S(0), std::vector<S>(4)); }, "HeightField", "0");
  checkRejects([&] { field(2, 2, S(1), inf, std::vector<S>(4)); }, "HeightField", "inf");
  const Field<S> flat = new spook::HeightFieldT<S>(2, 3, S(1), S(1), std::vector<S>(6));
  checkRejects([&] { flat->setHeight(2, 0, S(1)); }, "HeightField", "(2, 0)");
  checkRejects([&] { flat->setHeight(1, 2, -inf); }, "HeightField", "-inf");
  checkRejects([&] { (void)flat->heightAt(std::numeric_limits<S>::quiet_NaN(), S(0)); }, "HeightField", "(nan, 0)");
  CHECK(flat->getMaxHeight() == S(0));
}

namespace {

/// Two triangles sharing the edge from (0, 0, 0) to (0, 1, 0), the first in
/// the plane z = 0 over x < 0, the second folded down (convex seen from
/// above) by `degrees` over x > 0; both counter-clockwise seen from above.
template <class S>
Mesh<S> foldedPair(double degrees) {
  using V = spook::Vec3T<S>;
  const double a = degrees * std::numbers::pi / 180.0;
  return new spook::TrimeshT<S>({V(0, 0, 0), V(0, 1, 0), V(-1, 0, 0), V(S(std::cos(a)), 0, S(-std::sin(a)))},
                                {{0, 1, 2}, {1, 0, 3}});
}

}  // namespace

// Active edges (detail::edgeActivity): a contact on an edge between two
// triangles of a flat or gently folded region takes the face's normal; on a
// rim, a sharp convex fold or from the side the fold turns away from, it
// keeps its own.
TEST_CASE_TEMPLATE("mesh edges are active on rims and sharp folds, inactive inside flat and concave regions", S, float,
                   double) {
  // Edge 0 of triangle 0 runs (0,0,0) → (0,1,0): the shared one; its other edges are rims.
  const std::uint8_t rimsOnly = 0b110110;
  CHECK(foldedPair<S>(0)->getActiveEdges(0) == rimsOnly);
  CHECK(foldedPair<S>(3)->getActiveEdges(0) == rimsOnly);    // within 5°: flat
  CHECK(foldedPair<S>(-3)->getActiveEdges(0) == rimsOnly);
  CHECK(foldedPair<S>(10)->getActiveEdges(0) == (rimsOnly | 0b000001));  // convex from the front
  CHECK(foldedPair<S>(-10)->getActiveEdges(0) == (rimsOnly | 0b001000));  // concave from the front: active from behind
  CHECK(foldedPair<S>(90)->getActiveEdges(0) == (rimsOnly | 0b000001));
  CHECK(foldedPair<S>(179.5)->getActiveEdges(0) == 0b111111);  // back to back: a sheet's rim
  // Both triangles of a pair see the shared edge alike (it is edge 0 of the second too).
  CHECK((foldedPair<S>(10)->getActiveEdges(1) & 0b001001) == 0b000001);

  // A height field: flat inside, rims at the border; a ridge along x = 0 folds by 2 × 11.3°.
  const std::size_t n = 5;
  std::vector<S> flat(n * n, S(0)), ridge(n * n);
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = 0; i < n; ++i) ridge[i + n * j] = S(-0.2 * std::abs(double(i) - 2.0));
  const Field<S> field = new spook::HeightFieldT<S>(n, n, S(4), S(4), flat);
  const Field<S> ridged = new spook::HeightFieldT<S>(n, n, S(4), S(4), ridge);
  const auto cellTriangle = [&](std::size_t i, std::size_t j, std::size_t k) { return 2 * (i + (n - 1) * j) + k; };
  CHECK(field->getActiveEdges(cellTriangle(1, 1, 0)) == 0);
  CHECK(field->getActiveEdges(cellTriangle(1, 1, 1)) == 0);
  CHECK(field->getActiveEdges(cellTriangle(0, 0, 0)) == 0b001001);  // edge 0 on the rim y = -2
  CHECK(field->getActiveEdges(cellTriangle(0, 0, 1)) == 0b100100);  // edge 2 on the rim x = -2
  // Cell (1, 1)'s lower triangle has its edge 1 on the ridge line x = 0: convex from above.
  CHECK(ridged->getActiveEdges(cellTriangle(1, 1, 0)) == 0b000010);
  // Cell (2, 1)'s upper triangle has its edge 2 there: the same fold, seen from the other side.
  CHECK(ridged->getActiveEdges(cellTriangle(2, 1, 1)) == 0b000100);
  // In the valley of the negated ridge the fold is concave from above.
  for (S& h : ridge) h = -h;
  const Field<S> valley = new spook::HeightFieldT<S>(n, n, S(4), S(4), ridge);
  CHECK(valley->getActiveEdges(cellTriangle(1, 1, 0)) == 0b010000);
}
