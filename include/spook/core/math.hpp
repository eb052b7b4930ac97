#pragma once

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

#include <spook/core/error.hpp>
#include <spook/core/scalar.hpp>

namespace spook {

// Math types are Eigen types behind short aliases, templated on the scalar
// (default double, so `spook::Vec3(0, 0, 5)` deduces a double vector).
// Right-handed coordinates, SI units throughout.

/// 3-vector.
template <class S = double>
using Vec3 = Eigen::Matrix<S, 3, 1>;
/// Unit quaternion for rotations (Hamilton convention, as Eigen).
template <class S = double>
using Quat = Eigen::Quaternion<S>;
/// 3×3 matrix.
template <class S = double>
using Mat3 = Eigen::Matrix<S, 3, 3>;
/// Rigid transform: rotation and translation, no scale (AGX's AffineMatrix4x4).
template <class S = double>
using Transform = Eigen::Transform<S, 3, Eigen::Isometry>;

/// Rotation angles in radians about the fixed x, y and z axes, applied in
/// that order: R = Rz(z) · Ry(y) · Rx(x) (roll, pitch, yaw).
template <class S = double>
struct EulerAngles {
  S x = S(0);
  S y = S(0);
  S z = S(0);
};

/// A symmetric positive-definite 3×3 matrix, such as an inertia tensor
/// (kg·m²). Construction checks the property and throws spook::Error.
template <class S = double>
class SPDMat3 {
 public:
  /// The identity.
  SPDMat3() : m_(Mat3<S>::Identity()) {}
  /// From a 3-vector (a diagonal matrix) or a full 3×3 matrix; throws unless
  /// the result is finite, symmetric and positive definite.
  template <class Derived>
  explicit SPDMat3(const Eigen::MatrixBase<Derived>& value) {
    Mat3<S> m;
    if constexpr (Derived::ColsAtCompileTime == 1) {
      m = Vec3<S>(value).asDiagonal();
    } else {
      m = value;
    }
    if (const char* why = defect(m)) throw detail::makeError("SPDMat3", "", why, flat(m));
    m_ = S(0.5) * (m + m.transpose());
  }

  /// Why `m` is not symmetric positive definite, or nullptr when it is.
  [[nodiscard]] static const char* defect(const Mat3<S>& m) {
    if (!m.allFinite()) return "matrix must be finite";
    const S scale = m.cwiseAbs().maxCoeff();
    if (!((m - m.transpose()).cwiseAbs().maxCoeff() <= ScalarTraits<S>::symmetryTolerance() * scale))
      return "matrix must be symmetric";
    const Mat3<S> sym = S(0.5) * (m + m.transpose());
    // Relative to the largest eigenvalue, so that round-off cannot pass a
    // singular matrix off as positive definite.
    const Vec3<S> eigenvalues = Eigen::SelfAdjointEigenSolver<Mat3<S>>(sym, Eigen::EigenvaluesOnly).eigenvalues();
    if (!(eigenvalues.minCoeff() > S(16) * ScalarTraits<S>::epsilon() * eigenvalues.maxCoeff()))
      return "matrix must be positive definite";
    return nullptr;
  }

  [[nodiscard]] const Mat3<S>& matrix() const { return m_; }
  [[nodiscard]] Mat3<S> inverse() const { return m_.inverse(); }
  [[nodiscard]] Vec3<S> diagonal() const { return m_.diagonal(); }

  /// Row-major entries, for error messages.
  static Eigen::Matrix<S, 9, 1> flat(const Mat3<S>& m) {
    Eigen::Matrix<S, 9, 1> v;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) v[3 * r + c] = m(r, c);
    return v;
  }

 private:
  Mat3<S> m_;
};

/// True when R is finite, orthonormal (to ScalarTraits::rotationTolerance)
/// and right-handed: the linear part of a rigid transform.
template <class S>
[[nodiscard]] bool isRotation(const Mat3<S>& R) {
  return R.allFinite() && (R.transpose() * R - Mat3<S>::Identity()).norm() <= ScalarTraits<S>::rotationTolerance() &&
         R.determinant() > S(0);
}

/// True when every component is finite.
template <class Derived>
[[nodiscard]] bool isFinite(const Eigen::MatrixBase<Derived>& m) {
  return m.allFinite();
}
template <class S>
[[nodiscard]] bool isFinite(const Quat<S>& q) {
  return q.coeffs().allFinite();
}

