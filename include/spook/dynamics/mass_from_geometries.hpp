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
  Vec3<S> center = Vec3<S>::Zero();     ///< model frame (m)
  Mat3<S> inertia = Mat3<S>::Zero();    ///< about `center`, model frame axes (kg·m²)
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
    Vec3<S> center;
    Mat3<S> inertia;
  };
  const auto shift = [](S m, const Vec3<S>& d) {
    return Mat3<S>(m * (d.squaredNorm() * Mat3<S>::Identity() - d * d.transpose()));
  };
  std::vector<Part> parts;
  GeneratedMass<S> total;
  Vec3<S> moment = Vec3<S>::Zero();
  for (const auto& geometry : geometries) {
    const S density = geometry->getMaterial()->getBulkMaterial()->getDensity();
    const Transform<S> X_BG = geometry->getLocalTransform();
    for (const auto& entry : geometry->getShapes()) {
      const S volume = entry.shape->getVolume();
      if (!(volume > S(0))) continue;
      const S m = density * volume;
      const Transform<S> X_BS = X_BG * entry.transform;
      const Vec3<S> c_S = entry.shape->getCenterOfVolume();
      const Mat3<S> R = X_BS.linear();
      const Mat3<S> aboutCenter = entry.shape->calculateInertia(m).matrix() - shift(m, c_S);
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
