#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include <Eigen/Core>

namespace spook {

/// Which solver handles a constraint's rows under the hybrid policy
/// (seed 001 §12.17). The direct and iterative policies ignore it.
enum class SolveType : std::uint8_t {
  DIRECT = 1,               ///< the direct (pivoting, factorizing) solver
  ITERATIVE = 2,            ///< projected Gauss–Seidel
  DIRECT_AND_ITERATIVE = 3, ///< both: couples a direct subsystem to an iterative one
  SPLIT = 4                 ///< contacts only: normals direct, friction iterative with those normals
};

namespace detail {

/// How a friction row's bounds follow its contact's normal impulse Λn.
enum class FrictionBound : std::uint8_t {
  FIXED,       ///< the row's own bounds (box friction, or not a friction row)
  SCALED_BOX,  ///< ±μΛn, per tangent
  CONE         ///< the tangent pair within the disk of radius μΛn
};

using Vec6d = Eigen::Matrix<double, 6, 1>;

/// One scalar constraint row as the solver sees it, in double whatever the
/// scene's scalar. G v = J1·(v1, ω1) + J2·(v2, ω2) (+ J3·(v3, ω3)) with
/// velocities of the centers of mass in world coordinates; a body index of
/// −1 is the world. A third body is rare (a wire's bend row couples three
/// consecutive nodes): it is in a side table (ThirdBody).
///
/// A holonomic row has a violation g and SPOOK parameters (compliance ε,
/// damping τ): G v⁺ + Σ Λ = −a g + b' G v, Σ = 4ε/(h²(1+4τ/h)) (PHYSICS.md
/// §1.2). A velocity row (motors, friction) has a target speed u and a
/// viscosity γ: G v⁺ + (γ/h) Λ = u (§1.3). Bounds are forces (N or N·m).
/// A row's impulse Λ (N·s) is not in the row: the step keeps the impulses
/// in an array beside the rows, and each source of rows keeps its own
/// history (sim/step_extension.hpp). What only some rows have (a friction
/// row's link to its normal row, lever arms, a third body, second-order terms)
/// is in side tables (RowSet).
struct Row {
  // Members ordered by size (the step copies rows by the thousand).
  int body1 = -1;
  int body2 = -1;
  /// The index in the same row list of the first row of the constraint
  /// this row belongs to (−1: a contact's): an iterative sweep updates a
  /// constraint's unbounded rows together (iterative_solve.hpp).
  int constraint = -1;
  Vec6d J1 = Vec6d::Zero();  ///< (linear, angular) of body 1
  Vec6d J2 = Vec6d::Zero();  ///< (linear, angular) of body 2
  double violation = 0.0;   ///< g (m or rad), holonomic rows
  double speed = 0.0;       ///< target G v (m/s or rad/s), velocity rows
  double compliance = 0.0;  ///< ε, or γ for a velocity row
  double damping = 0.0;     ///< τ (s), holonomic rows
  double lower = -std::numeric_limits<double>::infinity();
  double upper = std::numeric_limits<double>::infinity();
  SolveType solveType = SolveType::DIRECT;
  bool holonomic = true;

  [[nodiscard]] bool bounded() const { return lower > -std::numeric_limits<double>::infinity() || upper < std::numeric_limits<double>::infinity(); }
};

/// Whether a row drives its bodies: a velocity row with a target speed (a
/// motor, a moving surface). Such a row wakes a sleeping body and keeps its
/// island awake (SimulationT::getAutoSleep). A row that only pushes
/// (lower bound >= 0) toward a negative speed, a gap the bodies may close
/// (a speculative contact), acts only on bodies that approach faster.
[[nodiscard]] inline bool drives(const Row& r) {
  return !r.holonomic && r.speed != 0.0 && !(r.lower >= 0.0 && r.speed < 0.0);
}

/// A friction row: its bounds follow the impulse of its contact's normal
/// row (solver/friction_bounds.hpp). Indices are in the same row list.
struct FrictionLink {
  int row = -1;              ///< the friction row
  int normal = -1;           ///< the normal row whose impulse bounds it
  int partner = -1;          ///< cone rows: the contact's other tangent row
  double coefficient = 0.0;  ///< μ
  FrictionBound bound = FrictionBound::FIXED;
  /// Without the least compliance of contact friction (islands.hpp,
  /// kFrictionSofterThan): a lone friction row on a degree of freedom of
  /// its own (a wire's slip over a sheave), which that floor would let creep.
  bool exact = false;
};

/// A translational row's lever arms (world, m) from each center of mass to
/// the point where its force acts, for the geometric stiffness
/// (geometric_stiffness.hpp); rows without them add none.
struct LeverArms {
  int row = -1;
  Eigen::Vector3d arm1 = Eigen::Vector3d::Zero(), arm2 = Eigen::Vector3d::Zero();
};

/// A holonomic row's second-order terms, used with post-stabilization only.
struct SecondOrder {
  int row = -1;
  /// κ = ½ vᵀ(∂²g/∂q²)v at the start of the step (m/s² or rad/s²), the
  /// quadratic velocity term of the index-1 DAE (Ġv/2). A step with velocity
  /// v⁺ moves g by hGv⁺ + h²κ + O(h³), and G_k v_k exceeds the last step's
  /// mean rate of g by hκ.
  double curvature = 0.0;
  /// The rate G_{k−1}v_k + hκ at which the last step moved g (m/s or rad/s),
  /// kept by post-stabilization; NaN when unknown, then G v − hκ stands in
  /// for it in SPOOK's b' term.
  double lastRate = std::numeric_limits<double>::quiet_NaN();
};

/// A row's third body and its Jacobian block (linear, angular).
struct ThirdBody {
  int row = -1;
  int body = -1;
  Vec6d J = Vec6d::Zero();
};

/// The rows of a step: one impulse per row beside them and, in side tables,
/// what only some rows have (entries in any order, one per row at most).
struct RowSet {
  std::vector<Row> rows;
  std::vector<double> impulses;  ///< N·s: each row's last impulse in, the solved one out
  std::vector<FrictionLink> friction;
  std::vector<LeverArms> arms;
  std::vector<ThirdBody> thirdBodies;
  std::vector<SecondOrder> secondOrder;

  [[nodiscard]] std::size_t size() const { return rows.size(); }
  [[nodiscard]] bool empty() const { return rows.empty(); }
  void clear() { truncate(0); }
  /// Drops the rows from n on and their side-table entries.
  void truncate(std::size_t n) {
    rows.resize(std::min(n, rows.size()));
    impulses.resize(rows.size());
    const auto dropRowsFromEnd = [&](auto& table) {
      std::erase_if(table, [&](const auto& entry) { return std::size_t(entry.row) >= rows.size(); });
    };
    dropRowsFromEnd(friction);
    dropRowsFromEnd(arms);
    dropRowsFromEnd(thirdBodies);
    dropRowsFromEnd(secondOrder);
  }
};

}  // namespace detail
}  // namespace spook
