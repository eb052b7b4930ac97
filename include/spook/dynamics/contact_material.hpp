#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <string_view>
#include <utility>

#include <spook/collide/contact_reduction.hpp>
#include <spook/core/error.hpp>
#include <spook/core/implementation.hpp>
#include <spook/core/ref_ptr.hpp>
#include <spook/core/referenced.hpp>
#include <spook/core/scalar.hpp>
#include <spook/dynamics/friction_model.hpp>
#include <spook/dynamics/material.hpp>

namespace spook {

namespace detail {

/// "steel/rubber", the name errors give a pair of materials.
template <Scalar S>
[[nodiscard]] std::string materialPairName(const MaterialT<S>* m1, const MaterialT<S>* m2) {
  const std::string_view a = m1 ? std::string_view(m1->getName()) : std::string_view("nullptr");
  const std::string_view b = m2 ? std::string_view(m2->getName()) : std::string_view("nullptr");
  if (a.empty() && b.empty()) return {};
  std::string name;
  name.reserve(a.size() + b.size() + 1);
  name.append(a).append("/").append(b);
  return name;
}

}  // namespace detail

/// What the solver uses for the contacts between two materials (plain
/// values). Default-constructed it holds the per-pair defaults of DESIGN.md.
template <Scalar S>
struct ContactParametersT {
  S friction[2] = {S(0.41667), S(0.41667)};          ///< coefficient along the primary (0) and secondary (1) tangent
  S surfaceViscosity[2] = {S(5e-9), S(5e-9)};        ///< compliance of the friction rows (m/(N·s)) per direction
  S restitution = S(0);                              ///< [0, 1]
  S youngsModulus = S(4e8);                          ///< Pa, the contact stiffness: the normal row's compliance is 1/E
  S damping = S(0.075);                              ///< SPOOK damping of the normal row (s)
  S adhesiveForce = S(0);                            ///< N, >= 0: the normal row may pull with up to this force
  S adhesiveOverlap = S(0);                          ///< m, >= 0: the contact is held at this overlap
  const FrictionModelT<S>* frictionModel = nullptr;  ///< nullptr: the default (iterative projected cone, SPLIT)
  ContactReductionMode reductionMode = ContactReductionMode::REDUCE_GEOMETRY;
  int binResolution = 2;          ///< contact reduction bins per dimension, 1..3
  bool explicitMaterial = false;  ///< true when it came from a ContactMaterial
};

/// The explicit contact parameters of a pair of materials (seed 000,
/// "Explicit agx::ContactMaterial"): overrides the implicit combination of
/// the two materials. Holds both materials alive.
template <Scalar S>
class ContactMaterialT : public Referenced {
 public:
  enum FrictionDirection { PRIMARY_DIRECTION, SECONDARY_DIRECTION, BOTH_PRIMARY_AND_SECONDARY };

  /// Starts from the implicit combination of the two materials, so creating
  /// one changes nothing until a value is set.
  ContactMaterialT(ref_ptr<MaterialT<S>> m1, ref_ptr<MaterialT<S>> m2)
      : material1_(checked(m1, m2)), material2_(std::move(m2)), params_(implicitParameters(*material1_, *material2_)) {
    params_.explicitMaterial = true;
  }

  [[nodiscard]] MaterialT<S>* getMaterial1() const { return material1_.get(); }
  [[nodiscard]] MaterialT<S>* getMaterial2() const { return material2_.get(); }

  /// Friction coefficient (dimensionless), finite and >= 0, along one or both
  /// tangent directions.
  void setFrictionCoefficient(S coefficient, FrictionDirection direction = BOTH_PRIMARY_AND_SECONDARY);
  [[nodiscard]] S getFrictionCoefficient(FrictionDirection direction = PRIMARY_DIRECTION) const;

  /// Surface viscosity, the compliance of the friction rows (m/(N·s)),
  /// finite and >= 0, along one or both tangent directions.
  void setSurfaceViscosity(S viscosity, FrictionDirection direction = BOTH_PRIMARY_AND_SECONDARY);
  [[nodiscard]] S getSurfaceViscosity(FrictionDirection direction = PRIMARY_DIRECTION) const;

  /// Restitution in [0, 1]: 1 keeps the normal speed in an impact, 0 stops it.
  void setRestitution(S restitution);
  [[nodiscard]] S getRestitution() const { return params_.restitution; }

  /// Young's modulus (Pa), finite and > 0: the contact stiffness.
  void setYoungsModulus(S modulus);
  [[nodiscard]] S getYoungsModulus() const { return params_.youngsModulus; }

