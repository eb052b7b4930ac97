#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <spook/collide/shapes/convex.hpp>
#include <spook/collide/shapes/line.hpp>
#include <spook/collide/shapes/plane.hpp>

#include "shape_helpers.hpp"
#include "tolerance.hpp"

using spook::test::checkRejects;
using spook::test::relative;

using spook::test::pick;

namespace {

template <class S>
using Points = std::vector<spook::Vec3T<S>>;

template <class S>
spook::ref_ptr<spook::ConvexT<S>> hullOf(const Points<S>& points) {
  return new spook::ConvexT<S>(points);
}


// A closed, consistently wound surface uses every directed edge once and its
// reverse once; the triangles face away from the center of volume.
template <class S>
void checkClosedOutward(const spook::ConvexT<S>& convex) {
  std::map<std::pair<int, int>, int> edges;
  for (const auto& t : convex.getTriangles())
    for (int i = 0; i < 3; ++i) ++edges[{t[i], t[(i + 1) % 3]}];
  bool closed = true;
  for (const auto& [edge, count] : edges) closed = closed && count == 1 && edges.count({edge.second, edge.first}) == 1;
  CHECK(closed);
  const auto& v = convex.getVertices();
  bool outward = true;
  for (const auto& t : convex.getTriangles()) {
    const spook::Vec3T<S> n = (v[t[1]] - v[t[0]]).cross(v[t[2]] - v[t[0]]);
    outward = outward && n.dot(v[t[0]] - convex.getCenterOfVolume()) > S(0);
  }
  CHECK(outward);
}

// Every face's corners lie on its plane and wind counter-clockwise about its
// outward normal; every corner lies on or below every face's plane.
template <class S>
void checkFaces(const spook::ConvexT<S>& convex, S tol) {
  const auto& v = convex.getVertices();
  S offPlane = S(0), beyond = S(0), turn = S(1);
  for (const auto& face : convex.getFaces()) {
    CHECK(std::abs(face.normal.norm() - S(1)) <= tol);
    for (std::size_t k = 0; k < face.vertices.size(); ++k) {
      const spook::Vec3T<S>& a = v[face.vertices[k]];
      const spook::Vec3T<S>& b = v[face.vertices[(k + 1) % face.vertices.size()]];
      const spook::Vec3T<S>& c = v[face.vertices[(k + 2) % face.vertices.size()]];
      offPlane = std::max(offPlane, std::abs(face.normal.dot(a) - face.offset));
      turn = std::min(turn, (b - a).cross(c - b).normalized().dot(face.normal));
    }
    for (const auto& p : v) beyond = std::max(beyond, face.normal.dot(p) - face.offset);
  }
  CHECK(offPlane <= tol);
  CHECK(beyond <= tol);
  CHECK(turn > S(0.99));  // every turn is a left turn about the normal: a convex loop, no straight corners
}


}  // namespace

