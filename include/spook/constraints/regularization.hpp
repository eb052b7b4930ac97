#pragma once

#include <cmath>
#include <string>

#include <spook/core/error.hpp>
#include <spook/core/implementation.hpp>
#include <spook/core/scalar.hpp>

namespace spook {

/// Compliance and damping of one degree of freedom of a constraint (PHYSICS.md
/// §1.1): compliance ε is the inverse stiffness (m/N, or rad/(N·m) for a
/// rotational DOF); damping τ is SPOOK's relaxation time (s). Defaults as
/// AGX: ε = 1e-8, τ = 2/60 s. For a velocity row (motor) ε acts as a
/// viscosity: the row gives way by ε·force in speed. The stepper uses at
/// least τ = h/10: at τ = 0 SPOOK's rigid rows oscillate with growing
/// amplitude (islands.hpp).
template <Scalar S>
class RegularizationParametersT {
 public:
  static constexpr S kDefaultCompliance = S(1e-8);
  static constexpr S kDefaultDamping = S(2) / S(60);

  RegularizationParametersT() = default;
  RegularizationParametersT(S compliance, S damping);

  [[nodiscard]] S getCompliance() const { return compliance_; }
  void setCompliance(S compliance);
  [[nodiscard]] S getDamping() const { return damping_; }
  void setDamping(S damping);

 private:
  S compliance_ = kDefaultCompliance;
  S damping_ = kDefaultDamping;
};

template <Scalar S>
RegularizationParametersT<S>::RegularizationParametersT(S compliance, S damping) {
  setCompliance(compliance);
  setDamping(damping);
}

template <Scalar S>
void RegularizationParametersT<S>::setCompliance(S compliance) {
  if (!(std::isfinite(compliance) && compliance >= S(0)))
    throw detail::makeError("RegularizationParameters", "", "compliance must be finite and >= 0", compliance);
  compliance_ = compliance;
}

template <Scalar S>
void RegularizationParametersT<S>::setDamping(S damping) {
  if (!(std::isfinite(damping) && damping >= S(0)))
    throw detail::makeError("RegularizationParameters", "", "damping must be finite and >= 0 s", damping);
  damping_ = damping;
}

SPOOK_COMPILED_ONCE(class, RegularizationParametersT)

/// compliance = 1/k (k in N/m or N·m/rad).
template <Scalar S>
[[nodiscard]] S convertSpringConstantToCompliance(S springConstant) {
  if (!(std::isfinite(springConstant) && springConstant > S(0)))
    throw detail::makeError("convertSpringConstantToCompliance", "", "spring constant must be finite and > 0",
                            springConstant);
  return S(1) / springConstant;
}

/// SPOOK damping τ = c/k: the viscous damping coefficient c (N·s/m or
/// N·m·s/rad) over the spring constant k (PHYSICS.md §1.6).
template <Scalar S>
[[nodiscard]] S convertDampingCoefficientToSpookDamping(S dampingCoefficient, S springConstant) {
  if (!(std::isfinite(springConstant) && springConstant > S(0)))
    throw detail::makeError("convertDampingCoefficientToSpookDamping", "", "spring constant must be finite and > 0",
                            springConstant);
  if (!(std::isfinite(dampingCoefficient) && dampingCoefficient >= S(0)))
    throw detail::makeError("convertDampingCoefficientToSpookDamping", "", "damping coefficient must be finite and >= 0",
                            dampingCoefficient);
  return dampingCoefficient / springConstant;
}

}  // namespace spook
