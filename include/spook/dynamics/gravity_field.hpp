#pragma once

#include <spook/core/error.hpp>
#include <spook/core/math.hpp>
#include <spook/core/ref_ptr.hpp>
#include <spook/core/referenced.hpp>

namespace spook {

/// Applies gravity to every enabled dynamic body of a simulation, as an
/// acceleration of its center of mass (m/s²).
template <Scalar S>
class GravityFieldT : public Referenced {
 public:
  using Vec3 = spook::Vec3T<S>;
  /// Gravitational acceleration at world point p_W (m/s²).
  [[nodiscard]] virtual Vec3 calculateGravity(const Vec3& p_W) const = 0;

 protected:
  ~GravityFieldT() override = default;
};

/// The same acceleration everywhere; default (0, 0, −9.80665) m/s².
template <Scalar S>
class UniformGravityFieldT : public GravityFieldT<S> {
 public:
  using Vec3 = spook::Vec3T<S>;
  explicit UniformGravityFieldT(const Vec3& gravity = Vec3(S(0), S(0), S(-9.80665))) { setGravity(gravity); }

  /// Acceleration in world coordinates (m/s²).
  [[nodiscard]] const Vec3& getGravity() const { return gravity_; }
  void setGravity(const Vec3& gravity) {
    if (!gravity.allFinite()) throw detail::makeError("UniformGravityField", "", "gravity must be finite", gravity);
    gravity_ = gravity;
  }
  [[nodiscard]] Vec3 calculateGravity(const Vec3&) const override { return gravity_; }

 protected:
  ~UniformGravityFieldT() override = default;

 private:
  Vec3 gravity_;
};

/// Inverse-square attraction toward a center: a(p) = μ (c − p) / |c − p|³,
/// with strength μ = G·M in m³/s² (3.986004418e14 for the Earth). Zero at
/// the center itself.
template <Scalar S>
class PointGravityFieldT : public GravityFieldT<S> {
 public:
  using Vec3 = spook::Vec3T<S>;
  PointGravityFieldT(const Vec3& center, S strength) {
    setCenter(center);
    setStrength(strength);
  }

  /// Attracting point, world coordinates (m).
  [[nodiscard]] const Vec3& getCenter() const { return center_; }
  void setCenter(const Vec3& center) {
    if (!center.allFinite()) throw detail::makeError("PointGravityField", "", "center must be finite", center);
    center_ = center;
  }
  /// μ = G·M (m³/s²), finite and ≥ 0.
  [[nodiscard]] S getStrength() const { return strength_; }
  void setStrength(S strength) {
    if (!(std::isfinite(strength) && strength >= S(0)))
      throw detail::makeError("PointGravityField", "", "strength must be finite and >= 0 m^3/s^2", strength);
    strength_ = strength;
  }

  [[nodiscard]] Vec3 calculateGravity(const Vec3& p_W) const override {
    const Vec3 d = center_ - p_W;
    const S r2 = d.squaredNorm();
    if (!(r2 > S(0))) return Vec3::Zero();
    return (strength_ / (r2 * std::sqrt(r2))) * d;
  }

 protected:
  ~PointGravityFieldT() override = default;

 private:
  Vec3 center_;
  S strength_ = S(0);
};

using GravityField = GravityFieldT<double>;
using UniformGravityField = UniformGravityFieldT<double>;
using PointGravityField = PointGravityFieldT<double>;
using GravityFieldRef = ref_ptr<GravityField>;
using UniformGravityFieldRef = ref_ptr<UniformGravityField>;
using PointGravityFieldRef = ref_ptr<PointGravityField>;
namespace f32 {
using GravityField = GravityFieldT<float>;
using UniformGravityField = UniformGravityFieldT<float>;
using PointGravityField = PointGravityFieldT<float>;
using GravityFieldRef = ref_ptr<GravityField>;
using UniformGravityFieldRef = ref_ptr<UniformGravityField>;
using PointGravityFieldRef = ref_ptr<PointGravityField>;
}  // namespace f32

}  // namespace spook
