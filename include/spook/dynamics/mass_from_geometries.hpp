#pragma once

#include <optional>
#include <vector>

#include <spook/collide/geometry.hpp>
#include <spook/core/math.hpp>

namespace spook::detail {

/// Mass, center of mass and inertia of a set of geometries whose local
/// transforms place them in a body's model frame.
template <Scalar S>
struct GeneratedMass {
  S mass = S(0);                        ///< kg
  Vec3T<S> center = Vec3T<S>::Zero();     ///< model frame (m)
  Mat3T<S> inertia = Mat3T<S>::Zero();    ///< about `center`, model frame axes (kg·m²)
};

/// Each shape of volume V contributes m = ρV (ρ its geometry's material
/// density) at its center of volume; its tensor about its own origin is
/// moved to its center, turned into the model frame, then moved to the
/// common center (parallel-axis theorem, J(m, d) = m(|d|² 1 − d dᵀ)).
/// Empty when no shape has volume.
template <Scalar S>
[[nodiscard]] std::optional<GeneratedMass<S>> massFromGeometries(const std::vector<ref_ptr<GeometryT<S>>>& geometries) {
  struct Part {
    S mass;
    Vec3T<S> center;
    Mat3T<S> inertia;
  };
  const auto shift = [](S m, const Vec3T<S>& d) {
    return Mat3T<S>(m * (d.squaredNorm() * Mat3T<S>::Identity() - d * d.transpose()));
  };
  std::vector<Part> parts;
  GeneratedMass<S> total;
  Vec3T<S> moment = Vec3T<S>::Zero();
  for (const auto& geometry : geometries) {
    const S density = geometry->getMaterial()->getBulkMaterial()->getDensity();
    const TransformT<S> X_BG = geometry->getLocalTransform();
    for (const auto& entry : geometry->getShapes()) {
      const S volume = entry.shape->getVolume();
      if (!(volume > S(0))) continue;
      const S m = density * volume;
      const TransformT<S> X_BS = X_BG * entry.transform;
      const Vec3T<S> c_S = entry.shape->getCenterOfVolume();
      const Mat3T<S> R = X_BS.linear();
      const Mat3T<S> aboutCenter = entry.shape->calculateInertia(m).matrix() - shift(m, c_S);
      parts.push_back({m, X_BS * c_S, R * aboutCenter * R.transpose()});
      total.mass += m;
      moment += m * parts.back().center;
    }
  }
  if (parts.empty()) return std::nullopt;
  total.center = moment / total.mass;
  for (const Part& p : parts) total.inertia += p.inertia + shift(p.mass, p.center - total.center);
  total.inertia = S(0.5) * (total.inertia + total.inertia.transpose());
  return total;
}

}  // namespace spook::detail
