#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <spook/collide/geometry.hpp>
#include <spook/core/error.hpp>
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

/// "spook::Geometry 'g': Box of bounding half extents (1e200, 1e200, 1e200) m,
/// volume inf m^3, density 1000 kg/m^3: <what>, got <value>".
template <Scalar S, class T>
[[nodiscard]] Error shapeMassError(const GeometryT<S>& geometry, const ShapeT<S>& shape, S density,
                                   const std::string& what, const T& value) {
  std::string out(shapeTypeName(shape.getType()));
  out += " of bounding half extents ";
  appendValue(out, Vec3T<S>(shape.getBoundingBox().halfExtents()));
  out += " m, volume ";
  appendScalar(out, shape.getVolume());
  out += " m^3, density ";
  appendScalar(out, density);
  out += " kg/m^3: ";
  out += what;
  return makeError("Geometry", geometry.getName(), out, value);
}

/// Each shape of volume V contributes m = ρV (ρ its geometry's material
/// density) at its center of volume; its tensor about its own origin is
/// moved to its center, turned into the model frame, then moved to the
/// common center (parallel-axis theorem, J(m, d) = m(|d|² 1 − d dᵀ)).
/// `edit` stands in for one geometry's shapes, material or local transform
/// as a change not yet made would leave them. Empty when no shape has
/// volume. Throws spook::Error, naming the geometry, its shape and its size,
/// when a shape's mass or inertia is not finite, or naming the body
/// (`bodyName`) when the total mass or its moment overflows (the caller
/// checks the total inertia); computes only, changes nothing.
template <Scalar S>
[[nodiscard]] std::optional<GeneratedMass<S>> massFromGeometries(const std::vector<ref_ptr<GeometryT<S>>>& geometries,
                                                                 std::string_view bodyName,
                                                                 const GeometryEdit<S>& edit = {}) {
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
    const bool edited = geometry.get() == edit.geometry;
    const MaterialT<S>* material = edited && edit.material ? edit.material : geometry->getMaterial();
    const S density = material->getBulkMaterial()->getDensity();
    const TransformT<S> X_BG =
        edited && edit.localTransform ? *edit.localTransform : geometry->getLocalTransform();
    for (const auto& entry : edited && edit.shapes ? *edit.shapes : geometry->getShapes()) {
      const ShapeT<S>& shape = *entry.shape;
      const S volume = shape.getVolume();
      if (!(volume > S(0))) continue;
      const S m = density * volume;
      if (!(std::isfinite(m) && m > S(0)))
        throw shapeMassError(*geometry, shape, density, "mass density * volume must be finite and > 0 kg", m);
      SPDMat3T<S> aboutOrigin;
      try {
        aboutOrigin = shape.calculateInertia(m);
      } catch (const Error& e) {
        throw shapeMassError(*geometry, shape, density, std::string("no valid inertia (") + e.what() + "); mass (kg)", m);
      }
      const TransformT<S> X_BS = X_BG * entry.transform;
      const Vec3T<S> c_S = shape.getCenterOfVolume();
      const Mat3T<S> R = X_BS.linear();
      const Mat3T<S> aboutCenter = aboutOrigin.matrix() - shift(m, c_S);
      parts.push_back({m, X_BS * c_S, R * aboutCenter * R.transpose()});
      if (!(parts.back().center.allFinite() && parts.back().inertia.allFinite()))
        throw shapeMassError(*geometry, shape, density,
                             "its inertia at its center in the body frame must be finite; center (m)",
                             parts.back().center);
      total.mass += m;
      moment += m * parts.back().center;
    }
  }
  if (parts.empty()) return std::nullopt;
  if (!(std::isfinite(total.mass) && moment.allFinite()))
    throw makeError("RigidBody", bodyName, "mass and its moment from the geometries must be finite (kg, kg·m)",
                    Eigen::Matrix<S, 4, 1>(total.mass, moment.x(), moment.y(), moment.z()));
  total.center = moment / total.mass;
  for (const Part& p : parts) total.inertia += p.inertia + shift(p.mass, p.center - total.center);
  total.inertia = S(0.5) * (total.inertia + total.inertia.transpose());
  return total;
}

}  // namespace spook::detail