// A box with half extents a, b, c: V = 8abc, I_c = m/3 (b² + c², a² + c², a² + b²)
// in its own axes. Its corners, 10 duplicates, its face centers, its edge
// midpoints and 200 interior points, turned by R and moved to t.
TEST_CASE_TEMPLATE("the hull of a box's corners and clutter inside is that box", S, float, double) {
  const S tol = pick<S>(1e-12, 1e-5);
  const spook::Vec3T<S> h(S(0.5), S(0.75), S(1.25));
  const spook::Mat3T<S> R = spook::toMatrix<S>({S(0.3), S(-1.1), S(2.4)});
  const spook::Vec3T<S> t(S(1.5), S(-1), S(0.5));
  Points<S> local;
  for (int i = 0; i < 8; ++i)
    local.emplace_back(i & 1 ? h.x() : -h.x(), i & 2 ? h.y() : -h.y(), i & 4 ? h.z() : -h.z());
  for (int i = 0; i < 10; ++i) local.push_back(local[static_cast<std::size_t>(i % 8)]);
  for (int axis = 0; axis < 3; ++axis) {
    local.push_back(h[axis] * spook::Vec3T<S>::Unit(axis));
    local.push_back(-h[axis] * spook::Vec3T<S>::Unit(axis));
  }
  for (int i = 0; i < 8; ++i)
    for (int axis = 0; axis < 3; ++axis) {
      spook::Vec3T<S> midpoint = local[static_cast<std::size_t>(i)];
      midpoint[axis] = S(0);
      local.push_back(midpoint);
    }
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.999, 0.999);
  for (int i = 0; i < 200; ++i) local.emplace_back(S(u(rng)) * h.x(), S(u(rng)) * h.y(), S(u(rng)) * h.z());
  std::shuffle(local.begin(), local.end(), rng);
  Points<S> points;
  for (const auto& p : local) points.push_back(R * p + t);

  const auto convex = hullOf<S>(points);
  CHECK(convex->getVertices().size() == 8);
  CHECK(convex->getTriangles().size() == 12);
  REQUIRE(convex->getFaces().size() == 6);
  for (const auto& face : convex->getFaces()) CHECK(face.vertices.size() == 4);
  for (const auto& v : convex->getVertices()) CHECK(((R.transpose() * (v - t)).cwiseAbs() - h).norm() <= tol * S(4));
  checkClosedOutward<S>(*convex);
  checkFaces<S>(*convex, tol * S(4));

  const S volume = S(8) * h.prod(), mass = S(7);
  CHECK(std::abs(convex->getVolume() - volume) <= tol * volume);
  CHECK((convex->getCenterOfVolume() - t).norm() <= tol * t.norm());
  const spook::Vec3T<S> sq = h.cwiseAbs2();
  const spook::Mat3T<S> expected = R * spook::Vec3T<S>(sq.y() + sq.z(), sq.x() + sq.z(), sq.x() + sq.y()).asDiagonal() *
                                  R.transpose() * (mass / S(3));
  const spook::Vec3T<S> c = convex->getCenterOfVolume();
  const spook::Mat3T<S> aboutCenter = convex->calculateInertia(mass).matrix() -
                                     mass * (c.squaredNorm() * spook::Mat3T<S>::Identity() - c * c.transpose());
  CHECK(relative<S>(aboutCenter, expected) <= tol);
  const spook::BoundingBoxT<S> box = convex->getBoundingBox();
  const spook::Vec3T<S> reach = R.cwiseAbs() * h;
  CHECK((box.min - (t - reach)).norm() <= tol * S(8));
  CHECK((box.max - (t + reach)).norm() <= tol * S(8));
}

// Regular tetrahedron of edge a about its centroid: V = a³/(6√2), I = m a²/20 · 1.
TEST_CASE_TEMPLATE("a regular tetrahedron has V = a³/(6√2) and I = m a²/20 about its centroid", S, float, double) {
  const S tol = pick<S>(1e-14, 2e-6);
  const double s = 0.7, a = 2 * std::sqrt(2.0) * s, mass = 3;
  const Points<S> corners = {spook::Vec3T<S>(S(s), S(s), S(s)), spook::Vec3T<S>(S(s), S(-s), S(-s)),
                             spook::Vec3T<S>(S(-s), S(s), S(-s)), spook::Vec3T<S>(S(-s), S(-s), S(s))};
  const auto convex = hullOf<S>(corners);
  CHECK(convex->getVertices().size() == 4);
  CHECK(convex->getFaces().size() == 4);
  checkClosedOutward<S>(*convex);
  const double volume = a * a * a / (6 * std::sqrt(2.0));
  CHECK(std::abs(convex->getVolume() - S(volume)) <= tol * S(volume));
  CHECK(convex->getCenterOfVolume().norm() <= tol);
  const spook::Mat3T<S> expected = spook::Mat3T<S>::Identity() * S(mass * a * a / 20);
  CHECK(relative<S>(convex->calculateInertia(S(mass)).matrix(), expected) <= tol);

  // Moved by d, about the shape origin: I + m(|d|² 1 − d dᵀ).
  const spook::Vec3T<S> d(S(1), S(-2), S(0.5));
  Points<S> moved;
  for (const auto& p : corners) moved.push_back(p + d);
  const auto shifted = hullOf<S>(moved);
  const spook::Mat3T<S> expectedShifted =
      expected + S(mass) * (d.squaredNorm() * spook::Mat3T<S>::Identity() - d * d.transpose());
  CHECK(relative<S>(shifted->calculateInertia(S(mass)).matrix(), expectedShifted) <= tol * S(4));
}

