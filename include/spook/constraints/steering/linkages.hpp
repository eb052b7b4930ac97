#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>

#include <Eigen/Core>

#include <spook/constraints/steering/steering_parameters.hpp>
#include <spook/core/error.hpp>

// Closed-form kinematics of the steering linkages of seed 001 §12.13 in the
// plane of SteeringParameters: left pivot K_L = (−½, 0), right pivot
// K_R = (½, 0), lengths in wheel tracks, wheel angles δ counterclockwise
// about z (positive: turning left), all in double.

namespace spook::detail {

using Vec2d = Eigen::Vector2d;

/// Steering angles of the two wheels (rad).
struct LinkageAngles {
  double left = 0.0;
  double right = 0.0;
};

/// A knuckle arm of length `length` on the pivot, at `restAngle` from +x
/// when driving straight; it turns with its wheel.
struct KnuckleArm {
  Vec2d pivot;
  double restAngle = 0.0;
  double length = 0.0;

  [[nodiscard]] Vec2d end(double steer) const {
    return pivot + length * Vec2d(std::cos(restAngle + steer), std::sin(restAngle + steer));
  }
  [[nodiscard]] double steerOf(const Vec2d& end) const {
    const Vec2d d = end - pivot;
    return std::remainder(std::atan2(d.y(), d.x()) - restAngle, 2.0 * std::numbers::pi);
  }
};

inline double cross2(const Vec2d& a, const Vec2d& b) { return a.x() * b.y() - a.y() * b.x(); }

/// A rod of fixed length from a moving joint P to the end of a knuckle arm:
/// the arm end is where the circle about the pivot (radius l) meets the
/// circle about P (radius L), on the side of the ray pivot → P where it was
/// when driving straight (the assembly branch). No intersection: the linkage
/// cannot reach P.
struct TieRod {
  KnuckleArm arm;
  double length = 0.0;
  double branch = 1.0;  // +1: the arm end left of pivot → P, −1: right

  /// The rod between P0 and the arm's straight-ahead end; `sine` is the sine
  /// of the transmission angle there, zero at a dead centre.
  static TieRod assemble(const KnuckleArm& arm, const Vec2d& P0, double& sine) {
    TieRod rod;
    rod.arm = arm;
    const Vec2d B0 = arm.end(0.0);
    rod.length = (B0 - P0).norm();
    const double c = cross2(P0 - arm.pivot, B0 - arm.pivot);
    rod.branch = c >= 0.0 ? 1.0 : -1.0;
    sine = rod.length > 0.0 ? std::abs(cross2((P0 - B0) / rod.length, (B0 - arm.pivot) / arm.length)) : 0.0;
    return rod;
  }

  [[nodiscard]] std::optional<double> steerFor(const Vec2d& P) const {
    const Vec2d d = P - arm.pivot;
    const double distance = d.norm();
    if (!(distance > 0.0)) return std::nullopt;
    const double along = (arm.length * arm.length - length * length + distance * distance) / (2.0 * distance);
    const double across2 = arm.length * arm.length - along * along;
    if (!(across2 >= 0.0)) return std::nullopt;
    const Vec2d u = d / distance, n(-u.y(), u.x());
    return arm.steerOf(arm.pivot + along * u + branch * std::sqrt(across2) * n);
  }
};

inline KnuckleArm leftKnuckle(const SteeringParameters& p) {
  return {Vec2d(-0.5, 0.0), std::numbers::pi - p.phi0, p.l};
}
inline KnuckleArm rightKnuckle(const SteeringParameters& p) { return {Vec2d(0.5, 0.0), p.phi0, p.l}; }

/// Smallest transmission-angle sine accepted when driving straight.
inline constexpr double kDeadCentreSine = 1e-6;

template <class T>
[[nodiscard]] Error linkageError(const char* kind, const std::string& what, const T& value) {
  return makeError(kind, "", what, value);
}

inline void checkCommon(const char* kind, const SteeringParameters& p) {
  if (!std::isfinite(p.phi0)) throw linkageError(kind, "phi0 must be finite (rad)", p.phi0);
  if (!(std::isfinite(p.gear) && p.gear > 0.0)) throw linkageError(kind, "gear must be finite and > 0", p.gear);
}
inline void checkKnuckle(const char* kind, const SteeringParameters& p) {
  if (!(std::isfinite(p.l) && p.l > 0.0 && p.l < 0.5))
    throw linkageError(kind, "knuckle arm length l must be in (0, 0.5) wheel tracks", p.l);
}

/// Ackermann (seed 001 §12.13): a symmetric trapezoid four-bar. The steering
/// arm turns the knuckle on `side` by gear × input; the tie rod, of its
/// straight-ahead length L₀ = 1 + 2 l cos φ₀, carries the other knuckle,
/// whose angle closes the loop |B − A| = L₀ in closed form.
class AckermannLinkage {
 public:
  static constexpr const char* kName = "Ackermann";
  [[nodiscard]] static SteeringParameters defaults() { return SteeringParameters::ackermann(); }

