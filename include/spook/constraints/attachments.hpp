#pragma once

#include <cmath>
#include <cstddef>
#include <iterator>
#include <numbers>
#include <vector>

#include <Eigen/Geometry>

#include <spook/core/implementation.hpp>
#include <spook/solver/island_problem.hpp>
#include <spook/solver/row.hpp>

namespace spook::detail {

using Quatd = Eigen::Quaterniond;

/// The two attachment frames of a constraint in world coordinates, in
/// double, with the bodies' centers of mass and velocities: everything an
/// elementary constraint needs to write its rows. For the world side the
/// center is the frame origin and the velocities are zero.
struct Attachments {
  Vec3d p1 = Vec3d::Zero(), p2 = Vec3d::Zero();  ///< frame origins (m)
  Quatd q1 = Quatd::Identity(), q2 = Quatd::Identity();
  Mat3d R1 = Mat3d::Identity(), R2 = Mat3d::Identity();  ///< frame axes as columns
  Vec3d c1 = Vec3d::Zero(), c2 = Vec3d::Zero();          ///< centers of mass (m)
  Vec6d v1 = Vec6d::Zero(), v2 = Vec6d::Zero();          ///< (v, ω) of the centers of mass
  /// The step (s) the rows are written for, which bounds their second-order
  /// terms where a body turns by radians in it (turnShare); 0: unbounded.
  double h = 0.0;

  [[nodiscard]] Vec3d r1() const { return p1 - c1; }
  [[nodiscard]] Vec3d r2() const { return p2 - c2; }
  /// G v of a row at the start of the step.
  [[nodiscard]] double speed(const Vec6d& J1, const Vec6d& J2) const { return J1.dot(v1) + J2.dot(v2); }
};

/// Where a constraint writes its rows this step. Each row names the
/// constraint's own variable that keeps its impulse (N·s) from step to step
/// (its slot): the step reads the warm start from it and writes the solved
/// impulse back to it after the solve.
struct RowSink {
  std::vector<Row>* rows = nullptr;
  int body1 = -1, body2 = -1;
  SolveType solveType = SolveType::DIRECT;
  /// True when the solver post-stabilizes these rows, which then take their
  /// second-order terms (SecondOrder::curvature); otherwise those are dropped.
  bool secondOrder = false;
  /// Each row's slot, in step with `rows` (none kept when null).
  std::vector<double*>* slots = nullptr;
  /// The lever arms of the rows that have them (none kept when null).
  std::vector<LeverArms>* arms = nullptr;
  /// The second-order terms of the rows that have them, in row order (none
  /// kept when null).
  std::vector<SecondOrder>* curvatures = nullptr;