// A 32-gon prism, r = 0.8, height 1.5, with a 5 × 5 grid on each cap:
// V = N/2 r² sin(2π/N) h, two 32-corner caps and 32 rectangles.
TEST_CASE_TEMPLATE("a prism with grids on its caps keeps two polygon caps", S, float, double) {
  const S tol = pick<S>(1e-12, 1e-5);
  const int n = 32;
  const double r = 0.8, height = 1.5, pi = std::numbers::pi;
  Points<S> points;
  for (int i = 0; i < n; ++i)
    for (const double z : {-height / 2, height / 2})
      points.emplace_back(S(r * std::cos(2 * pi * i / n)), S(r * std::sin(2 * pi * i / n)), S(z));
  for (int i = -2; i <= 2; ++i)
    for (int j = -2; j <= 2; ++j)
      for (const double z : {-height / 2, height / 2}) points.emplace_back(S(0.2 * i), S(0.2 * j), S(z));
  const auto convex = hullOf<S>(points);
  CHECK(convex->getVertices().size() == 2 * n);
  CHECK(convex->getFaces().size() == n + 2);
  std::size_t largest = 0;
  for (const auto& face : convex->getFaces()) largest = std::max(largest, face.vertices.size());
  CHECK(largest == std::size_t(n));
  CHECK(convex->getTriangles().size() == std::size_t(4 * n - 4));
  checkClosedOutward<S>(*convex);
  checkFaces<S>(*convex, tol);
  const double volume = n / 2.0 * r * r * std::sin(2 * pi / n) * height;
  CHECK(std::abs(convex->getVolume() - S(volume)) <= tol * S(volume));
}

// Points within the tolerance of a face (1e-7 of the size for double, 16 ulps
// for float) merge into it; points clearly beyond it (here 1e-3 of the size)
// become the apexes of shallow pyramids.
TEST_CASE_TEMPLATE("face points barely above a face are dropped, points clearly above are kept", S, float, double) {
  for (const double lift : {double(pick<S>(1e-8, 1e-7)), 1e-3}) {
    CAPTURE(lift);
    Points<S> points;
    for (int i = 0; i < 8; ++i) points.emplace_back(i & 1 ? S(1) : S(-1), i & 2 ? S(1) : S(-1), i & 4 ? S(1) : S(-1));
    for (int axis = 0; axis < 3; ++axis)
      for (const double side : {-1.0, 1.0}) points.push_back(S(side * (1 + lift)) * spook::Vec3T<S>::Unit(axis));
    const auto convex = hullOf<S>(points);
    const bool kept = lift > 1e-4;
    CHECK(convex->getVertices().size() == (kept ? 14u : 8u));
    CHECK(convex->getFaces().size() == (kept ? 24u : 6u));
    checkClosedOutward<S>(*convex);
    checkFaces<S>(*convex, S(2) * convex->getTolerance());
    const double volume = 8 + (kept ? 6 * 4 * lift / 3 : 0);
    CHECK(std::abs(convex->getVolume() - S(volume)) <= pick<S>(1e-12, 1e-6) * S(volume));
  }
}