  explicit AckermannLinkage(const SteeringParameters& p) {
    checkCommon(kName, p);
    checkKnuckle(kName, p);
    if (p.side != 0 && p.side != 1) throw linkageError(kName, "side must be 0 (left) or 1 (right)", p.side);
    driven_ = p.side == 0 ? leftKnuckle(p) : rightKnuckle(p);
    double sine = 0.0;
    follower_ = TieRod::assemble(p.side == 0 ? rightKnuckle(p) : leftKnuckle(p), driven_.end(0.0), sine);
    if (!(follower_.length > 0.0 && sine > kDeadCentreSine))
      throw linkageError(kName, "phi0 and l put the tie rod at a dead centre when driving straight (rad)", p.phi0);
    gear_ = p.gear;
    side_ = p.side;
  }

  /// Inputs beyond half a turn of the driven knuckle are not considered.
  [[nodiscard]] double inputCap() const { return std::numbers::pi / gear_; }

  [[nodiscard]] std::optional<LinkageAngles> solve(double input) const {
    const double driven = gear_ * input;
    const auto follower = follower_.steerFor(driven_.end(driven));
    if (!follower) return std::nullopt;
    return side_ == 0 ? LinkageAngles{driven, *follower} : LinkageAngles{*follower, driven};
  }

 private:
  KnuckleArm driven_;
  TieRod follower_;
  double gear_ = 1.0;
  int side_ = 0;
};

/// Two tie rods from inner joints that move along x to the knuckle arms,
/// at α to the x axis when driving straight. The input is scaled so that the
/// wheels turn by gear × input at small angles: the inner joints move by
/// s = gear·input/k₀, where k₀ = dδ/ds = cos α / (l sin(α − φ₀)) at s = 0
/// (from the rod length's derivative, e·dB = e·dP).
class TieRodPair {
 public:
  TieRodPair(const char* kind, const SteeringParameters& p, double innerSpacing) {
    checkCommon(kind, p);
    checkKnuckle(kind, p);
    if (!(std::isfinite(p.alpha) && std::abs(p.alpha) < 0.5 * std::numbers::pi))
      throw linkageError(kind, "tie rod angle alpha must be in (-pi/2, pi/2) rad", p.alpha);
    const KnuckleArm left = leftKnuckle(p), right = rightKnuckle(p);
    const Vec2d B0 = right.end(0.0);
    const double reach = B0.x() - 0.5 * innerSpacing;
    if (!(reach > 0.0))
      throw linkageError(kind, "the knuckle arms end inside the tie rods' inner joints (x of the right arm end, W_t)",
                         B0.x());
    innerY_ = B0.y() - reach * std::tan(p.alpha);
    halfSpacing_ = 0.5 * innerSpacing;
    double sineLeft = 0.0, sineRight = 0.0;
    left_ = TieRod::assemble(left, Vec2d(-halfSpacing_, innerY_), sineLeft);
    right_ = TieRod::assemble(right, Vec2d(halfSpacing_, innerY_), sineRight);
    if (!(std::min(sineLeft, sineRight) > kDeadCentreSine))
      throw linkageError(kind, "phi0 and alpha put the tie rods at a dead centre when driving straight (rad)", p.phi0);
    gainPerInput_ = p.gear * p.l * std::sin(p.alpha - p.phi0) / std::cos(p.alpha);
    inputCap_ = std::numbers::pi / p.gear;
  }

  /// Inputs beyond half a turn (of the wheels, at the small-angle gain) are not considered.
  [[nodiscard]] double inputCap() const { return inputCap_; }

  /// Displacement (W_t) of the inner joints for an input (rad).
  [[nodiscard]] double travel(double input) const { return gainPerInput_ * input; }
  /// Wheel angles with the inner joints at (∓spacing/2 + dx, innerY + dy).
  [[nodiscard]] std::optional<LinkageAngles> solveAt(double dx, double dy) const {
    const auto left = left_.steerFor(Vec2d(-halfSpacing_ + dx, innerY_ + dy));
    const auto right = right_.steerFor(Vec2d(halfSpacing_ + dx, innerY_ + dy));
    if (!left || !right) return std::nullopt;
    return LinkageAngles{*left, *right};
  }

 private:
  TieRod left_, right_;
  double innerY_ = 0.0, halfSpacing_ = 0.0, gainPerInput_ = 0.0, inputCap_ = 0.0;
};

/// Bell crank, or central lever (seed 001 §12.13): both tie rods meet at one
/// joint carried by a lever of length lc pivoted lc behind it on the
/// centre line; the lever turns by ψ = s/lc, moving the joint on its arc,
/// P = O + lc (sin ψ, cos ψ).
class BellCrankLinkage {
 public:
  static constexpr const char* kName = "BellCrank";
  [[nodiscard]] static SteeringParameters defaults() { return SteeringParameters::bellCrank(); }

  explicit BellCrankLinkage(const SteeringParameters& p) : rods_(kName, p, 0.0), lever_(checkedLever(p.lc)) {}

  [[nodiscard]] double inputCap() const { return rods_.inputCap(); }

