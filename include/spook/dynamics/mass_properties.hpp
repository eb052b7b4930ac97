#pragma once

#include <cmath>
#include <string>

#include <spook/core/error.hpp>
#include <spook/core/implementation.hpp>
#include <spook/core/math.hpp>

namespace spook {

/// Mass attributes of a rigid body, expressed in its center-of-mass frame:
/// mass (kg), inertia tensor (kg·m²) and added-mass coefficients. Owned by
/// its RigidBody (getMassProperties()); every setter validates first and
/// leaves the values unchanged when it throws.
template <Scalar S>
class MassPropertiesT {
 public:
  using Vec3 = spook::Vec3T<S>;
  using Mat3 = spook::Mat3T<S>;

  /// Which properties the body recomputes from its geometries (shape
  /// volumes times material density) when geometries, shapes or materials
  /// change. Setting a property by hand takes it out of the mask.
  enum AutoGenerate : unsigned {
    MASS = 1u << 0,
    CM_OFFSET = 1u << 1,
    INERTIA = 1u << 2,
    ALL = MASS | CM_OFFSET | INERTIA
  };
  [[nodiscard]] unsigned getAutoGenerateMask() const { return autoGenerate_; }
  void setAutoGenerateMask(unsigned mask);

  /// Mass in kg; must be finite and > 0 (a body of infinite mass is STATIC).
  /// Stops the mass from being generated from the geometries. An inertia
  /// generated from the geometries (shape volumes × density) is
  /// proportional to the mass and scales with it, so setting the mass
  /// before or after adding the geometries gives the same tensor; a tensor
  /// set by hand (setInertiaTensor) stays as set.
  [[nodiscard]] S getMass() const { return mass_; }
  void setMass(S mass);

  /// Inertia tensor about the center of mass, in the CM frame (kg·m²).
  [[nodiscard]] const Mat3& getInertiaTensor() const { return inertia_.matrix(); }
  /// Sets the tensor from a full 3×3 matrix, which must be finite, symmetric
  /// and positive definite, or from a 3-vector of principal moments along
  /// the CM frame axes, which must be finite and > 0. Stops the tensor from
  /// being generated from the geometries.
  template <class Derived>
  void setInertiaTensor(const Eigen::MatrixBase<Derived>& value) {
    if constexpr (Derived::ColsAtCompileTime == 1) {
      const Vec3 diagonal = value;
      if (!(diagonal.allFinite() && diagonal.minCoeff() > S(0)))
        throw error("inertia diagonal must be finite and > 0 kg·m²", diagonal);
      inertia_ = SPDMat3T<S>(diagonal);
      autoGenerate_ &= ~unsigned(INERTIA);
      inertiaGenerated_ = false;
    } else {
      const Mat3 inertia = value;
      if (const char* why = SPDMat3T<S>::defect(inertia))
        throw error(std::string("inertia tensor: ") + why, SPDMat3T<S>::flat(inertia));
      inertia_ = SPDMat3T<S>(inertia);
      autoGenerate_ &= ~unsigned(INERTIA);
      inertiaGenerated_ = false;
    }
  }
  void setInertiaTensor(const SPDMat3T<S>& inertia);

  /// Added-mass coefficients c along the CM frame axes (dimensionless, ≥ 0):
  /// the inertial mass along axis i is m(1 + cᵢ), e.g. water carried by a
  /// hull. They resist applied and constraint forces; gravity still
  /// accelerates the body at g (the gravitational mass is m).
  [[nodiscard]] const Vec3& getMassCoefficients() const { return massCoefficients_; }
  void setMassCoefficients(const Vec3& c);

  /// Inertial mass along the CM frame axes, m(1 + c) (kg).
  [[nodiscard]] Vec3 getEffectiveMass() const;

  explicit MassPropertiesT(const std::string* ownerName = nullptr) : ownerName_(ownerName) {}

 private:
  template <Scalar>
  friend class RigidBodyT;
  // Generated values, set by the body without touching the mask.
  void generate(S mass, const SPDMat3T<S>& inertia);

  template <class T>
  [[nodiscard]] Error error(const std::string& what, const T& value) const {
    return detail::makeError("RigidBody", ownerName_ ? *ownerName_ : std::string(), what, value);
  }

  const std::string* ownerName_;
  S mass_ = S(1);
  SPDMat3T<S> inertia_;
  Vec3 massCoefficients_ = Vec3::Zero();
  unsigned autoGenerate_ = ALL;
  bool inertiaGenerated_ = false;  // inertia_ came from the geometries (generate)
};

template <Scalar S>
void MassPropertiesT<S>::setAutoGenerateMask(unsigned mask) {
  if (mask & ~unsigned(ALL)) throw error("auto-generate mask has unknown bits", mask);
  autoGenerate_ = mask;
}

template <Scalar S>
void MassPropertiesT<S>::setMass(S mass) {
  if (!(std::isfinite(mass) && mass > S(0))) throw error("mass must be finite and > 0 kg", mass);
  if (inertiaGenerated_ && (autoGenerate_ & INERTIA)) {
    const Mat3 scaled = inertia_.matrix() * (mass / mass_);
    if (SPDMat3T<S>::defect(scaled))
      throw error("mass would scale the inertia generated from the geometries out of range (kg)", mass);
    inertia_ = SPDMat3T<S>(scaled);
  }
  mass_ = mass;
  autoGenerate_ &= ~unsigned(MASS);
}

template <Scalar S>
void MassPropertiesT<S>::setInertiaTensor(const SPDMat3T<S>& inertia) {
  inertia_ = inertia;
  autoGenerate_ &= ~unsigned(INERTIA);
  inertiaGenerated_ = false;
}

template <Scalar S>
void MassPropertiesT<S>::setMassCoefficients(const Vec3& c) {
  if (!(c.allFinite() && c.minCoeff() >= S(0))) throw error("mass coefficients must be finite and >= 0", c);
  massCoefficients_ = c;
}

template <Scalar S>
auto MassPropertiesT<S>::getEffectiveMass() const -> Vec3 {
  return mass_ * (Vec3::Ones() + massCoefficients_);
}

template <Scalar S>
void MassPropertiesT<S>::generate(S mass, const SPDMat3T<S>& inertia) {
  if (autoGenerate_ & MASS) mass_ = mass;
  if (autoGenerate_ & INERTIA) {
    inertia_ = inertia;
    inertiaGenerated_ = true;
  }
}

SPOOK_COMPILED_ONCE(class, MassPropertiesT)

using MassProperties = MassPropertiesT<double>;
namespace f32 {
using MassProperties = MassPropertiesT<float>;
}

}  // namespace spook
