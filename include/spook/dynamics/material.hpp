#pragma once

#include <cmath>
#include <string>
#include <utility>

#include <spook/core/error.hpp>
#include <spook/core/implementation.hpp>
#include <spook/core/ref_ptr.hpp>
#include <spook/core/referenced.hpp>
#include <spook/core/scalar.hpp>

namespace spook {

namespace detail {
/// A material property checked on its way in: finite and > 0, or >= 0 when
/// `zeroAllowed`; else a spook::Error naming the material and the value.
template <class S>
S checkedMaterialValue(const std::string& material, const char* what, S value, bool zeroAllowed) {
  if (!(std::isfinite(value) && (value > S(0) || (zeroAllowed && value == S(0)))))
    throw makeError("Material", material, what, value);
  return value;
}
}  // namespace detail

/// What a geometry is made of. The bulk part gives the density that turns
/// shape volumes into body mass; the stiffness and surface parameters are
/// used by contacts (the contact-dynamics layer combines two materials into
/// a contact material). Changing a parameter does not recompute the mass of
/// bodies already built from it (as in AGX): call
/// RigidBody::updateMassProperties() for that.
template <Scalar S>
class MaterialT : public Referenced {
 public:
  /// Volume-related properties.
  class BulkMaterial {
   public:
    /// Density (kg/m³), finite and > 0; default 1000 (water).
    [[nodiscard]] S getDensity() const { return density_; }
    void setDensity(S density) { density_ = positive("density must be finite and > 0 kg/m^3", density); }
    /// Young's modulus (Pa), the contact stiffness; default 4e8.
    [[nodiscard]] S getYoungsModulus() const { return youngsModulus_; }
    void setYoungsModulus(S modulus) {
      youngsModulus_ = positive("Young's modulus must be finite and > 0 Pa", modulus);
    }
    /// Viscosity, 1 − restitution, in [0, 1]; default 1 (no bounce).
    [[nodiscard]] S getViscosity() const { return viscosity_; }
    void setViscosity(S viscosity) {
      if (!(viscosity >= S(0) && viscosity <= S(1))) throw error("viscosity must be in [0, 1]", viscosity);
      viscosity_ = viscosity;
    }
    /// SPOOK damping of contacts (s), finite and >= 0; default 0.075.
    [[nodiscard]] S getDamping() const { return damping_; }
    void setDamping(S damping) {
      damping_ = detail::checkedMaterialValue(*owner_, "damping must be finite and >= 0 s", damping, true);
    }

   private:
    friend class MaterialT;
    explicit BulkMaterial(const std::string* owner) : owner_(owner) {}
    template <class T>
    [[nodiscard]] Error error(const char* what, const T& value) const {
      return detail::makeError("Material", *owner_, what, value);
    }
    S positive(const char* what, S value) const { return detail::checkedMaterialValue(*owner_, what, value, false); }
    const std::string* owner_;
    S density_ = S(1000);
    S youngsModulus_ = S(4e8);
    S viscosity_ = S(1);
    S damping_ = S(0.075);
  };

  /// Surface-related properties.
  class SurfaceMaterial {
   public:
    /// Roughness, the friction coefficient of the material with itself (>= 0);
    /// default 0.41667.
    [[nodiscard]] S getRoughness() const { return roughness_; }
    void setRoughness(S roughness) {
      roughness_ = detail::checkedMaterialValue(*owner_, "roughness must be finite and >= 0", roughness, true);
    }
    /// Surface viscosity, the compliance of the friction rows (m/(N·s));
    /// default 5e-9.
    [[nodiscard]] S getViscosity() const { return viscosity_; }
    void setViscosity(S viscosity) {
      viscosity_ =
          detail::checkedMaterialValue(*owner_, "surface viscosity must be finite and >= 0", viscosity, true);
    }

   private:
    friend class MaterialT;
    explicit SurfaceMaterial(const std::string* owner) : owner_(owner) {}
    const std::string* owner_;
    S roughness_ = S(0.41667);
    S viscosity_ = S(5e-9);
  };

