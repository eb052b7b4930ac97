#pragma once

#include <cmath>

#include <spook/constraints/secondary/secondary_constraint.hpp>

namespace spook {

/// Holds a free DOF at a position (m or rad, angles with winding) with its own
/// compliance, damping and force range (seed 001 §12.15.2): g = x − position.
template <Scalar S>
class Lock1DT : public SecondaryConstraintT<S> {
 public:
  Lock1DT() : SecondaryConstraintT<S>("Lock1D") {}

  [[nodiscard]] S getPosition() const { return position_; }
  void setPosition(S position);

  void addRows(detail::RowSink& sink, const detail::Coordinate& c);
  /// The same row for post-stabilization, when the lock's force is unbounded.
  void addProjectionRow(detail::RowSink& sink, const detail::Coordinate& c);

 protected:
  ~Lock1DT() override = default;

 private:
  S position_ = S(0);
};

template <Scalar S>
void Lock1DT<S>::setPosition(S position) {
  if (!std::isfinite(position)) throw detail::makeError("Lock1D", "", "position must be finite (m or rad)", position);
  position_ = position;
}

template <Scalar S>
void Lock1DT<S>::addRows(detail::RowSink& sink, const detail::Coordinate& c) {
  if (!this->enable_) return;
  detail::Row& row = this->addRow(sink, c);
  row.violation = c.value - double(position_);
}

template <Scalar S>
void Lock1DT<S>::addProjectionRow(detail::RowSink& sink, const detail::Coordinate& c) {
  if (!this->enable_ || std::isfinite(this->forceRange_.lower) || std::isfinite(this->forceRange_.upper)) return;
  detail::Row& row = sink.add(c.J1, c.J2, &this->impulse_);
  row.violation = c.value - double(position_);
  row.compliance = double(this->regularization_.getCompliance());
  row.damping = double(this->regularization_.getDamping());
}

SPOOK_COMPILED_ONCE(class, Lock1DT)

/// The seeds' spelling (AGX's agx::Lock1D): `spook::Lock1D* m = hinge->getLock1D();`.
using Lock1D = Lock1DT<double>;
namespace f32 {
using Lock1D = Lock1DT<float>;
}  // namespace f32

}  // namespace spook
