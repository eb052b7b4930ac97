#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include <spook/core/error.hpp>
#include <spook/core/math.hpp>
#include <spook/core/ref_ptr.hpp>
#include <spook/core/referenced.hpp>

namespace spook {

/// A C¹ curve through control points (seed 001 §12.11, AGX's CubicSpline):
/// a cubic Hermite segment between consecutive points P₀ … Pₙ₋₁, each point
/// with a tangent mᵢ given by the user or a cardinal tangent of tension c
/// (c = 0, the default, is Catmull–Rom):
///   mᵢ = (1 − c)(Pᵢ₊₁ − Pᵢ₋₁)/2,  m₀ = (1 − c)(P₁ − P₀),  mₙ₋₁ = (1 − c)(Pₙ₋₁ − Pₙ₋₂).
/// The curve parameter t runs from 0 at P₀ to n − 1 at Pₙ₋₁; segment i covers
/// [i, i + 1], and with u = t − i
///   P(t) = (2u³ − 3u² + 1)Pᵢ + (u³ − 2u² + u)mᵢ + (3u² − 2u³)Pᵢ₊₁ + (u³ − u²)mᵢ₊₁,
/// so a tangent is dP/dt (m per unit of parameter). Two points give the
/// straight segment traversed at constant speed. Positions are in the frame
/// the spline lives in (the world, or a body's model frame), in m.
///
/// add() keeps the curve ready for evaluation (tangents, arc lengths and
/// normals of the segments it changes are recomputed), so updateTangents()
/// is never required; it recomputes everything, as AGX's does.
template <Scalar S>
class CubicSplineT : public Referenced {
 public:
  using Vec3 = spook::Vec3T<S>;

  CubicSplineT() = default;

  /// Appends a control point (m) with a cardinal tangent.
  void add(const Vec3& point) { append(point, Vec3::Zero(), false); }
  /// Appends a control point (m) with its tangent dP/dt (m per unit of parameter).
  void add(const Vec3& point, const Vec3& tangent) {
    if (!tangent.allFinite() || !(tangent.norm() > S(0)))
      throw detail::makeError("CubicSpline", "", "tangent must be finite and non-zero (m)", tangent);
    append(point, tangent, true);
  }
  /// Recomputes the cardinal tangents, arc lengths and normals.
  void updateTangents() { rebuildFrom(0); }

  /// Tension c of the cardinal tangents, in [0, 1); 0 (Catmull–Rom) by default.
  [[nodiscard]] S getTension() const { return tension_; }
  void setTension(S tension) {
    if (!(std::isfinite(tension) && tension >= S(0) && tension < S(1)))
      throw detail::makeError("CubicSpline", "", "tension must be in [0, 1)", tension);
    tension_ = tension;
    rebuildFrom(0);
  }

  [[nodiscard]] std::size_t getNumPoints() const { return knots_.size(); }
  /// Control point `index` (m).
  [[nodiscard]] const Vec3& getPoint(std::size_t index) const { return knot(index).position; }
  /// Tangent dP/dt at control point `index` (m per unit of parameter).
  [[nodiscard]] const Vec3& getPointTangent(std::size_t index) const { return knot(index).tangent; }

  /// The largest parameter, n − 1 (0 with fewer than two points).
  [[nodiscard]] S getMaxParameter() const { return knots_.size() < 2 ? S(0) : S(knots_.size() - 1); }
  /// `t` clamped to [0, n − 1].
  [[nodiscard]] S clampParameter(S t) const { return std::clamp(t, S(0), getMaxParameter()); }

  /// P(t) (m); t is clamped to the curve.
  [[nodiscard]] Vec3 getPosition(S t) const { return evaluate<0>(t); }
  /// dP/dt (m per unit of parameter).
  [[nodiscard]] Vec3 getFirstDerivative(S t) const { return evaluate<1>(t); }
  /// d²P/dt² (m per unit of parameter squared).
  [[nodiscard]] Vec3 getSecondDerivative(S t) const { return evaluate<2>(t); }
  /// Unit tangent dP/ds at t.
  [[nodiscard]] Vec3 getUnitTangent(S t) const {
    requireCurve();
    const Segment s = segmentAt(t);
    return direction(s.index, s.u);
  }

  /// Length of the whole curve (m).
  [[nodiscard]] S getLength() const {
    requireCurve();
    return lengths_.back();
  }
  /// Arc length s(t) from P₀ to P(t) (m), by adaptive Gauss–Legendre quadrature of |dP/dt|.
  [[nodiscard]] S getLength(S t) const {
    requireCurve();
    const Segment s = segmentAt(t);
    return lengths_[s.index] + lengthWithin(s.index, S(0), s.u);
  }
  /// The parameter at arc length `length` (m), clamped to the curve: the inverse of getLength(t).
  [[nodiscard]] S getParameterAtLength(S length) const;