// The hull of points on the unit sphere is inscribed: its volume tends to
// 4/3 π from below, and it contains every point it was built from.
TEST_CASE_TEMPLATE("the hull of 2000 points on a sphere contains them all and nearly fills the ball", S, float,
                   double) {
  std::mt19937 rng(11);
  std::normal_distribution<double> normal(0.0, 1.0);
  Points<S> points;
  for (int i = 0; i < 2000; ++i) {
    const spook::Vec3 p(normal(rng), normal(rng), normal(rng));
    points.push_back(p.normalized().template cast<S>());
  }
  const auto convex = hullOf<S>(points);
  const auto& v = convex->getVertices();
  CHECK(v.size() > 64);                                      // large enough that support() climbs
  CHECK(convex->getTriangles().size() == 2 * v.size() - 4);  // Euler: closed triangulated sphere
  checkClosedOutward<S>(*convex);
  // The hull's tolerance: 1e-7 (double) or 16 ulps (float) of the half
  // diagonal √3, plus 16 ulps of the largest coordinate 1.
  CHECK(convex->getTolerance() <= pick<S>(1.8e-7, 5.3e-6));
  const S tol = S(2) * convex->getTolerance();
  checkFaces<S>(*convex, tol);

  const S ball = S(4.0 / 3.0 * std::numbers::pi);
  CHECK(convex->getVolume() < ball);
  CHECK(convex->getVolume() > S(0.99) * ball);
  S outside = S(0);
  for (const auto& face : convex->getFaces())
    for (const auto& p : points) outside = std::max(outside, face.normal.dot(p) - face.offset);
  CHECK(outside <= tol);

  S shortfall = S(0), againstScan = S(0);
  for (int i = 0; i < 200; ++i) {
    const spook::Vec3T<S> d(S(normal(rng)), S(normal(rng)), S(normal(rng)));
    const S reached = convex->support(d).dot(d);
    S best = std::numeric_limits<S>::lowest();
    for (const auto& p : points) best = std::max(best, p.dot(d));
    shortfall = std::max(shortfall, (best - reached) / d.norm());
    S scan = std::numeric_limits<S>::lowest();
    for (const auto& p : v) scan = std::max(scan, p.dot(d));
    againstScan = std::max(againstScan, (scan - reached) / d.norm());
  }
  CHECK(shortfall <= tol);
  CHECK(againstScan <= tol);
}

TEST_CASE_TEMPLATE("a small hull's support is its farthest corner by a full scan", S, float, double) {
  std::mt19937 rng(3);
  std::normal_distribution<double> normal(0.0, 1.0);
  Points<S> points;
  for (int i = 0; i < 40; ++i) points.emplace_back(S(normal(rng)), S(2 * normal(rng)), S(0.5 * normal(rng)));
  const auto convex = hullOf<S>(points);
  CHECK(convex->getVertices().size() <= 40);
  bool farthest = true;
  for (int i = 0; i < 200; ++i) {
    const spook::Vec3T<S> d(S(normal(rng)), S(normal(rng)), S(normal(rng)));
    const S reached = convex->support(d).dot(d);
    for (const auto& p : points) farthest = farthest && p.dot(d) <= reached;
  }
  CHECK(farthest);
  const spook::BoundingBoxT<S> box = convex->getBoundingBox();
  bool inside = true;
  for (const auto& p : points) inside = inside && box.contains(p);
  CHECK(inside);
  for (int axis = 0; axis < 3; ++axis) {
    S hi = std::numeric_limits<S>::lowest();
    for (const auto& p : points) hi = std::max(hi, p[axis]);
    CHECK(box.max[axis] == hi);
  }
}

TEST_CASE_TEMPLATE("a line's support is the endpoint farther along, the first on a tie", S, float, double) {
  const spook::Vec3T<S> p1(S(1), S(-2), S(0.5)), p2(S(-3), S(4), S(2));
  spook::ref_ptr<spook::LineT<S>> line = new spook::LineT<S>(p1, p2);
  std::mt19937 rng(9);
  std::normal_distribution<double> normal(0.0, 1.0);
  bool farthest = true;
  for (int i = 0; i < 200; ++i) {
    const spook::Vec3T<S> d(S(normal(rng)), S(normal(rng)), S(normal(rng)));
    const spook::Vec3T<S> s = line->support(d);
    farthest = farthest && (s == p1 || s == p2) && s.dot(d) >= p1.dot(d) && s.dot(d) >= p2.dot(d);
  }
  CHECK(farthest);
  const spook::Vec3T<S> across = (p2 - p1).cross(spook::Vec3T<S>::UnitZ());
  CHECK(line->support(across) == p1);
  CHECK(line->support(spook::Vec3T<S>::Zero()) == p1);
  CHECK(line->getVolume() == S(0));
  CHECK(line->getCenterOfVolume() == spook::Vec3T<S>(S(-1), S(1), S(1.25)));
  CHECK(line->getBoundingBox().min == spook::Vec3T<S>(S(-3), S(-2), S(0.5)));
  CHECK(line->getBoundingBox().max == spook::Vec3T<S>(S(1), S(4), S(2)));
  CHECK(std::abs(line->getLength() - std::sqrt(S(54.25))) <= pick<S>(1e-15, 1e-6) * S(8));
  CHECK((line->getType() == spook::ShapeType::LINE));
}

