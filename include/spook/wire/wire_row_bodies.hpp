#pragma once

#include <Eigen/Core>

#include <spook/sim/step_extension.hpp>
#include <spook/solver/row.hpp>

namespace spook::detail {

/// Up to three (body, Jacobian block) terms of one of a wire's rows, merged
/// per body: a point on a body contributes (a, r × a) for a world direction
/// a at lever arm r; the world contributes nothing.
struct WireRowBodies {
  int index[3] = {-1, -1, -1};
  Vec6d J[3] = {Vec6d::Zero(), Vec6d::Zero(), Vec6d::Zero()};
  /// Arms of points that turn with their body (a wire's end fixed to it),
  /// the row's share of the geometric stiffness; zero elsewhere (a wrap's
  /// tangent point stays where the wire leaves the geometry).
  Eigen::Vector3d turningArm[3] = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  int count = 0;
  bool overflow = false;
  void add(int body, const Eigen::Vector3d& a, const Eigen::Vector3d& arm, bool turnsWithBody = false) {
    if (body < 0) return;
    int k = 0;
    while (k < count && index[k] != body) ++k;
    if (k == 3) {
      overflow = true;
      return;
    }
    if (k == count) index[count++] = body;
    J[k].head<3>() += a;
    J[k].tail<3>() += arm.cross(a);
    if (turnsWithBody) turningArm[k] = arm;
  }
  void write(RowWriter& rows, Row& row) const {
    row.body1 = index[0];
    row.J1 = J[0];
    row.body2 = index[1];
    row.J2 = J[1];
    if (count == 3) rows.setThirdBody(rows.size() - 1, index[2], J[2]);
    if (!(turningArm[0].isZero(0.0) && turningArm[1].isZero(0.0)))
      rows.setLeverArms(rows.size() - 1, turningArm[0], turningArm[1]);
  }
};
}  // namespace spook::detail
