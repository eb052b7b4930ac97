#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include <spook/core/error.hpp>
#include <spook/core/implementation.hpp>
#include <spook/core/scalar.hpp>

namespace spook {

// Math types are Eigen types behind short aliases, named like the classes:
// `Vec3T<S>` is the template, `spook::Vec3` the double type and
// `spook::f32::Vec3` the float one (as RigidBodyT<S> / RigidBody), so that
// `spook::Vec3 x = spook::Vec3(0, 0, 1);` is plain C++.
// Right-handed coordinates, SI units throughout.

/// 3-vector.
template <class S>
using Vec3T = Eigen::Matrix<S, 3, 1>;
/// Unit quaternion for rotations (Hamilton convention, as Eigen).
template <class S>
using QuatT = Eigen::Quaternion<S>;
/// 3×3 matrix.
template <class S>
using Mat3T = Eigen::Matrix<S, 3, 3>;
/// Rigid transform: rotation and translation, no scale (AGX's AffineMatrix4x4).
template <class S>
using TransformT = Eigen::Transform<S, 3, Eigen::Isometry>;

/// Rotation angles in radians about the fixed x, y and z axes, applied in
/// that order: R = Rz(z) · Ry(y) · Rx(x) (roll, pitch, yaw).
template <class S>
struct EulerAnglesT {
  EulerAnglesT() = default;
  EulerAnglesT(S x_, S y_, S z_) : x(x_), y(y_), z(z_) {}
  S x = S(0);
  S y = S(0);
  S z = S(0);
};

/// A symmetric positive-definite 3×3 matrix, such as an inertia tensor
/// (kg·m²). Construction checks the property and throws spook::Error.
template <class S>
class SPDMat3T {
 public:
  /// The identity.
  SPDMat3T() : m_(Mat3T<S>::Identity()) {}
  /// From a 3-vector (a diagonal matrix) or a full 3×3 matrix; throws unless
  /// the result is finite, symmetric and positive definite.
  template <class Derived>
  explicit SPDMat3T(const Eigen::MatrixBase<Derived>& value) {
    Mat3T<S> m;
    if constexpr (Derived::ColsAtCompileTime == 1) {
      m = Vec3T<S>(value).asDiagonal();
    } else {
      m = value;
    }
    if (const char* why = defect(m)) throw detail::makeError("SPDMat3", "", why, flat(m));
    m_ = S(0.5) * (m + m.transpose());
  }

  /// Why `m` is not symmetric positive definite, or nullptr when it is.
  [[nodiscard]] static const char* defect(const Mat3T<S>& m);

  [[nodiscard]] const Mat3T<S>& matrix() const { return m_; }
  [[nodiscard]] Mat3T<S> inverse() const { return m_.inverse(); }
  [[nodiscard]] Vec3T<S> diagonal() const { return m_.diagonal(); }

  /// Row-major entries, for error messages.
  static Eigen::Matrix<S, 9, 1> flat(const Mat3T<S>& m);

 private:
  Mat3T<S> m_;
};

template <class S>
const char* SPDMat3T<S>::defect(const Mat3T<S>& m) {
  if (!m.allFinite()) return "matrix must be finite";
  const S scale = m.cwiseAbs().maxCoeff();
  if (!((m - m.transpose()).cwiseAbs().maxCoeff() <= ScalarTraits<S>::symmetryTolerance() * scale))
    return "matrix must be symmetric";
  const Mat3T<S> sym = S(0.5) * (m + m.transpose());
  // Relative to the largest eigenvalue, so that round-off cannot pass a
  // singular matrix off as positive definite.
  const Vec3T<S> eigenvalues = Eigen::SelfAdjointEigenSolver<Mat3T<S>>(sym, Eigen::EigenvaluesOnly).eigenvalues();
  if (!(eigenvalues.minCoeff() > S(16) * ScalarTraits<S>::epsilon() * eigenvalues.maxCoeff()))
    return "matrix must be positive definite";
  return nullptr;
}

template <class S>
auto SPDMat3T<S>::flat(const Mat3T<S>& m) -> Eigen::Matrix<S, 9, 1> {
  Eigen::Matrix<S, 9, 1> v;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) v[3 * r + c] = m(r, c);
  return v;
}

SPOOK_COMPILED_ONCE(class, SPDMat3T)

/// True when R is finite, orthonormal (to ScalarTraits::rotationTolerance)
/// and right-handed: the linear part of a rigid transform.
template <class S>
[[nodiscard]] bool isRotation(const Mat3T<S>& R) {
  return R.allFinite() && (R.transpose() * R - Mat3T<S>::Identity()).norm() <= ScalarTraits<S>::rotationTolerance() &&
         R.determinant() > S(0);
}