  Row& add(const Vec6d& J1, const Vec6d& J2, double* impulse);
  /// The lever arms (world, m) of the row added last (LeverArms).
  void setArms(const Vec3d& arm1, const Vec3d& arm2);
  /// The second-order term κ of the row added last (SecondOrder), kept only
  /// when the rows are post-stabilized (`secondOrder`).
  void setCurvature(double kappa);
  /// Adds to the second-order term of an earlier row i.
  void addCurvature(std::size_t i, double kappa);
  /// Rows written so far: the index the next row gets.
  [[nodiscard]] std::size_t size() const { return rows->size(); }
  /// The slot of row i (nullptr when slots are not kept).
  [[nodiscard]] const double* slot(std::size_t i) const { return slots ? (*slots)[i] : nullptr; }
  /// Keeps the rows from `first` on for which keep(row, i − first, slot)
  /// holds (it may adjust the row), in order, with their slots.
  template <class Keep>
  void keepRows(std::size_t first, Keep&& keep) {
    std::vector<int> moved(rows->size() - first, -1);  // new index of each row from first on
    std::size_t out = first;
    for (std::size_t i = first; i < rows->size(); ++i) {
      if (!keep((*rows)[i], i - first, slot(i))) continue;
      if (out != i) {
        (*rows)[out] = (*rows)[i];
        if (slots) (*slots)[out] = (*slots)[i];
      }
      moved[i - first] = static_cast<int>(out++);
    }
    rows->resize(out);
    if (slots) slots->resize(out);
    const auto renumber = [&](auto* table) {
      if (!table) return;
      for (auto& entry : *table)
        if (std::size_t(entry.row) >= first) entry.row = moved[std::size_t(entry.row) - first];
      std::erase_if(*table, [](const auto& entry) { return entry.row < 0; });
    };
    renumber(arms);
    renumber(curvatures);
  }
};

#if defined(SPOOK_DEFINES_NON_TEMPLATES)
SPOOK_INLINE Row& RowSink::add(const Vec6d& J1, const Vec6d& J2, double* impulse) {
  Row& row = rows->emplace_back();
  row.body1 = body1;
  row.body2 = body2;
  row.J1 = J1;
  row.J2 = J2;
  row.solveType = solveType;
  if (slots) slots->push_back(impulse);
  return row;
}

SPOOK_INLINE void RowSink::setArms(const Vec3d& arm1, const Vec3d& arm2) {
  if (arms) arms->push_back({static_cast<int>(rows->size()) - 1, arm1, arm2});
}

SPOOK_INLINE void RowSink::setCurvature(double kappa) {
  if (secondOrder && curvatures) curvatures->push_back({static_cast<int>(rows->size()) - 1, kappa});
}

SPOOK_INLINE void RowSink::addCurvature(std::size_t i, double kappa) {
  if (!secondOrder || !curvatures) return;
  auto it = curvatures->end();
  while (it != curvatures->begin() && std::prev(it)->row >= static_cast<int>(i)) --it;
  if (it != curvatures->end() && it->row == static_cast<int>(i))
    it->curvature += kappa;
  else
    curvatures->insert(it, {static_cast<int>(i), kappa});
}
#endif

SPOOK_INLINE Vec6d linearAngular(const Vec3d& linear, const Vec3d& angular);

/// A scalar coordinate of a joint's free motion (an angle or a position)
/// with its Jacobian: what Motor1D, Lock1D and Range1D act on.
struct Coordinate {
  double value = 0.0;  ///< m or rad (angles with winding)
  double speed = 0.0;  ///< d(value)/dt at the start of the step
  Vec6d J1 = Vec6d::Zero(), J2 = Vec6d::Zero();
  bool rotational = false;
  /// ½ vᵀ∇²(value) v at the start of the step (SecondOrder::curvature); zero for
  /// the free angles, whose second-order term vanishes on the joint's
  /// manifold (the slack angles of slack.hpp, which leave it, carry theirs).
  double curvature = 0.0;
};

/// An angle (rad) whose rate is the relative angular velocity about `axis`
/// (world, unit): J₁ = (0, axis), J₂ = −J₁.
[[nodiscard]] SPOOK_INLINE Coordinate angleAbout(const Attachments& a, double value, const Vec3d& axis);

/// The relative rotation of frame 1 in frame 2, q₂* q₁, with w ≥ 0.
[[nodiscard]] SPOOK_INLINE Quatd relativeRotation(const Attachments& a);

/// Keeps an angle continuous across ±π: the raw angle in (−π, π] is turned
/// into the value nearest the last one.
class Winding {
 public:
  [[nodiscard]] double unwrap(double raw) const {
    if (!started_) return raw;
    return last_ + std::remainder(raw - last_, 2.0 * std::numbers::pi);
  }
  void update(double value) {
    last_ = value;
    started_ = true;
  }
  void reset() { started_ = false; }

 private:
  double last_ = 0.0;
  bool started_ = false;
};

#if defined(SPOOK_DEFINES_NON_TEMPLATES)
SPOOK_INLINE Vec6d linearAngular(const Vec3d& linear, const Vec3d& angular) {
  Vec6d J;
  J << linear, angular;
  return J;
}

SPOOK_INLINE Coordinate angleAbout(const Attachments& a, double value, const Vec3d& axis) {
  Coordinate c;
  c.rotational = true;
  c.value = value;
  c.J1 = linearAngular(Vec3d::Zero(), axis);
  c.J2 = linearAngular(Vec3d::Zero(), -axis);
  c.speed = a.speed(c.J1, c.J2);
  return c;
}

SPOOK_INLINE Quatd relativeRotation(const Attachments& a) {
  Quatd q = a.q2.conjugate() * a.q1;
  if (q.w() < 0.0) q.coeffs() = -q.coeffs();
  return q;
}
#endif
}  // namespace spook::detail