/// The shortest rotation taking direction `from` onto direction `to` (AGX's
/// Quat::rotate). Antiparallel vectors give a half turn about an axis
/// perpendicular to both.
template <class S>
[[nodiscard]] Quat<S> rotate(const Vec3<S>& from, const Vec3<S>& to) {
  if (!(from.norm() > S(0)) || !(to.norm() > S(0)) || !from.allFinite() || !to.allFinite())
    throw detail::makeError("rotate", "", "vectors must be finite and non-zero",
                            Eigen::Matrix<S, 6, 1>(from.x(), from.y(), from.z(), to.x(), to.y(), to.z()));
  return Quat<S>::FromTwoVectors(from, to);
}

/// Rotation matrix of Euler angles (R = Rz · Ry · Rx).
template <class S>
[[nodiscard]] Mat3<S> toMatrix(const EulerAngles<S>& e) {
  return (Eigen::AngleAxis<S>(e.z, Vec3<S>::UnitZ()) * Eigen::AngleAxis<S>(e.y, Vec3<S>::UnitY()) *
          Eigen::AngleAxis<S>(e.x, Vec3<S>::UnitX()))
      .toRotationMatrix();
}

/// Quaternion of Euler angles.
template <class S>
[[nodiscard]] Quat<S> toQuat(const EulerAngles<S>& e) {
  return Quat<S>(Eigen::AngleAxis<S>(e.z, Vec3<S>::UnitZ()) * Eigen::AngleAxis<S>(e.y, Vec3<S>::UnitY()) *
                 Eigen::AngleAxis<S>(e.x, Vec3<S>::UnitX()));
}

/// Euler angles of a rotation matrix, with y in [−π/2, π/2]. At y = ±π/2
/// (gimbal lock) only x ∓ z is defined; z is set to 0. y comes from atan2,
/// which stays accurate near ±π/2 where asin would not.
template <class S>
[[nodiscard]] EulerAngles<S> toEulerAngles(const Mat3<S>& R) {
  using std::atan2;
  EulerAngles<S> e;
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
[[nodiscard]] EulerAngles<S> toEulerAngles(const Quat<S>& q) {
  return toEulerAngles<S>(q.normalized().toRotationMatrix());
}

/// Transform from translation and rotation.
template <class S>
[[nodiscard]] Transform<S> makeTransform(const Vec3<S>& translate, const Quat<S>& rotate = Quat<S>::Identity()) {
  Transform<S> X = Transform<S>::Identity();
  X.linear() = rotate.normalized().toRotationMatrix();
  X.translation() = translate;
  return X;
}

/// Skew-symmetric cross-product matrix: skew(a) b = a × b.
template <class S>
[[nodiscard]] Mat3<S> skew(const Vec3<S>& a) {
  Mat3<S> m;
  m << S(0), -a.z(), a.y(), a.z(), S(0), -a.x(), -a.y(), a.x(), S(0);
  return m;
}

/// exp of the rotation vector `phi` (radians): the rotation by |phi| about phi/|phi|.
template <class S>
[[nodiscard]] Quat<S> expRotation(const Vec3<S>& phi) {
  const S angle = phi.norm();
  if (angle < S(1e-4)) {
    // Taylor series of cos(θ/2) and sin(θ/2)/θ, exact to round-off here.
    const S a2 = angle * angle;
    const S w = S(1) - a2 / S(8) + a2 * a2 / S(384);
    const S k = S(0.5) - a2 / S(48);
    return Quat<S>(w, k * phi.x(), k * phi.y(), k * phi.z()).normalized();
  }
  return Quat<S>(Eigen::AngleAxis<S>(angle, phi / angle));
}

/// log of a rotation: the rotation vector (radians, |result| ≤ π).
template <class S>
[[nodiscard]] Vec3<S> logRotation(const Quat<S>& q) {
  Quat<S> u = q.normalized();
  if (u.w() < S(0)) u.coeffs() = -u.coeffs();
  const S s = u.vec().norm();
  if (s < S(1e-6)) return S(2) * u.vec() / u.w();
  return S(2) * std::atan2(s, u.w()) * u.vec() / s;
}

}  // namespace spook