/// True when every component is finite.
template <class Derived>
[[nodiscard]] bool isFinite(const Eigen::MatrixBase<Derived>& m) {
  return m.allFinite();
}
template <class S>
[[nodiscard]] bool isFinite(const QuatT<S>& q) {
  return q.coeffs().allFinite();
}

/// True when q is a rotation up to scale: every component finite and at
/// least one non-zero.
template <class S>
[[nodiscard]] bool isRotationQuaternion(const QuatT<S>& q) {
  return q.coeffs().allFinite() && q.coeffs().cwiseAbs().maxCoeff() > S(0);
}

/// q / |q| for any finite non-zero q. Eigen's normalized() squares the
/// components: |q|² overflows to inf from components ~1e154 (double), ~1e19
/// (float), which would give (0, 0, 0, 0), and underflows to 0 below ~1e-154
/// (~1e-19), which would leave q as it is. Such q are first divided by their
/// largest |component|; ordinary ones take the plain (bit-identical) path.
template <class S>
[[nodiscard]] QuatT<S> unitQuaternion(const QuatT<S>& q) {
  const S squared = q.squaredNorm();
  if (squared >= std::numeric_limits<S>::min() && squared <= std::numeric_limits<S>::max()) return q.normalized();
  const S largest = q.coeffs().cwiseAbs().maxCoeff();
  if (!(largest > S(0))) return q;
  return QuatT<S>(q.coeffs() / largest).normalized();
}

namespace detail {
/// The shortest rotation taking non-zero `from` onto `to`, for unit a, b:
/// q ∝ (|a + b|²/2, a × (a + b)), the half-angle form (1 + a·b, a × b) with
/// both parts taken from the sum a + b, which is exact where b nears −a and
/// keeps the axis accurate to round-off there (a × b would not be). Exact
/// antiparallels take a half turn about the axis perpendicular to a and to
/// its least aligned cardinal axis. (Eigen's FromTwoVectors needs an SVD for
/// those, a heavy instantiation in every program.)
template <class S>
[[nodiscard]] QuatT<S> shortestArc(const Vec3T<S>& from, const Vec3T<S>& to) {
  // Divided by the largest |component| first, so that vectors whose squared
  // norm overflows or underflows keep their direction.
  const Vec3T<S> a = (from / from.cwiseAbs().maxCoeff()).normalized(), b = (to / to.cwiseAbs().maxCoeff()).normalized();
  const Vec3T<S> sum = a + b;
  if (sum.norm() > S(8) * std::numeric_limits<S>::epsilon()) {
    const Vec3T<S> v = a.cross(sum);
    return QuatT<S>(S(0.5) * sum.squaredNorm(), v.x(), v.y(), v.z()).normalized();
  }
  Eigen::Index least = 0;
  a.cwiseAbs().minCoeff(&least);
  const Vec3T<S> axis = a.cross(Vec3T<S>::Unit(least)).normalized();
  return QuatT<S>(S(0), axis.x(), axis.y(), axis.z());
}
}  // namespace detail

/// The shortest rotation taking direction `from` onto direction `to` (AGX's
/// Quat::rotate). Antiparallel vectors give a half turn about an axis
/// perpendicular to both.
template <class S>
[[nodiscard]] QuatT<S> rotate(const Vec3T<S>& from, const Vec3T<S>& to) {
  if (!from.allFinite() || !to.allFinite() || !(from.cwiseAbs().maxCoeff() > S(0)) ||
      !(to.cwiseAbs().maxCoeff() > S(0)))
    throw detail::makeError("rotate", "", "vectors must be finite and non-zero",
                            Eigen::Matrix<S, 6, 1>(from.x(), from.y(), from.z(), to.x(), to.y(), to.z()));
  return detail::shortestArc<S>(from, to);
}

/// Rotation matrix of Euler angles (R = Rz · Ry · Rx).
template <class S>
[[nodiscard]] Mat3T<S> toMatrix(const EulerAnglesT<S>& e) {
  return (Eigen::AngleAxis<S>(e.z, Vec3T<S>::UnitZ()) * Eigen::AngleAxis<S>(e.y, Vec3T<S>::UnitY()) *
          Eigen::AngleAxis<S>(e.x, Vec3T<S>::UnitX()))
      .toRotationMatrix();
}

/// Quaternion of Euler angles.
template <class S>
[[nodiscard]] QuatT<S> toQuat(const EulerAnglesT<S>& e) {
  return QuatT<S>(Eigen::AngleAxis<S>(e.z, Vec3T<S>::UnitZ()) * Eigen::AngleAxis<S>(e.y, Vec3T<S>::UnitY()) *
                  Eigen::AngleAxis<S>(e.x, Vec3T<S>::UnitX()));
}