  /// SPOOK damping of the normal row (s), finite and >= 0.
  void setDamping(S damping);
  [[nodiscard]] S getDamping() const { return params_.damping; }

  /// Adhesion: the normal row may pull with up to `force` (N, >= 0) and holds
  /// the contact at `overlap` (m, >= 0).
  void setAdhesion(S force, S overlap);
  [[nodiscard]] S getAdhesiveForce() const { return params_.adhesiveForce; }
  [[nodiscard]] S getAdhesiveOverlap() const { return params_.adhesiveOverlap; }

  /// The friction model of the pair; nullptr restores the default
  /// (iterative projected cone, solved SPLIT).
  void setFrictionModel(ref_ptr<FrictionModelT<S>> model);
  [[nodiscard]] FrictionModelT<S>* getFrictionModel() const { return frictionModel_.get(); }

  void setContactReductionMode(ContactReductionMode mode);
  [[nodiscard]] ContactReductionMode getContactReductionMode() const { return params_.reductionMode; }

  /// Bins per dimension of contact reduction: 1, 2 (default) or 3.
  void setContactReductionBinResolution(int resolution);
  [[nodiscard]] int getContactReductionBinResolution() const { return params_.binResolution; }

  /// The values the solver uses for this pair (explicitMaterial = true).
  [[nodiscard]] const ContactParametersT<S>& parameters() const { return params_; }

  /// The implicit combination of two materials (seed 000, "Materials"):
  /// friction √(r₁r₂) of the roughnesses, restitution √((1−v₁)(1−v₂)) of
  /// the bulk viscosities, Young's modulus Y₁Y₂/(Y₁+Y₂) (two springs in
  /// series), damping the larger bulk damping, surface viscosity the sum of
  /// the two (compliances in series); no adhesion, the default friction
  /// model, REDUCE_GEOMETRY at resolution 2, explicitMaterial = false.
  [[nodiscard]] static ContactParametersT<S> implicitParameters(const MaterialT<S>& a, const MaterialT<S>& b);

 protected:
  ~ContactMaterialT() override = default;

 private:
  static ref_ptr<MaterialT<S>> checked(ref_ptr<MaterialT<S>>& m1, const ref_ptr<MaterialT<S>>& m2);
  template <class T>
  [[nodiscard]] Error error(const char* what, const T& value) const {
    return detail::makeError("ContactMaterial", detail::materialPairName<S>(material1_.get(), material2_.get()), what,
                             value);
  }
  void checkDirection(FrictionDirection direction) const;
  static void setPerDirection(S (&values)[2], S value, FrictionDirection direction);