  /// The parameter of the point of the curve nearest to `point` (m) found
  /// from `guess` by Newton's method on the squared distance, each step at
  /// most half a segment and never increasing the distance, so the answer
  /// is the local minimum the guess leads to, not a nearer but distant part
  /// of the curve. When Newton does not settle, the curve within one
  /// segment of the guess is scanned and the search restarts at the best sample.
  [[nodiscard]] S findNearestParameter(const Vec3& point, S guess) const;
  /// The same over the whole curve (a scan of every segment, then Newton).
  [[nodiscard]] S findNearestParameter(const Vec3& point) const;

  /// A unit normal of the curve at t, carried from P₀ along the curve without
  /// turning about the tangent (a rotation-minimizing frame, by minimal
  /// rotations between samples): the reference for angles about the tangent.
  /// At P₀ it is the part of z across the tangent (or of x when the tangent is along z).
  [[nodiscard]] Vec3 getNormal(S t) const;

 protected:
  ~CubicSplineT() override = default;

 private:
  struct Knot {
    Vec3 position;
    Vec3 tangent;
    bool given;
  };
  struct Segment {
    std::size_t index;
    S u;
  };
  /// Samples per segment of the normals and of the nearest-point scans.
  static constexpr int kSamples = 8;
  /// Largest Newton step of the nearest-point search (units of parameter).
  static constexpr S kMaxStep = S(0.5);
  /// Newton steps below this (units of parameter) are not checked for descent.
  static constexpr S kFineStep = S(1e-3);

  const Knot& knot(std::size_t index) const {
    if (index >= knots_.size())
      throw detail::makeError("CubicSpline", "", "point index out of range 0.." + std::to_string(knots_.size()) + " (exclusive)",
                              index);
    return knots_[index];
  }
  void requireCurve() const {
    if (knots_.size() < 2) throw detail::makeError("CubicSpline", "", "needs at least two points", knots_.size());
  }

  void append(const Vec3& point, const Vec3& tangent, bool given) {
    if (!point.allFinite()) throw detail::makeError("CubicSpline", "", "point must be finite (m)", point);
    if (!knots_.empty() && !((point - knots_.back().position).norm() >
                             S(16) * ScalarTraits<S>::epsilon() * std::max(S(1), point.norm())))
      throw detail::makeError("CubicSpline", "", "point must differ from the previous point (m)", point);
    knots_.push_back({point, tangent, given});
    rebuildFrom(knots_.size() < 3 ? 0 : knots_.size() - 3);
  }

  // Tangents of the points from `first` on, then the arc lengths and normals
  // of the segments from `first` on.
  void rebuildFrom(std::size_t first) {
    const std::size_t n = knots_.size();
    if (n < 2) return;
    const S keep = S(1) - tension_;
    for (std::size_t i = first; i < n; ++i) {
      if (knots_[i].given) continue;
      const Vec3& before = knots_[i == 0 ? 0 : i - 1].position;
      const Vec3& after = knots_[i + 1 == n ? n - 1 : i + 1].position;
      knots_[i].tangent = (i == 0 || i + 1 == n ? keep : keep * S(0.5)) * (after - before);
    }
    lengths_.resize(n);
    lengths_[0] = S(0);
    for (std::size_t i = first; i + 1 < n; ++i) lengths_[i + 1] = lengths_[i] + lengthWithin(i, S(0), S(1));
    const std::size_t samples = (n - 1) * kSamples + 1;
    normals_.resize(samples);
    tangents_.resize(samples);
    std::size_t j = first * kSamples;
    if (j == 0) {
      tangents_[0] = direction(0, S(0));
      normals_[0] = startNormal(tangents_[0]);
      j = 1;
    }
    for (; j < samples; ++j) {
      const Segment s = sampleSegment(j);
      tangents_[j] = direction(s.index, s.u);
      normals_[j] = carried(normals_[j - 1], tangents_[j - 1], tangents_[j]);
    }
  }

  static Vec3 startNormal(const Vec3& tangent) {
    const Vec3 reference = std::abs(tangent.z()) < S(0.9) ? Vec3::UnitZ() : Vec3::UnitX();
    return (reference - reference.dot(tangent) * tangent).normalized();
  }
  // `normal` turned with the smallest rotation taking tangent `from` to `to`.
  static Vec3 carried(const Vec3& normal, const Vec3& from, const Vec3& to) {
    const Vec3 turned = detail::shortestArc<S>(from, to) * normal;
    const Vec3 across = turned - turned.dot(to) * to;
    const S norm = across.norm();
    return norm > S(0) ? Vec3(across / norm) : startNormal(to);
  }

