#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <spook/collide/contact_sink.hpp>
#include <spook/collide/detail/ccd_bridge.hpp>
#include <spook/collide/detail/cylinder_rim.hpp>
#include <spook/collide/detail/triangle.hpp>
#include <spook/collide/shapes/cylinder.hpp>

namespace spook::detail {

/// The projection overlap of a cylinder (radius R, half-height H, axis y,
/// centered on its frame's origin) and a triangle given in that frame,
/// along the unit n from the cylinder toward the triangle:
/// f(n) = R·|n_xz| + H·|n_y| − min_i n·v_i.
struct CylinderTriangleOverlap {
  double R, H;
  std::array<Vec3T<double>, 3> v;

  [[nodiscard]] double operator()(const Vec3T<double>& n) const {
    return R * std::sqrt(n.x() * n.x() + n.z() * n.z()) + H * std::abs(n.y()) -
           std::min({n.dot(v[0]), n.dot(v[1]), n.dot(v[2])});
  }
};

/// The lowest f found so far and its direction.
struct LowestOverlap {
  double f = std::numeric_limits<double>::infinity();
  Vec3T<double> n = Vec3T<double>::UnitY();

  void consider(const CylinderTriangleOverlap& overlap, const Vec3T<double>& direction) {
    const double length = direction.norm();
    if (!(length > 0.0)) return;
    const Vec3T<double> d = direction / length;
    if (const double value = overlap(d); value < f) {
      f = value;
      n = d;
    }
  }
};

/// Samples of a great circle before the local minima are refined, and the
/// golden-section steps that refine each (a bracket of two sample spacings,
/// 0.26 rad, to 1e-8 rad: a smooth minimum's depth within R·1e-16).
inline constexpr int kCircleSamples = 48;
inline constexpr int kGoldenSteps = 36;

/// The minimum of f over the great circle perpendicular to `axis`: sampled
/// evenly and at the directions `kinks` project to (where f is not smooth,
/// and the points nearest ±y, where R·|n_xz| narrows to a notch), each
/// sampled local minimum then refined by golden section between its
/// neighbours. f on the circle is smooth between its kinks, with at most a
/// few minima. The refinement moves along normalize(d + t·tangent), which
/// covers the arc between the neighbours monotonically in t (no sines).
inline void circleMinimum(const CylinderTriangleOverlap& f, const Vec3T<double>& axis,
                          const std::vector<Vec3T<double>>& kinks, LowestOverlap& lowest) {
  const double length = axis.norm();
  if (!(length > 0.0)) return;
  const Vec3T<double> u = axis / length, a = u.unitOrthogonal(), b = u.cross(a);
  constexpr double kTwoPi = 6.283185307179586;
  struct Sample {
    double angle;
    Vec3T<double> d;
    double f;
  };
  static const std::array<std::array<double, 2>, kCircleSamples> unit = [] {
    std::array<std::array<double, 2>, kCircleSamples> table{};
    for (int i = 0; i < kCircleSamples; ++i)
      table[static_cast<std::size_t>(i)] = {std::cos(kTwoPi * i / kCircleSamples),
                                            std::sin(kTwoPi * i / kCircleSamples)};
    return table;
  }();
  thread_local std::vector<Sample> samples;
  samples.clear();
  for (int i = 0; i < kCircleSamples; ++i) {
    const auto& [c, sn] = unit[static_cast<std::size_t>(i)];
    samples.push_back({kTwoPi * i / kCircleSamples, c * a + sn * b, 0.0});
  }
  for (const Vec3T<double>& k : kinks) {
    const double x = k.dot(a), y = k.dot(b), r = std::hypot(x, y);
    if (r > 1e-12 * k.norm())
      samples.push_back({std::atan2(y, x) + (y < 0.0 ? kTwoPi : 0.0), (x / r) * a + (y / r) * b, 0.0});
  }
  std::sort(samples.begin(), samples.end(), [](const Sample& x, const Sample& y) { return x.angle < y.angle; });
  for (Sample& sample : samples) sample.f = f(sample.d);
  const std::size_t count = samples.size();
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  for (std::size_t i = 0; i < count; ++i) {
    const Sample &before = samples[(i + count - 1) % count], &at = samples[i], &after = samples[(i + 1) % count];
    if (at.f > before.f || at.f > after.f) continue;
    lowest.consider(f, at.d);
    const Vec3T<double> tangent = u.cross(at.d);
    const double back = std::remainder(at.angle - before.angle, kTwoPi),
                 ahead = std::remainder(after.angle - at.angle, kTwoPi);
    const auto direction = [&](double t) { return Vec3T<double>((at.d + t * tangent).normalized()); };
    double lo = -std::tan(std::abs(back)), hi = std::tan(std::abs(ahead));
    double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
    double f1 = f(direction(x1)), f2 = f(direction(x2));
    for (int step = 0; step < kGoldenSteps; ++step) {
      if (f1 <= f2) {
        hi = x2, x2 = x1, f2 = f1;
        x1 = hi - g * (hi - lo), f1 = f(direction(x1));
      } else {
        lo = x1, x1 = x2, f1 = f2;
        x2 = lo + g * (hi - lo), f2 = f(direction(x2));
      }
    }
    lowest.consider(f, direction(f1 <= f2 ? x1 : x2));
  }
}

/// A cylinder against a triangle's face as against a plane (Collider<
/// CylinderT, PlaneT>): where the normal n (from the cylinder toward the
/// triangle, world) is the face's, on its front, within the supporting-
/// feature angle, the rim candidates (cylinderRimCandidates) over the
/// triangle within the sink's margin are its points, touching or gap
/// points, and true is returned. False leaves the pair to the features:
/// apart other than across the face (no points: a ghost contact where a
/// wheel rolls from one triangle onto the next), or touching with a
/// candidate beside the triangle across an active edge (`active`, as
/// activeEdges(): the cylinder rests across a ridge or a rim). A candidate
/// beside it across an inactive edge is the flat neighbour's (a triangle
/// under the cap with no candidate over it gives none). Touching, the
/// features' points (five to eight around a standing cylinder's cap, one
/// once it tilts past the feature angle) let Gauss–Seidel tip a cylinder
/// resting on a mesh and rock it 15–23 mm deep at h = 0.1 s, a wheel 12 mm
/// (through the mesh under a 2.5 kN load), where on a plane it rests.
template <Scalar S>
bool rimPointsOverFace(const CylinderT<S>& cylinder, const TransformT<S>& X_WA, const Triangle<S>& t_M,
                       const TransformT<S>& X_WM, const Vec3T<double>& n, bool touchingIt, double touching,
                       std::uint8_t active, ContactSinkT<S>& sink) {
  const TransformT<double> X = X_WM.template cast<double>();
  const Triangle<double> t{{X * t_M.v[0].template cast<double>(), X * t_M.v[1].template cast<double>(),
                            X * t_M.v[2].template cast<double>()}};
  const Vec3T<double> face = t.normal();
  if (!(-n.dot(face) >= kSupportingFeatureCos)) return !touchingIt;
  const auto& R_WA = X_WA.linear();
  const auto candidates = cylinderRimCandidates<double>(
      X_WA.translation().template cast<double>(), R_WA.col(1).template cast<double>(),
      R_WA.col(0).template cast<double>(), double(cylinder.getRadius()), 0.5 * double(cylinder.getHeight()), face);
  return addRimPointsOverFace<S>(
      candidates, face, t.v[0], touching, -1.0, [&](const Vec3T<double>& p) { return t.edgesBeside(p, face) == 0; },
      [&](const Vec3T<double>& p) { return touchingIt && (t.edgesBeside(p, face) & active & 7u) != 0; }, sink);
}

/// Cylinder against one triangle of a mesh (mesh frame t_M, placed by
/// X_WM), without libccd: f's minimum over the unit sphere is the
/// penetration (or minus the distance apart), and it lies where f is
/// smooth, at a direction normal to both shapes (the nearest boundary point
/// of the Minkowski difference). Those are ±y (a cap), the triangle's ±
/// normal, the great circle perpendicular to y (the side) and those
/// perpendicular to each edge (the edge against a cap, the side or the
/// rim); apart, also a vertex against the rim, along the line from the
/// rim's nearest point. Across the triangle's face, on its front (its
/// winding's normal), the contacts are the rim candidates over the
/// triangle, as against a plane, touching or within the sink's margin
/// (rimPointsOverFace; `active`: the triangle's activeEdges()); elsewhere
/// the overlap of the two supporting features along that normal
/// (contactsOfFeatures), as libccd's path gives them, at a fraction of its
/// cost, and apart no points. Without the gap points a wheel driven over a
/// height field at h = 0.1 s dropped a step of free fall into each
/// downslope, its center 17 cm below the terrain.
template <Scalar S>
void collideCylinderTriangle(const CylinderT<S>& cylinder, const TransformT<S>& X_WA, const Triangle<S>& t_M,
                             const TransformT<S>& X_WM, ContactSinkT<S>& sink, std::uint8_t active = 0b111111) {
  const ConvexSupport viewA = convexSupportOf(cylinder), viewB = convexSupportOf(t_M);
  const double sizeA = viewA.size, sizeB = viewB.size;
  if (!std::isfinite(sizeA) || !std::isfinite(sizeB)) return;
  const TransformT<double> X_AM = X_WA.template cast<double>().inverse(Eigen::Isometry) * X_WM.template cast<double>();
  CylinderTriangleOverlap f{double(cylinder.getRadius()), 0.5 * double(cylinder.getHeight()), {}};
  for (int k = 0; k < 3; ++k)
    f.v[static_cast<std::size_t>(k)] = X_AM * t_M.v[static_cast<std::size_t>(k)].template cast<double>();
  const Vec3T<double> y = Vec3T<double>::UnitY();
  const Vec3T<double> normal = (f.v[1] - f.v[0]).cross(f.v[2] - f.v[0]);
  LowestOverlap lowest;
  for (const Vec3T<double>& d : {y, Vec3T<double>(-y), normal, Vec3T<double>(-normal)}) lowest.consider(f, d);
  // Apart: a vertex nearest the rim.
  for (const Vec3T<double>& v : f.v) {
    const double radial = std::hypot(v.x(), v.z());
    const double scale = radial > f.R ? f.R / radial : 1.0;
    const Vec3T<double> nearest(v.x() * scale, std::clamp(v.y(), -f.H, f.H), v.z() * scale);
    lowest.consider(f, v - nearest);
  }
  // Most triangles a query visits are apart along one of these already.
  const double touching = kTouchingGap * std::min(sizeA, sizeB);
  const double reach = std::max(touching, double(sink.margin()));
  if (lowest.f < -reach) return;
  thread_local std::vector<Vec3T<double>> kinks;
  kinks.clear();
  for (int k = 0; k < 3; ++k) {
    const Vec3T<double>& v = f.v[static_cast<std::size_t>(k)];
    kinks.push_back(Vec3T<double>(v.x(), 0.0, v.z()));
    kinks.push_back(y.cross(f.v[static_cast<std::size_t>((k + 1) % 3)] - v));
  }
  circleMinimum(f, y, kinks, lowest);
  for (int k = 0; k < 3; ++k) {
    const Vec3T<double> edge = f.v[static_cast<std::size_t>((k + 1) % 3)] - f.v[static_cast<std::size_t>(k)];
    kinks.assign({y.cross(edge), normal, y, Vec3T<double>(-y)});
    circleMinimum(f, edge, kinks, lowest);
  }
  if (!std::isfinite(lowest.f) || lowest.f < -reach) return;
  const Vec3T<double> n = X_WA.linear().template cast<double>() * lowest.n;
  if (rimPointsOverFace<S>(cylinder, X_WA, t_M, X_WM, n, lowest.f >= -touching, touching, active, sink)) return;
  const CcdObject objectA(viewA, X_WA);
  const CcdObject objectB(viewB, X_WM);
  for (const FeatureClipping::Contact& contact : contactsOfFeatures(objectA, objectB, n, std::max(lowest.f, 0.0)))
    sink.add(contact.point.cast<S>(), n.cast<S>(), S(contact.depth));
}

}  // namespace spook::detail