TEST_CASE_TEMPLATE("a plane's normal is normalized and its solid lies below it", S, float, double) {
  const S tol = pick<S>(1e-15, 1e-6);
  spook::ref_ptr<spook::PlaneT<S>> plane =
      new spook::PlaneT<S>(spook::Vec3T<S>(S(0), S(3), S(4)), spook::Vec3T<S>(S(7), S(1), S(-2)));
  CHECK((plane->getNormal() - spook::Vec3T<S>(S(0), S(0.6), S(0.8))).norm() <= tol);
  CHECK(std::abs(plane->getDistance() - S(-1)) <= tol);  // 0.6·1 + 0.8·(−2)
  CHECK(std::abs(plane->signedDistance(spook::Vec3T<S>(S(-5), S(1), S(3))) - S(4)) <= tol * S(4));
  CHECK(plane->signedDistance(spook::Vec3T<S>(S(0), S(-10), S(0))) < S(0));

  spook::ref_ptr<spook::PlaneT<S>> ground = new spook::PlaneT<S>(spook::Vec3T<S>(S(0), S(0), S(2)), S(1.5));
  CHECK(ground->getPoint() == spook::Vec3T<S>(S(0), S(0), S(1.5)));
  CHECK(ground->getDistance() == S(1.5));
  CHECK(ground->signedDistance(spook::Vec3T<S>(S(9), S(-9), S(1))) == S(-0.5));
  spook::ref_ptr<spook::PlaneT<S>> tiny = new spook::PlaneT<S>(spook::Vec3T<S>(S(1e-30), S(0), S(0)), 0);
  CHECK(tiny->getNormal() == spook::Vec3T<S>::UnitX());

  CHECK(plane->getVolume() == S(0));
  CHECK((plane->getType() == spook::ShapeType::PLANE));
  const spook::BoundingBoxT<S> box = plane->getBoundingBox();
  CHECK(box.min == spook::Vec3T<S>::Constant(-std::numeric_limits<S>::infinity()));
  CHECK(box.max == spook::Vec3T<S>::Constant(std::numeric_limits<S>::infinity()));
}

