#pragma once

#include <numbers>

namespace spook {

/// Geometry of a steering linkage (seed 001 §12.13.1, Table 12.6), in the
/// mechanism's plane: x runs from the left to the right steering pivot (the
/// wheel joints' frame 2 origins), z along the steering axes, y = z × x
/// (forward for a car with z up). Lengths are in units of the wheel track
/// W_t, the distance between the two pivots. Fields a mechanism does not use
/// are ignored.
struct SteeringParameters {
  /// Angle (rad) from +x to the right knuckle (kingpin) arm when driving
  /// straight; the left arm is its mirror image, at π − phi0.
  double phi0 = 0.0;
  /// Knuckle arm length (W_t): Ackermann, BellCrank, RackPinion.
  double l = 0.0;
  /// Angle (rad) from ±x to each tie rod when driving straight, positive
  /// when the inner end lies behind (−y) the outer one: BellCrank, RackPinion.
  double alpha = 0.0;
  /// Length of the central steering lever that carries the tie rods' inner
  /// joint (W_t): BellCrank.
  double lc = 0.0;
  /// Rack length between the tie rods' inner joints (W_t): RackPinion.
  double lr = 0.0;
  /// Steering gear: the linkage's input member turns gear × the steering
  /// angle (dimensionless, > 0).
  double gear = 1.0;
  /// The knuckle carrying the steering arm: 0 left, 1 right (Ackermann).
  int side = 0;

  /// Table 12.6 defaults.
  [[nodiscard]] static SteeringParameters ackermann() { return {degrees(-115.0), 0.16, 0.0, 0.0, 0.0, 1.0, 0}; }
  [[nodiscard]] static SteeringParameters bellCrank() { return {degrees(-108.0), 0.14, 0.0, 1.0, 0.0, 1.0, 0}; }
  [[nodiscard]] static SteeringParameters rackPinion() { return {degrees(-108.0), 0.14, 0.0, 1.0, 0.25, 1.0, 0}; }
  [[nodiscard]] static SteeringParameters davis() { return {degrees(104.0), 0.0, 0.0, 0.0, 0.0, 1.0, 0}; }

 private:
  static constexpr double degrees(double angle) { return angle * std::numbers::pi / 180.0; }
};

}  // namespace spook