  Segment sampleSegment(std::size_t sample) const {
    const std::size_t last = knots_.size() - 2;
    const std::size_t index = std::min(sample / kSamples, last);
    return {index, S(sample - index * kSamples) / S(kSamples)};
  }
  Segment segmentAt(S t) const {
    const S c = clampParameter(t);
    const std::size_t last = knots_.size() - 2;
    const std::size_t index = std::min(static_cast<std::size_t>(c), last);
    return {index, c - S(index)};
  }

  // The Hermite basis or its derivative of order D at u.
  template <int D>
  static std::array<S, 4> basis(S u) {
    const S u2 = u * u, u3 = u2 * u;
    if constexpr (D == 0)
      return {S(2) * u3 - S(3) * u2 + S(1), u3 - S(2) * u2 + u, S(3) * u2 - S(2) * u3, u3 - u2};
    else if constexpr (D == 1)
      return {S(6) * u2 - S(6) * u, S(3) * u2 - S(4) * u + S(1), S(6) * u - S(6) * u2, S(3) * u2 - S(2) * u};
    else
      return {S(12) * u - S(6), S(6) * u - S(4), S(6) - S(12) * u, S(6) * u - S(2)};
  }
  template <int D>
  Vec3 evaluateSegment(std::size_t i, S u) const {
    const std::array<S, 4> b = basis<D>(u);
    const Knot &k0 = knots_[i], &k1 = knots_[i + 1];
    return b[0] * k0.position + b[1] * k0.tangent + b[2] * k1.position + b[3] * k1.tangent;
  }
  template <int D>
  Vec3 evaluate(S t) const {
    requireCurve();
    const Segment s = segmentAt(t);
    return evaluateSegment<D>(s.index, s.u);
  }
  // Unit tangent; where dP/dt vanishes (a cusp) the direction of d²P/dt², then the chord.
  Vec3 direction(std::size_t i, S u) const {
    const Vec3 d1 = evaluateSegment<1>(i, u);
    const S scale = (knots_[i + 1].position - knots_[i].position).norm();
    if (d1.norm() > S(64) * ScalarTraits<S>::epsilon() * scale) return d1.normalized();
    const Vec3 d2 = evaluateSegment<2>(i, u);
    if (d2.norm() > S(64) * ScalarTraits<S>::epsilon() * scale) return d2.normalized();
    return (knots_[i + 1].position - knots_[i].position).normalized();
  }

  // ∫ |dP/dt| dt over [a, b] within segment i: five-point Gauss–Legendre on
  // halves until two levels agree.
  S lengthWithin(std::size_t i, S a, S b) const {
    if (!(b > a)) return S(0);
    return refine(i, a, b, gauss(i, a, b), 12);
  }
  S refine(std::size_t i, S a, S b, S whole, int depth) const {
    const S mid = S(0.5) * (a + b);
    const S left = gauss(i, a, mid), right = gauss(i, mid, b);
    const S tolerance = S(64) * ScalarTraits<S>::epsilon() * std::max(whole, S(1e-30));
    if (depth == 0 || std::abs(left + right - whole) <= tolerance) return left + right;
    return refine(i, a, mid, left, depth - 1) + refine(i, mid, b, right, depth - 1);
  }
  S gauss(std::size_t i, S a, S b) const {
    // Nodes ±x and weights w of the five-point rule on [−1, 1].
    static constexpr std::array<double, 3> x{0.0, 0.5384693101056831, 0.9061798459386640};
    static constexpr std::array<double, 3> w{0.5688888888888889, 0.4786286704993665, 0.2369268850561891};
    const S half = S(0.5) * (b - a), mid = S(0.5) * (a + b);
    S sum = S(w[0]) * evaluateSegment<1>(i, mid).norm();
    for (std::size_t k = 1; k < 3; ++k)
      sum += S(w[k]) * (evaluateSegment<1>(i, mid - half * S(x[k])).norm() +
                        evaluateSegment<1>(i, mid + half * S(x[k])).norm());
    return half * sum;
  }

  S squaredDistance(const Vec3& point, S t) const { return (evaluate<0>(t) - point).squaredNorm(); }
  // Newton's method on f(t) = |P(t) − x|²/2 from t: f' = (P − x)·P',
  // f'' = P'·P' + (P − x)·P''. Steps of at most kMaxStep, halved until the
  // distance does not grow. True when it settled at a minimum or at an end.
  bool descend(const Vec3& point, S& t) const;
  S bestSample(const Vec3& point, S from, S to) const {
    S best = clampParameter(from), bestDistance = squaredDistance(point, best);
    const S spacing = S(1) / S(kSamples);
    for (S s = best + spacing; s <= clampParameter(to) + spacing * S(0.5); s += spacing) {
      const S t = clampParameter(s), d = squaredDistance(point, t);
      if (d < bestDistance) {
        best = t;
        bestDistance = d;
      }
    }
    return best;
  }

