#pragma once

#include <cmath>
#include <string>
#include <utility>

#include <spook/core/error.hpp>
#include <spook/core/implementation.hpp>
#include <spook/core/math.hpp>
#include <spook/core/ref_ptr.hpp>
#include <spook/core/referenced.hpp>
#include <spook/core/scalar.hpp>
#include <spook/solver/row.hpp>

namespace spook {

/// How the friction of a contact is bounded and which solver handles its rows
/// (seed 000, "Friction Model"). Assigned to a ContactMaterial; contacts
/// without one use an IterativeProjectedConeFriction solved SPLIT.
template <Scalar S>
class FrictionModelT : public Referenced {
 public:
  enum Type {
    BOX,                      ///< fixed bounds ±μN with a given N, decoupled from the normal force
    SCALE_BOX,                ///< bounds ±μ·(current normal force), per tangent
    ITERATIVE_PROJECTED_CONE  ///< the tangent force projected onto the cone |f_t| <= μ f_n
  };

  FrictionModelT(const FrictionModelT&) = delete;
  FrictionModelT& operator=(const FrictionModelT&) = delete;

  [[nodiscard]] Type getType() const { return type_; }

  /// How the contact rows using this model are solved under the hybrid
  /// policy; default SolveType::SPLIT (normals direct, friction iterative).
  [[nodiscard]] SolveType getSolveType() const { return solveType_; }
  void setSolveType(SolveType solveType);

  /// Whether a primary friction direction is set; when not, the first
  /// tangent follows the sliding direction.
  [[nodiscard]] bool hasPrimaryDirection() const { return hasPrimaryDirection_; }
  /// The primary friction direction (world, unit); zero when unset.
  [[nodiscard]] const Vec3T<S>& getPrimaryDirection() const { return primaryDirection_; }
  /// Sets the primary friction direction (world, any finite nonzero length;
  /// stored normalized).
  void setPrimaryDirection(const Vec3T<S>& direction);
  void clearPrimaryDirection();

  [[nodiscard]] const std::string& getName() const { return name_; }

 protected:
  FrictionModelT(Type type, std::string name) : name_(std::move(name)), type_(type) {}
  ~FrictionModelT() override = default;

  template <class T>
  [[nodiscard]] Error error(const char* what, const T& value) const {
    return detail::makeError("FrictionModel", name_, what, value);
  }

 private:
  std::string name_;
  Type type_;
  SolveType solveType_ = SolveType::SPLIT;
  bool hasPrimaryDirection_ = false;
  Vec3T<S> primaryDirection_ = Vec3T<S>::Zero();
};

template <Scalar S>
void FrictionModelT<S>::setSolveType(SolveType solveType) {
  switch (solveType) {
    case SolveType::DIRECT:
    case SolveType::ITERATIVE:
    case SolveType::DIRECT_AND_ITERATIVE:
    case SolveType::SPLIT:
      solveType_ = solveType;
      return;
  }
  throw error("solve type must be DIRECT (1), ITERATIVE (2), DIRECT_AND_ITERATIVE (3) or SPLIT (4)",
              static_cast<int>(solveType));
}

template <Scalar S>
void FrictionModelT<S>::setPrimaryDirection(const Vec3T<S>& direction) {
  const S length = direction.norm();
  if (!(direction.allFinite() && std::isfinite(length) && length > S(0)))
    throw error("primary direction must be finite and nonzero", direction);
  primaryDirection_ = direction / length;
  hasPrimaryDirection_ = true;
}

template <Scalar S>
void FrictionModelT<S>::clearPrimaryDirection() {
  primaryDirection_ = Vec3T<S>::Zero();
  hasPrimaryDirection_ = false;
}

SPOOK_COMPILED_ONCE(class, FrictionModelT)

/// Fixed friction bounds ±μN per tangent, decoupled from the solved normal
/// force: linear, so the direct solver can take it whole.
template <Scalar S>
class BoxFrictionT final : public FrictionModelT<S> {
 public:
  explicit BoxFrictionT(std::string name = "") : FrictionModelT<S>(FrictionModelT<S>::BOX, std::move(name)) {}

  /// The normal force N used for the bounds (N), finite and >= 0. When unset
  /// the solver uses the last step's normal force of the contact (or the
  /// lighter body's weight on the first step).
  void setNormalForceMagnitude(S normalForce) {
    if (!(std::isfinite(normalForce) && normalForce >= S(0)))
      throw this->error("normal force magnitude must be finite and >= 0 N", normalForce);
    normalForce_ = normalForce;
    hasNormalForce_ = true;
  }
  [[nodiscard]] bool hasNormalForceMagnitude() const { return hasNormalForce_; }
  /// The normal force set for the bounds (N); 0 when unset.
  [[nodiscard]] S getNormalForceMagnitude() const { return normalForce_; }
  void clearNormalForceMagnitude() {
    normalForce_ = S(0);
    hasNormalForce_ = false;
  }

 protected:
  ~BoxFrictionT() override = default;

 private:
  S normalForce_ = S(0);
  bool hasNormalForce_ = false;
};

/// Friction bounds ±μ·(current normal force) per tangent: a box that scales
/// with the normal force as the iterations update it.
template <Scalar S>
class ScaleBoxFrictionT final : public FrictionModelT<S> {
 public:
  explicit ScaleBoxFrictionT(std::string name = "")
      : FrictionModelT<S>(FrictionModelT<S>::SCALE_BOX, std::move(name)) {}

 protected:
  ~ScaleBoxFrictionT() override = default;
};

/// The default: like ScaleBoxFriction, but the tangent force (both
/// directions together) is projected onto the cone |f_t| <= μ f_n, which
/// recovers isotropic Coulomb friction.
template <Scalar S>
class IterativeProjectedConeFrictionT final : public FrictionModelT<S> {
 public:
  explicit IterativeProjectedConeFrictionT(std::string name = "")
      : FrictionModelT<S>(FrictionModelT<S>::ITERATIVE_PROJECTED_CONE, std::move(name)) {}

 protected:
  ~IterativeProjectedConeFrictionT() override = default;
};

using FrictionModel = FrictionModelT<double>;
using BoxFriction = BoxFrictionT<double>;
using ScaleBoxFriction = ScaleBoxFrictionT<double>;
using IterativeProjectedConeFriction = IterativeProjectedConeFrictionT<double>;
using FrictionModelRef = ref_ptr<FrictionModel>;
namespace f32 {
using FrictionModel = FrictionModelT<float>;
using BoxFriction = BoxFrictionT<float>;
using ScaleBoxFriction = ScaleBoxFrictionT<float>;
using IterativeProjectedConeFriction = IterativeProjectedConeFrictionT<float>;
using FrictionModelRef = ref_ptr<FrictionModel>;
}  // namespace f32

}  // namespace spook
