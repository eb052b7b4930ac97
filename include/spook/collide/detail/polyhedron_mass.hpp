#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include <spook/core/math.hpp>

namespace spook::detail {

/// Volume, center of volume and second moments of a closed, outward-wound
/// triangle mesh of unit density.
template <Scalar S>
struct PolyhedronMass {
  S volume = S(0);               ///< m³
  Vec3T<S> center = Vec3T<S>::Zero();  ///< center of volume, mesh frame (m)
  Mat3T<S> inertia = Mat3T<S>::Zero();  ///< unit-density inertia about `center`, mesh frame (m⁵)
};

/// Exact integrals over the polyhedron by the divergence theorem, one
/// tetrahedron-free pass over the faces (D. Eberly, "Polyhedral Mass
/// Properties (Revisited)", 2002; after Mirtich 1996). The vertices are first
/// shifted to their mean so that far-from-origin meshes keep their digits.
template <Scalar S>
[[nodiscard]] PolyhedronMass<S> polyhedronMass(const std::vector<Vec3T<S>>& vertices,
                                               const std::vector<std::array<int, 3>>& triangles) {
  Vec3T<S> reference = Vec3T<S>::Zero();
  for (const auto& v : vertices) reference += v;
  if (!vertices.empty()) reference /= S(vertices.size());

  // ∫1, ∫x, ∫y, ∫z, ∫x², ∫y², ∫z², ∫xy, ∫yz, ∫zx (each times 6, 24, 60 or 120).
  std::array<S, 10> integral{};
  const auto subexpressions = [](S w0, S w1, S w2, S& f1, S& f2, S& f3, S& g0, S& g1, S& g2) {
    const S t0 = w0 + w1, t1 = w0 * w0, t2 = t1 + w1 * t0;
    f1 = t0 + w2;
    f2 = t2 + w2 * f1;
    f3 = w0 * t1 + w1 * t2 + w2 * f2;
    g0 = f2 + w0 * (f1 + w0);
    g1 = f2 + w1 * (f1 + w1);
    g2 = f2 + w2 * (f1 + w2);
  };
  for (const auto& t : triangles) {
    const Vec3T<S> p0 = vertices[static_cast<std::size_t>(t[0])] - reference;
    const Vec3T<S> p1 = vertices[static_cast<std::size_t>(t[1])] - reference;
    const Vec3T<S> p2 = vertices[static_cast<std::size_t>(t[2])] - reference;
    const Vec3T<S> d = (p1 - p0).cross(p2 - p0);
    S f1x, f2x, f3x, g0x, g1x, g2x, f1y, f2y, f3y, g0y, g1y, g2y, f1z, f2z, f3z, g0z, g1z, g2z;
    subexpressions(p0.x(), p1.x(), p2.x(), f1x, f2x, f3x, g0x, g1x, g2x);
    subexpressions(p0.y(), p1.y(), p2.y(), f1y, f2y, f3y, g0y, g1y, g2y);
    subexpressions(p0.z(), p1.z(), p2.z(), f1z, f2z, f3z, g0z, g1z, g2z);
    integral[0] += d.x() * f1x;
    integral[1] += d.x() * f2x;
    integral[2] += d.y() * f2y;
    integral[3] += d.z() * f2z;
    integral[4] += d.x() * f3x;
    integral[5] += d.y() * f3y;
    integral[6] += d.z() * f3z;
    integral[7] += d.x() * (p0.y() * g0x + p1.y() * g1x + p2.y() * g2x);
    integral[8] += d.y() * (p0.z() * g0y + p1.z() * g1y + p2.z() * g2y);
    integral[9] += d.z() * (p0.x() * g0z + p1.x() * g1z + p2.x() * g2z);
  }
  constexpr std::array<double, 10> scale = {1.0 / 6,  1.0 / 24, 1.0 / 24, 1.0 / 24,  1.0 / 60,
                                            1.0 / 60, 1.0 / 60, 1.0 / 120, 1.0 / 120, 1.0 / 120};
  for (std::size_t i = 0; i < integral.size(); ++i) integral[i] *= S(scale[i]);

  PolyhedronMass<S> mass;
  mass.volume = integral[0];
  if (!(mass.volume > S(0))) return mass;
  const Vec3T<S> c(integral[1] / mass.volume, integral[2] / mass.volume, integral[3] / mass.volume);
  // Second moments about the reference point, then moved to the center
  // (parallel-axis theorem with the unit-density mass V).
  Mat3T<S> I;
  I(0, 0) = integral[5] + integral[6];
  I(1, 1) = integral[4] + integral[6];
  I(2, 2) = integral[4] + integral[5];
  I(0, 1) = I(1, 0) = -integral[7];
  I(1, 2) = I(2, 1) = -integral[8];
  I(0, 2) = I(2, 0) = -integral[9];
  mass.inertia = I - mass.volume * (c.squaredNorm() * Mat3T<S>::Identity() - c * c.transpose());
  mass.center = c + reference;
  return mass;
}

}  // namespace spook::detail