  std::vector<Knot> knots_;
  S tension_ = S(0);
  std::vector<S> lengths_;     // arc length from P₀ to Pᵢ (m)
  std::vector<Vec3> tangents_;  // unit tangents at the samples t = j / kSamples
  std::vector<Vec3> normals_;   // rotation-minimizing normals at the same samples
};

template <Scalar S>
S CubicSplineT<S>::getParameterAtLength(S length) const {
  requireCurve();
  if (!std::isfinite(length)) throw detail::makeError("CubicSpline", "", "arc length must be finite (m)", length);
  if (length <= S(0)) return S(0);
  if (length >= lengths_.back()) return getMaxParameter();
  const std::size_t i =
      std::min(static_cast<std::size_t>(std::upper_bound(lengths_.begin(), lengths_.end(), length) - lengths_.begin()) - 1,
               knots_.size() - 2);
  const S target = length - lengths_[i], segment = lengths_[i + 1] - lengths_[i];
  // Newton on s(u) − target, kept inside a bisection bracket.
  S lo = S(0), hi = S(1), u = std::clamp(target / segment, S(0), S(1));
  for (int k = 0; k < 60; ++k) {
    const S f = lengthWithin(i, S(0), u) - target;
    if (std::abs(f) <= S(8) * ScalarTraits<S>::epsilon() * std::max(length, S(1))) break;
    (f > S(0) ? hi : lo) = u;
    const S next = u - f / evaluateSegment<1>(i, u).norm();
    u = next > lo && next < hi ? next : S(0.5) * (lo + hi);
    if (hi - lo <= ScalarTraits<S>::epsilon()) break;
  }
  return S(i) + u;
}

template <Scalar S>
bool CubicSplineT<S>::descend(const Vec3& point, S& t) const {
  const S tolerance = std::sqrt(ScalarTraits<S>::epsilon());
  const int iterations = 32 + 2 * static_cast<int>(knots_.size());
  S distance = squaredDistance(point, t);
  for (int k = 0; k < iterations; ++k) {
    const Vec3 offset = evaluate<0>(t) - point, d1 = evaluate<1>(t), d2 = evaluate<2>(t);
    const S slope = offset.dot(d1), curvature = d1.squaredNorm() + offset.dot(d2);
    const bool minimum = curvature > S(0);
    S step = minimum ? -slope / curvature : (slope > S(0) ? -kMaxStep : kMaxStep);
    step = std::clamp(step, -kMaxStep, kMaxStep);
    S next = clampParameter(t + step), nextDistance = squaredDistance(point, next);
    // Near a minimum a Newton step changes the distance by less than its
    // round-off: such steps are taken as they are.
    const bool fine = minimum && std::abs(step) <= kFineStep;
    if (fine) distance = std::max(distance, nextDistance);
    while (nextDistance > distance && std::abs(next - t) > tolerance) {
      step *= S(0.5);
      next = clampParameter(t + step);
      nextDistance = squaredDistance(point, next);
    }
    const bool settled = std::abs(next - t) <= tolerance;
    if (nextDistance <= distance) {
      t = next;
      distance = nextDistance;
    }
    if (settled) return minimum || t == S(0) || t == getMaxParameter();
  }
  return false;
}

template <Scalar S>
S CubicSplineT<S>::findNearestParameter(const Vec3& point, S guess) const {
  requireCurve();
  if (!point.allFinite()) throw detail::makeError("CubicSpline", "", "point must be finite (m)", point);
  if (!std::isfinite(guess)) throw detail::makeError("CubicSpline", "", "parameter guess must be finite", guess);
  S t = clampParameter(guess);
  if (descend(point, t)) return t;
  t = bestSample(point, guess - S(1), guess + S(1));
  descend(point, t);
  return t;
}

template <Scalar S>
S CubicSplineT<S>::findNearestParameter(const Vec3& point) const {
  requireCurve();
  if (!point.allFinite()) throw detail::makeError("CubicSpline", "", "point must be finite (m)", point);
  S t = bestSample(point, S(0), getMaxParameter());
  descend(point, t);
  return t;
}

template <Scalar S>
typename CubicSplineT<S>::Vec3 CubicSplineT<S>::getNormal(S t) const {
  requireCurve();
  const S c = clampParameter(t);
  const std::size_t j = std::min(static_cast<std::size_t>(c * S(kSamples)), normals_.size() - 1);
  const Segment s = segmentAt(c);
  return carried(normals_[j], tangents_[j], direction(s.index, s.u));
}

using CubicSpline = CubicSplineT<double>;
using CubicSplineRef = ref_ptr<CubicSpline>;
namespace f32 {
using CubicSpline = CubicSplineT<float>;
using CubicSplineRef = ref_ptr<CubicSpline>;
}  // namespace f32

}  // namespace spook