// AGX's four Plane constructors: (normal, point), (normal, distance),
// three points (normal by the right-hand rule), a·x + b·y + c·z = d.
TEST_CASE_TEMPLATE("every plane constructor gives the plane its arguments describe", S, float, double) {
  using V = spook::Vec3T<S>;
  using PlaneRef = spook::ref_ptr<spook::PlaneT<S>>;
  const S tol = pick<S>(1e-15, 1e-6);
  // The plane 2x − y + 2z = 6: unit normal (2, −1, 2)/3, distance 2, through (1, −2, 1).
  const V n(S(2) / S(3), S(-1) / S(3), S(2) / S(3));
  const auto describes = [&](const PlaneRef& plane) {
    CHECK((plane->getNormal() - n).norm() <= tol);
    CHECK(std::abs(plane->getDistance() - S(2)) <= S(2) * tol);
    CHECK(std::abs(plane->signedDistance(V(S(1), S(-2), S(1)))) <= S(4) * tol);
    CHECK(std::abs(plane->signedDistance(V(S(3), S(-3), S(3))) - S(3)) <= S(8) * tol);  // 3 above along n
  };
  describes(new spook::PlaneT<S>(V(S(2), S(-1), S(2)), V(S(1), S(-2), S(1))));
  describes(new spook::PlaneT<S>(V(S(4), S(-2), S(4)), S(2)));
  describes(new spook::PlaneT<S>(S(2), S(-1), S(2), S(6)));
  describes(new spook::PlaneT<S>(S(4e-20), S(-2e-20), S(4e-20), S(12e-20)));  // squares underflow in float
  // Points (1, −2, 1), (2, 0, 1), (1, 0, 2): (p2 − p1) × (p3 − p1) = (1, 2, 0) × (0, 2, 1) = (2, −1, 2).
  describes(new spook::PlaneT<S>(V(S(1), S(-2), S(1)), V(S(2), S(0), S(1)), V(S(1), S(0), S(2))));
  // Clockwise order flips the normal: the solid is then on the other side.
  const PlaneRef flipped = new spook::PlaneT<S>(V(S(1), S(-2), S(1)), V(S(1), S(0), S(2)), V(S(2), S(0), S(1)));
  CHECK((flipped->getNormal() + n).norm() <= tol);
  CHECK(flipped->getPoint() == V(S(1), S(-2), S(1)));
  // Through three points far apart in scale: huge and tiny triangles give the same unit normal.
  const PlaneRef huge = new spook::PlaneT<S>(V::Zero(), V(S(1e30), S(0), S(0)), V(S(0), S(1e30), S(0)));
  const PlaneRef tiny = new spook::PlaneT<S>(V::Zero(), V(S(1e-30), S(0), S(0)), V(S(0), S(1e-30), S(0)));
  CHECK(huge->getNormal() == V::UnitZ());
  CHECK(tiny->getNormal() == V::UnitZ());
  // a·x + b·y + c·z = d with the ground's numbers: z = 0.5.
  const PlaneRef ground = new spook::PlaneT<S>(0, 0, 1, S(0.5));
  CHECK(ground->getNormal() == V::UnitZ());
  CHECK(ground->getPoint() == V(S(0), S(0), S(0.5)));
}

TEST_CASE_TEMPLATE("plane constructors refuse coincident or collinear points and a zero normal, naming the value", S,
                   float, double) {
  using V = spook::Vec3T<S>;
  const S nan = std::numeric_limits<S>::quiet_NaN(), inf = std::numeric_limits<S>::infinity();
  const S big = std::numeric_limits<S>::max();
  const auto three = [](V a, V b, V c) { return [=] { spook::ref_ptr<spook::PlaneT<S>> p = new spook::PlaneT<S>(a, b, c); }; };
  const auto four = [](S a, S b, S c, S d) { return [=] { spook::ref_ptr<spook::PlaneT<S>> p = new spook::PlaneT<S>(a, b, c, d); }; };
  checkRejects(three(V::Ones(), V::Ones(), V::UnitX()), "coincide", "(1, 1, 1, 1, 1, 1, 1, 0, 0)");
  checkRejects(three(V::Zero(), V::UnitX(), V::UnitX()), "collinear", "(0, 0, 0, 1, 0, 0, 1, 0, 0)");
  checkRejects(three(V::Zero(), V(S(1), S(2), S(3)), V(S(-2), S(-4), S(-6))), "collinear",
               "(0, 0, 0, 1, 2, 3, -2, -4, -6)");
  checkRejects(three(V::Zero(), V(S(1), S(1), S(0)), V(S(4), S(4), S(1e-20))), "collinear",
               "(0, 0, 0, 1, 1, 0, 4, 4, 1e-20)");
  checkRejects(three(V::Zero(), V(nan, S(0), S(0)), V::UnitY()), "finite", "(0, 0, 0, nan, 0, 0, 0, 1, 0)");
  checkRejects(three(V(-big, S(0), S(0)), V(big, S(0), S(0)), V::UnitY()), "finite", "(-");
  checkRejects(four(S(0), S(0), S(0), S(1)), "non-zero", "(0, 0, 0)");
  checkRejects(four(S(0), inf, S(1), S(1)), "non-zero", "(0, inf, 1)");
  checkRejects(four(S(0), S(0), S(1), nan), "Plane", "(0, 0, 1, nan)");
  checkRejects(four(S(0), S(0), S(1e-30), big), "Plane", "(0, 0, 1e-30, ");
}