  [[nodiscard]] std::optional<LinkageAngles> solve(double input) const {
    const double psi = rods_.travel(input) / lever_;
    return rods_.solveAt(lever_ * std::sin(psi), lever_ * (std::cos(psi) - 1.0));
  }

 private:
  static double checkedLever(double lc) {
    if (!(std::isfinite(lc) && lc > 0.0)) throw linkageError(kName, "lever length lc must be finite and > 0 (W_t)", lc);
    return lc;
  }
  TieRodPair rods_;
  double lever_;
};

/// Rack and pinion (seed 001 §12.13): the tie rods' inner joints sit at the
/// ends of a rack of length lr that the pinion slides along x.
class RackPinionLinkage {
 public:
  static constexpr const char* kName = "RackPinion";
  [[nodiscard]] static SteeringParameters defaults() { return SteeringParameters::rackPinion(); }

  explicit RackPinionLinkage(const SteeringParameters& p) : rods_(kName, p, checkedRack(p.lr)) {}

  [[nodiscard]] double inputCap() const { return rods_.inputCap(); }
  [[nodiscard]] std::optional<LinkageAngles> solve(double input) const {
    return rods_.solveAt(rods_.travel(input), 0.0);
  }

 private:
  static double checkedRack(double lr) {
    if (!(std::isfinite(lr) && lr >= 0.0 && lr < 1.0))
      throw linkageError(kName, "rack length lr must be in [0, 1) wheel tracks", lr);
    return lr;
  }
  TieRodPair rods_;
};

/// Davis (seed 001 §12.13): a bar ahead of the axle slides along x; each
/// knuckle arm, at β = φ₀ − π/2 from the y axis (inward for β > 0), slides
/// through a pivoted block on the bar. With the bar at distance b and
/// moved by −u b, t = tan β:
///   tan(β + δ_R) = t + u,   tan(β − δ_L) = t − u
/// ⇒ tan δ_R = u/(1 + t² + t u),  tan δ_L = u/(1 + t² − t u),
/// so cot δ_R − cot δ_L = 2t for every u: Ackermann's rule exactly, for the
/// wheel base W_b = W_t/(2 tan β). The input is the mean-cotangent (bicycle)
/// angle: u = (1 + t²) tan(gear·input) gives (cot δ_L + cot δ_R)/2 =
/// cot(gear·input).
class DavisLinkage {
 public:
  static constexpr const char* kName = "Davis";
  [[nodiscard]] static SteeringParameters defaults() { return SteeringParameters::davis(); }

  explicit DavisLinkage(const SteeringParameters& p) {
    checkCommon(kName, p);
    if (!(p.phi0 > 0.0 && p.phi0 < std::numbers::pi))
      throw linkageError(kName, "phi0 must be in (0, pi) rad: the arms reach forward to the bar", p.phi0);
    t_ = std::tan(p.phi0 - 0.5 * std::numbers::pi);
    gear_ = p.gear;
    inputCap_ = 0.5 * std::numbers::pi / p.gear;
  }

  /// The wheel base (W_t) for which the mechanism is exact.
  [[nodiscard]] double exactWheelBase() const { return 0.5 / t_; }
  [[nodiscard]] double inputCap() const { return inputCap_; }

  [[nodiscard]] std::optional<LinkageAngles> solve(double input) const {
    if (!(std::abs(input) < inputCap_)) return std::nullopt;
    const double u = (1.0 + t_ * t_) * std::tan(gear_ * input);
    return LinkageAngles{std::atan2(u, 1.0 + t_ * t_ - t_ * u), std::atan2(u, 1.0 + t_ * t_ + t_ * u)};
  }

 private:
  double t_ = 0.0, gear_ = 1.0, inputCap_ = 0.0;
};

/// The largest input x such that on [−x, x] the linkage closes, both wheel
/// angles stay within ±π/2 and rise strictly with the input (past a dead
/// centre a wheel would turn back). Scanned in steps of cap/720 from
/// straight ahead in both directions, the first failure refined by bisection.
template <class Linkage>
[[nodiscard]] double maximumLinkageInput(const Linkage& linkage) {
  const double cap = linkage.inputCap();
  constexpr double kProbe = 1e-7;
  const auto admissible = [&](double x, double sign) {
    const auto here = linkage.solve(sign * x), before = linkage.solve(sign * (x - kProbe));
    if (!here || !before) return false;
    const double halfTurn = 0.5 * std::numbers::pi;
    if (!(std::abs(here->left) < halfTurn && std::abs(here->right) < halfTurn)) return false;
    return sign * (here->left - before->left) > 0.0 && sign * (here->right - before->right) > 0.0;
  };
  double maximum = cap;
  const double step = cap / 720.0;
  for (const double sign : {1.0, -1.0}) {
    double good = 0.0, bad = cap;
    for (double x = step; x < cap; x += step) {
      if (!admissible(x, sign)) {
        bad = x;
        break;
      }
      good = x;
    }
    for (int i = 0; i < 60 && bad < cap; ++i) {
      const double middle = 0.5 * (good + bad);
      (admissible(middle, sign) ? good : bad) = middle;
    }
    maximum = std::min(maximum, good);
  }
  return maximum;
}

}  // namespace spook::detail
