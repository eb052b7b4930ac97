#pragma once

#include <cmath>
#include <limits>

#include <spook/constraints/secondary/secondary_constraint.hpp>

namespace spook {

/// Keeps a free DOF within [lower, upper] (m or rad) like a contact at each
/// end (seed 001 §12.15.3): a one-sided row, pushing only inward, added when
/// the DOF is beyond a limit or would reach it within two steps at its
/// current speed. Default range unbounded.
template <Scalar S>
class Range1DT : public SecondaryConstraintT<S> {
 public:
  Range1DT() : SecondaryConstraintT<S>("Range1D") {}

  [[nodiscard]] RangeT<S> getRange() const { return range_; }
  void setRange(S lower, S upper);
  void setRange(RangeT<S> range) { setRange(range.lower, range.upper); }

  void addRows(detail::RowSink& sink, const detail::Coordinate& c, double h);

 protected:
  ~Range1DT() override = default;

 private:
  RangeT<S> range_;
};

template <Scalar S>
void Range1DT<S>::setRange(S lower, S upper) {
  if (std::isnan(lower) || std::isnan(upper) || lower > upper)
    throw detail::makeError("Range1D", "", "range must have lower <= upper (m or rad)",
                            Eigen::Matrix<S, 2, 1>(lower, upper));
  range_ = {lower, upper};
}

template <Scalar S>
void Range1DT<S>::addRows(detail::RowSink& sink, const detail::Coordinate& c, double h) {
  if (!this->enable_) return;
  const double lower = double(range_.lower), upper = double(range_.upper);
  const double reach = 2.0 * h * std::abs(c.speed);
  const bool atLower = c.value - lower <= reach;
  const bool atUpper = upper - c.value <= reach;
  if (!atLower && !atUpper) return;
  detail::Row& row = this->addRow(sink, c);
  const bool lowerSide = atLower && (!atUpper || c.value - lower <= upper - c.value);
  row.violation = c.value - (lowerSide ? lower : upper);
  if (lower == upper) return;
  // One-sided: the force range keeps only its inward part.
  if (lowerSide) {
    row.lower = std::max(row.lower, 0.0);
    row.upper = std::max(row.upper, 0.0);
  } else {
    row.lower = std::min(row.lower, 0.0);
    row.upper = std::min(row.upper, 0.0);
  }
}

SPOOK_COMPILED_ONCE(class, Range1DT)

/// The seeds' spelling (AGX's agx::Range1D): `spook::Range1D* m = hinge->getRange1D();`.
using Range1D = Range1DT<double>;
namespace f32 {
using Range1D = Range1DT<float>;
}  // namespace f32

}  // namespace spook