/// Euler angles of a rotation matrix, with y in [−π/2, π/2]. At y = ±π/2
/// (gimbal lock) only x ∓ z is defined; z is set to 0. y comes from atan2,
/// which stays accurate near ±π/2 where asin would not.
template <class S>
[[nodiscard]] EulerAnglesT<S> toEulerAngles(const Mat3T<S>& R) {
  using std::atan2;
  EulerAnglesT<S> e;
  const S cosY = std::hypot(R(0, 0), R(1, 0));
  e.y = atan2(-R(2, 0), cosY);
  if (cosY > S(16) * ScalarTraits<S>::epsilon()) {
    e.x = atan2(R(2, 1), R(2, 2));
    e.z = atan2(R(1, 0), R(0, 0));
  } else {
    e.z = S(0);
    e.x = atan2(-R(1, 2), R(1, 1));
  }
  return e;
}

/// Euler angles of a quaternion.
template <class S>
[[nodiscard]] EulerAnglesT<S> toEulerAngles(const QuatT<S>& q) {
  return toEulerAngles<S>(unitQuaternion<S>(q).toRotationMatrix());
}

/// Transform from translation and rotation.
template <class S>
[[nodiscard]] TransformT<S> makeTransform(const Vec3T<S>& translate, const QuatT<S>& rotate = QuatT<S>::Identity()) {
  TransformT<S> X = TransformT<S>::Identity();
  X.linear() = unitQuaternion<S>(rotate).toRotationMatrix();
  X.translation() = translate;
  return X;
}

/// Skew-symmetric cross-product matrix: skew(a) b = a × b.
template <class S>
[[nodiscard]] Mat3T<S> skew(const Vec3T<S>& a) {
  Mat3T<S> m;
  m << S(0), -a.z(), a.y(), a.z(), S(0), -a.x(), -a.y(), a.x(), S(0);
  return m;
}

/// exp of the rotation vector `phi` (radians): the rotation by |phi| about phi/|phi|.
template <class S>
[[nodiscard]] QuatT<S> expRotation(const Vec3T<S>& phi) {
  const S angle = phi.norm();
  if (angle < S(1e-4)) {
    // Taylor series of cos(θ/2) and sin(θ/2)/θ, exact to round-off here.
    const S a2 = angle * angle;
    const S w = S(1) - a2 / S(8) + a2 * a2 / S(384);
    const S k = S(0.5) - a2 / S(48);
    return QuatT<S>(w, k * phi.x(), k * phi.y(), k * phi.z()).normalized();
  }
  return QuatT<S>(Eigen::AngleAxis<S>(angle, phi / angle));
}

/// log of a rotation: the rotation vector (radians, |result| ≤ π).
template <class S>
[[nodiscard]] Vec3T<S> logRotation(const QuatT<S>& q) {
  QuatT<S> u = unitQuaternion<S>(q);
  if (u.w() < S(0)) u.coeffs() = -u.coeffs();
  const S s = u.vec().norm();
  if (s < S(1e-6)) return S(2) * u.vec() / u.w();
  return S(2) * std::atan2(s, u.w()) * u.vec() / s;
}

/// The double math types (what user code writes) and their float twins.
using Vec3 = Vec3T<double>;
using Quat = QuatT<double>;
using Mat3 = Mat3T<double>;
using Transform = TransformT<double>;
using EulerAngles = EulerAnglesT<double>;
using SPDMat3 = SPDMat3T<double>;
namespace f32 {
using Vec3 = Vec3T<float>;
using Quat = QuatT<float>;
using Mat3 = Mat3T<float>;
using Transform = TransformT<float>;
using EulerAngles = EulerAnglesT<float>;
using SPDMat3 = SPDMat3T<float>;
}  // namespace f32

/// π and its halves and quarters, as in the seeds (agx::PI, agx::PI_2, agx::PI_4).
inline constexpr double PI = 3.14159265358979323846;
inline constexpr double PI_2 = PI / 2;
inline constexpr double PI_4 = PI / 4;

/// Degrees to radians and back.
template <class S>
[[nodiscard]] constexpr S degreesToRadians(S degrees) {
  return degrees * S(PI / 180.0);
}
template <class S>
[[nodiscard]] constexpr S radiansToDegrees(S radians) {
  return radians * S(180.0 / PI);
}

/// The unit axes (agx::X_AXIS; Eigen spells them Vec3::UnitX()).
inline const Vec3 X_AXIS = Vec3::UnitX();
inline const Vec3 Y_AXIS = Vec3::UnitY();
inline const Vec3 Z_AXIS = Vec3::UnitZ();
namespace f32 {
inline const Vec3 X_AXIS = Vec3::UnitX();
inline const Vec3 Y_AXIS = Vec3::UnitY();
inline const Vec3 Z_AXIS = Vec3::UnitZ();
}  // namespace f32

}  // namespace spook