  ref_ptr<MaterialT<S>> material1_;
  ref_ptr<MaterialT<S>> material2_;
  ref_ptr<FrictionModelT<S>> frictionModel_;
  ContactParametersT<S> params_;
};

template <Scalar S>
void ContactMaterialT<S>::setFrictionCoefficient(S coefficient, FrictionDirection direction) {
  checkDirection(direction);
  if (!(std::isfinite(coefficient) && coefficient >= S(0)))
    throw error("friction coefficient must be finite and >= 0", coefficient);
  setPerDirection(params_.friction, coefficient, direction);
}

template <Scalar S>
S ContactMaterialT<S>::getFrictionCoefficient(FrictionDirection direction) const {
  return params_.friction[direction == SECONDARY_DIRECTION ? 1 : 0];
}

template <Scalar S>
void ContactMaterialT<S>::setSurfaceViscosity(S viscosity, FrictionDirection direction) {
  checkDirection(direction);
  if (!(std::isfinite(viscosity) && viscosity >= S(0)))
    throw error("surface viscosity must be finite and >= 0 m/(N*s)", viscosity);
  setPerDirection(params_.surfaceViscosity, viscosity, direction);
}

template <Scalar S>
S ContactMaterialT<S>::getSurfaceViscosity(FrictionDirection direction) const {
  return params_.surfaceViscosity[direction == SECONDARY_DIRECTION ? 1 : 0];
}

template <Scalar S>
void ContactMaterialT<S>::setRestitution(S restitution) {
  if (!(restitution >= S(0) && restitution <= S(1))) throw error("restitution must be in [0, 1]", restitution);
  params_.restitution = restitution;
}

template <Scalar S>
void ContactMaterialT<S>::setYoungsModulus(S modulus) {
  if (!(std::isfinite(modulus) && modulus > S(0))) throw error("Young's modulus must be finite and > 0 Pa", modulus);
  params_.youngsModulus = modulus;
}

template <Scalar S>
void ContactMaterialT<S>::setDamping(S damping) {
  if (!(std::isfinite(damping) && damping >= S(0))) throw error("damping must be finite and >= 0 s", damping);
  params_.damping = damping;
}

template <Scalar S>
void ContactMaterialT<S>::setAdhesion(S force, S overlap) {
  if (!(std::isfinite(force) && force >= S(0))) throw error("adhesive force must be finite and >= 0 N", force);
  if (!(std::isfinite(overlap) && overlap >= S(0))) throw error("adhesive overlap must be finite and >= 0 m", overlap);
  params_.adhesiveForce = force;
  params_.adhesiveOverlap = overlap;
}

template <Scalar S>
void ContactMaterialT<S>::setFrictionModel(ref_ptr<FrictionModelT<S>> model) {
  frictionModel_ = std::move(model);
  params_.frictionModel = frictionModel_.get();
}

template <Scalar S>
void ContactMaterialT<S>::setContactReductionMode(ContactReductionMode mode) {
  switch (mode) {
    case ContactReductionMode::REDUCE_NONE:
    case ContactReductionMode::REDUCE_GEOMETRY:
    case ContactReductionMode::REDUCE_ALL:
      params_.reductionMode = mode;
      return;
  }
  throw error("contact reduction mode must be REDUCE_NONE, REDUCE_GEOMETRY or REDUCE_ALL", static_cast<int>(mode));
}

template <Scalar S>
void ContactMaterialT<S>::setContactReductionBinResolution(int resolution) {
  if (resolution < 1 || resolution > 3) throw error("bin resolution must be 1, 2 or 3", resolution);
  params_.binResolution = resolution;
}

template <Scalar S>
auto ContactMaterialT<S>::implicitParameters(const MaterialT<S>& a, const MaterialT<S>& b) -> ContactParametersT<S> {
  const auto* bulkA = a.getBulkMaterial();
  const auto* bulkB = b.getBulkMaterial();
  const auto* surfaceA = a.getSurfaceMaterial();
  const auto* surfaceB = b.getSurfaceMaterial();
  const S friction = std::sqrt(surfaceA->getRoughness() * surfaceB->getRoughness());
  const S surfaceViscosity = surfaceA->getViscosity() + surfaceB->getViscosity();
  const S youngsA = bulkA->getYoungsModulus(), youngsB = bulkB->getYoungsModulus();
  ContactParametersT<S> p;
  p.friction[0] = p.friction[1] = friction;
  p.surfaceViscosity[0] = p.surfaceViscosity[1] = surfaceViscosity;
  p.restitution = std::sqrt((S(1) - bulkA->getViscosity()) * (S(1) - bulkB->getViscosity()));
  p.youngsModulus = youngsA * youngsB / (youngsA + youngsB);
  p.damping = std::max(bulkA->getDamping(), bulkB->getDamping());
  p.adhesiveForce = S(0);
  p.adhesiveOverlap = S(0);
  p.frictionModel = nullptr;
  p.reductionMode = ContactReductionMode::REDUCE_GEOMETRY;
  p.binResolution = 2;
  p.explicitMaterial = false;
  return p;
}

template <Scalar S>
auto ContactMaterialT<S>::checked(ref_ptr<MaterialT<S>>& m1, const ref_ptr<MaterialT<S>>& m2) -> ref_ptr<MaterialT<S>> {
  if (!m1 || !m2)
    throw detail::makeError("ContactMaterial", detail::materialPairName<S>(m1.get(), m2.get()),
                            "both materials must be non-null", "nullptr");
  return std::move(m1);
}

template <Scalar S>
void ContactMaterialT<S>::checkDirection(FrictionDirection direction) const {
  if (direction != PRIMARY_DIRECTION && direction != SECONDARY_DIRECTION && direction != BOTH_PRIMARY_AND_SECONDARY)
    throw error("friction direction must be PRIMARY_DIRECTION, SECONDARY_DIRECTION or BOTH_PRIMARY_AND_SECONDARY",
                static_cast<int>(direction));
}

template <Scalar S>
void ContactMaterialT<S>::setPerDirection(S (&values)[2], S value, FrictionDirection direction) {
  if (direction != SECONDARY_DIRECTION) values[0] = value;
  if (direction != PRIMARY_DIRECTION) values[1] = value;
}

SPOOK_COMPILED_ONCE(class, ContactMaterialT)

using ContactParameters = ContactParametersT<double>;
using ContactMaterial = ContactMaterialT<double>;
using ContactMaterialRef = ref_ptr<ContactMaterial>;
namespace f32 {
using ContactParameters = ContactParametersT<float>;
using ContactMaterial = ContactMaterialT<float>;
using ContactMaterialRef = ref_ptr<ContactMaterial>;
}  // namespace f32

}  // namespace spook