  /// Wire properties (wire/wire.hpp; PHYSICS.md §3.2): the stretch rows
  /// between consecutive nodes have compliance l/(E_stretch·A) and the bend
  /// rows over three nodes l/(E_bend·I), A = πr², I = πr⁴/4. Defaults as
  /// AGX's (6e10 Pa both, damping 0.05 s and 0.1 s). A bend modulus near 1
  /// behaves like a chain, 1e12 like a stiff pipe; 0 is a limp rope (no bend
  /// rows). The wire's mass per length is the bulk density times A.
  class WireMaterial {
   public:
    /// Young's modulus of the stretch rows (Pa), finite and > 0.
    [[nodiscard]] S getYoungsModulusStretch() const { return stretch_; }
    void setYoungsModulusStretch(S modulus) {
      stretch_ = checked("wire Young's modulus stretch must be finite and > 0 Pa", modulus, false);
    }
    /// Young's modulus of the bend rows (Pa), finite and >= 0.
    [[nodiscard]] S getYoungsModulusBend() const { return bend_; }
    void setYoungsModulusBend(S modulus) {
      bend_ = checked("wire Young's modulus bend must be finite and >= 0 Pa", modulus, true);
    }
    /// SPOOK damping of the stretch rows (s), finite and >= 0.
    [[nodiscard]] S getDampingStretch() const { return dampingStretch_; }
    void setDampingStretch(S damping) {
      dampingStretch_ = checked("wire stretch damping must be finite and >= 0 s", damping, true);
    }
    /// SPOOK damping of the bend rows (s), finite and >= 0.
    [[nodiscard]] S getDampingBend() const { return dampingBend_; }
    void setDampingBend(S damping) {
      dampingBend_ = checked("wire bend damping must be finite and >= 0 s", damping, true);
    }
    /// Friction coefficient along the wire where it slides over a geometry
    /// (wire/wire_node.hpp's ContactNode), finite and >= 0; default 0.41667
    /// (AGX's default friction).
    [[nodiscard]] S getFrictionCoefficient() const { return friction_; }
    void setFrictionCoefficient(S coefficient) {
      friction_ = checked("wire friction coefficient must be finite and >= 0", coefficient, true);
    }

   private:
    friend class MaterialT;
    explicit WireMaterial(const std::string* owner) : owner_(owner) {}
    S checked(const char* what, S value, bool zeroAllowed) const {
      return detail::checkedMaterialValue(*owner_, what, value, zeroAllowed);
    }
    const std::string* owner_;
    S stretch_ = S(6e10);
    S bend_ = S(6e10);
    S dampingStretch_ = S(0.05);
    S dampingBend_ = S(0.1);
    S friction_ = S(0.41667);
  };

  explicit MaterialT(std::string name = "") : name_(std::move(name)) {}
  MaterialT(const MaterialT&) = delete;
  MaterialT& operator=(const MaterialT&) = delete;

  [[nodiscard]] const std::string& getName() const { return name_; }
  [[nodiscard]] BulkMaterial* getBulkMaterial() { return &bulk_; }
  [[nodiscard]] const BulkMaterial* getBulkMaterial() const { return &bulk_; }
  [[nodiscard]] SurfaceMaterial* getSurfaceMaterial() { return &surface_; }
  [[nodiscard]] const SurfaceMaterial* getSurfaceMaterial() const { return &surface_; }
  [[nodiscard]] WireMaterial* getWireMaterial() { return &wire_; }
  [[nodiscard]] const WireMaterial* getWireMaterial() const { return &wire_; }

 protected:
  ~MaterialT() override = default;

 private:
  std::string name_;
  BulkMaterial bulk_{&name_};
  SurfaceMaterial surface_{&name_};
  WireMaterial wire_{&name_};
};

SPOOK_COMPILED_ONCE(class, MaterialT)

using Material = MaterialT<double>;
using MaterialRef = ref_ptr<Material>;
namespace f32 {
using Material = MaterialT<float>;
using MaterialRef = ref_ptr<Material>;
}  // namespace f32

}  // namespace spook