TEST_CASE_TEMPLATE("plane, line and convex reject bad input and name the value", S, float, double) {
  const S nan = std::numeric_limits<S>::quiet_NaN(), inf = std::numeric_limits<S>::infinity();
  using V = spook::Vec3T<S>;
  const auto convex = [](Points<S> points) { return [points] { (void)hullOf<S>(points); }; };

  Points<S> cube;
  for (int i = 0; i < 8; ++i) cube.emplace_back(S(i & 1), S((i >> 1) & 1), S((i >> 2) & 1));
  Points<S> bad = cube;
  bad[5] = V(S(1), nan, S(0));
  checkRejects(convex(bad), "Convex", "(1, nan, 0)");
  bad[5] = V(inf, S(0), S(0));
  checkRejects(convex(bad), "Convex", "(inf, 0, 0)");
  checkRejects(convex({V(S(0), S(0), S(0)), V(S(1), S(0), S(0)), V(S(0), S(1), S(0))}), "Convex", "3");
  checkRejects(convex({}), "Convex", "0");

  // Ten points on a tilted plane (off it only by round-off), collinear points,
  // coincident points: none spans a volume.
  const spook::Mat3T<S> R = spook::toMatrix<S>({S(0.4), S(0.9), S(-0.3)});
  Points<S> flat, collinear, coincident;
  for (int i = 0; i < 10; ++i) {
    flat.push_back(R * V(S(std::cos(i)), S(std::sin(3 * i)), S(0)) + V(S(1), S(2), S(3)));
    collinear.push_back(R * V(S(0.25 * i), S(0), S(0)));
    coincident.push_back(V(S(1), S(2), S(3)));
  }
  checkRejects(convex(flat), "Convex", "10");
  checkRejects(convex(collinear), "Convex", "10");
  checkRejects(convex(coincident), "Convex", "10");
  checkRejects([&] { (void)hullOf<S>(cube)->calculateInertia(S(-1)); }, "Convex", "-1");

  checkRejects([] { spook::ref_ptr<spook::PlaneT<S>> p = new spook::PlaneT<S>(V::Zero()); }, "Plane", "(0, 0, 0)");
  checkRejects([&] { spook::ref_ptr<spook::PlaneT<S>> p = new spook::PlaneT<S>(V(nan, S(0), S(1))); }, "Plane",
               "(nan, 0, 1)");
  checkRejects([&] { spook::ref_ptr<spook::PlaneT<S>> p = new spook::PlaneT<S>(V::UnitZ(), V(S(0), inf, S(0))); },
               "Plane", "(0, inf, 0)");
  checkRejects([&] { spook::ref_ptr<spook::PlaneT<S>> p = new spook::PlaneT<S>(V::UnitZ(), nan); }, "Plane", "nan");
  spook::ref_ptr<spook::PlaneT<S>> plane = new spook::PlaneT<S>(V::UnitY(), S(2));
  checkRejects([&] { plane->set(V::Zero(), V::Zero()); }, "Plane", "(0, 0, 0)");
  CHECK(plane->getNormal() == V::UnitY());
  CHECK(plane->getPoint() == V(S(0), S(2), S(0)));
  checkRejects([&] { (void)plane->calculateInertia(S(2)); }, "Plane", "2");

  checkRejects([] { spook::ref_ptr<spook::LineT<S>> l = new spook::LineT<S>(V::Ones(), V::Ones()); }, "Line",
               "(1, 1, 1, 1, 1, 1)");
  checkRejects([&] { spook::ref_ptr<spook::LineT<S>> l = new spook::LineT<S>(V::Zero(), V(S(1), nan, S(0))); }, "Line",
               "(0, 0, 0, 1, nan, 0)");
  spook::ref_ptr<spook::LineT<S>> line = new spook::LineT<S>(V::Zero(), V::UnitX());
  checkRejects([&] { line->setPoints(V::UnitY(), V::UnitY()); }, "Line", "(0, 1, 0, 0, 1, 0)");
  CHECK(line->getFirstPoint() == V::Zero());
  CHECK(line->getSecondPoint() == V::UnitX());
  checkRejects([&] { (void)line->calculateInertia(S(1.5)); }, "Line", "1.5");
}
