#pragma once

#include <cmath>
#include <numbers>
#include <optional>

#include <spook/constraints/secondary/secondary_constraint.hpp>

namespace spook {

/// Couples the translation and the rotation of a CylindricalJoint (seed 001
/// §12.10.1): the body advances `lead` meters per revolution,
/// g = (x − x₀) − lead (θ − θ₀)/2π, from where it was when the screw engaged.
template <Scalar S>
class Screw1DT : public SecondaryConstraintT<S> {
 public:
  Screw1DT() : SecondaryConstraintT<S>("Screw1D") {}

  /// Meters of translation per revolution (may be negative: a left-hand thread).
  [[nodiscard]] S getLead() const { return lead_; }
  void setLead(S lead);

  void addRows(detail::RowSink& sink, const detail::Coordinate& translation, const detail::Coordinate& angle);

 protected:
  ~Screw1DT() override = default;

 private:
  struct Reference {
    double translation, angle;
  };
  S lead_ = S(0);
  std::optional<Reference> reference_;
};

template <Scalar S>
void Screw1DT<S>::setLead(S lead) {
  if (!std::isfinite(lead)) throw detail::makeError("Screw1D", "", "lead must be finite (m per revolution)", lead);
  lead_ = lead;
}

template <Scalar S>
void Screw1DT<S>::addRows(detail::RowSink& sink, const detail::Coordinate& translation,
                          const detail::Coordinate& angle) {
  if (!this->enable_) {
    reference_.reset();
    return;
  }
  if (!reference_) reference_ = Reference{translation.value, angle.value};
  const double ratio = double(lead_) / (2.0 * std::numbers::pi);
  detail::Coordinate c;
  c.J1 = translation.J1 - ratio * angle.J1;
  c.J2 = translation.J2 - ratio * angle.J2;
  detail::Row& row = this->addRow(sink, c);
  row.violation = (translation.value - reference_->translation) - ratio * (angle.value - reference_->angle);
}

SPOOK_COMPILED_ONCE(class, Screw1DT)

/// The seeds' spelling (AGX's agx::Screw1D): `spook::Screw1D* s = cylindrical->getScrew1D();`.
using Screw1D = Screw1DT<double>;
namespace f32 {
using Screw1D = Screw1DT<float>;
}  // namespace f32

}  // namespace spook
