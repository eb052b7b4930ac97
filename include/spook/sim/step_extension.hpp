#pragma once

// The doors through which new physics enters a step without edits to the
// simulation: body stores (bodies the step integrates beside its rigid
// bodies: particles, a wire's lumped nodes) and row producers (sources of
// constraint rows: a wire's stretch and bend rows, granular contacts).
// Both work in double whatever the scene's scalar; a simulation holds them
// with add()/remove() like its other content.

#include <cstddef>
#include <functional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include <spook/core/referenced.hpp>
#include <spook/core/scalar.hpp>
#include <spook/sim/membership.hpp>
#include <spook/solver/island_problem.hpp>
#include <spook/solver/row.hpp>

namespace spook {

class BodyStore;
template <Scalar S>
class SimulationT;
template <Scalar S>
class RigidBodyT;

/// What stores and producers see of the step they take part in.
class StepContext {
 public:
  using Vec3d = Eigen::Vector3d;

  StepContext(double timeStep, std::function<Vec3d(const Vec3d&)> gravity)
      : timeStep_(timeStep), gravity_(std::move(gravity)) {}

  /// h (s).
  [[nodiscard]] double getTimeStep() const { return timeStep_; }
  /// The simulation's gravity (m/s²) at a world point (m).
  [[nodiscard]] Vec3d gravity(const Vec3d& point) const { return gravity_(point); }
  /// The solver index of body i of `store` in this step (for Row::body1..3),
  /// −1 when the store is not in the step or i is out of its range.
  [[nodiscard]] int indexOf(const BodyStore& store, std::size_t i) const;
  /// The solver index of a rigid body of the simulation (for Row::body1..3),
  /// −1 when it is not in the simulation or not of its scalar type.
  template <Scalar S>
  [[nodiscard]] int indexOf(const RigidBodyT<S>& body) const {
    return bodyIndex_ && bodyScalarSize_ == sizeof(S) ? bodyIndex_(&body) : -1;
  }
  /// The simulation taking the step (its geometries, materials), nullptr
  /// when it is not of scalar type S.
  template <Scalar S>
  [[nodiscard]] const SimulationT<S>* getSimulation() const {
    return bodyScalarSize_ == sizeof(S) ? static_cast<const SimulationT<S>*>(simulation_) : nullptr;
  }

 private:
  template <Scalar>
  friend class SimulationT;
  double timeStep_;
  std::function<Vec3d(const Vec3d&)> gravity_;
  std::function<int(const void*)> bodyIndex_;  ///< of a RigidBodyT of bodyScalarSize_
  std::size_t bodyScalarSize_ = 0;
  const void* simulation_ = nullptr;  ///< a SimulationT of bodyScalarSize_
  std::vector<std::pair<const BodyStore*, std::size_t>> firstIndex_;  ///< per store in the step
  std::vector<std::size_t> sizes_;
};

/// Appends rows for the solver. A row is written in double with the
/// solver's conventions (solver/row.hpp): body indices from
/// StepContext::indexOf (−1: the world), Jacobian blocks (linear, angular),
/// a holonomic row's violation, compliance and damping (SPOOK), a velocity
/// row's target speed and viscosity, force bounds (N or N·m).
class RowWriter {
 public:
  using Vec3d = Eigen::Vector3d;

  explicit RowWriter(detail::RowSet& rows) : rows_(rows) {}

  /// A new row. `impulse` (N·s, usually the row's impulse last step) is the
  /// iterative solvers' warm start when they warm start and the direct
  /// solver's first guess of the row's state (at a bound or free) always.
  detail::Row& add(double impulse = 0.0) {
    rows_.impulses.push_back(impulse);
    return rows_.rows.emplace_back();
  }
  /// Rows written so far in the step: the index the next row gets.
  [[nodiscard]] std::size_t size() const { return rows_.size(); }

  /// Makes row `row` a friction row whose bounds follow the impulse of row
  /// `normal` (both this producer's): ±μΛn per row (SCALED_BOX), or within
  /// the disk of radius μΛn with its contact's other tangent row `partner`
  /// (CONE); with FIXED the row keeps its own bounds. `exact`: without the
  /// least compliance contact friction rows get (detail::FrictionLink).
  void setFriction(std::size_t row, std::size_t normal, double coefficient, detail::FrictionBound bound,
                   int partner = -1, bool exact = false) {
    rows_.friction.push_back({static_cast<int>(row), static_cast<int>(normal), partner, coefficient, bound, exact});
  }
  /// A third body of row `row` (StepContext::indexOf) and its Jacobian
  /// block (linear, angular): G v = J1·v1 + J2·v2 + J·v3.
  void setThirdBody(std::size_t row, int body, const detail::Vec6d& J) {
    rows_.thirdBodies.push_back({static_cast<int>(row), body, J});
  }
  /// The second-order term κ = ½ vᵀ(∂²g/∂q²)v of holonomic row `row` at the
  /// start of the step (m/s² or rad/s²; detail::SecondOrder), which a step
  /// with post-stabilization takes into account.
  void setCurvature(std::size_t row, double curvature) {
    rows_.secondOrder.push_back({static_cast<int>(row), curvature});
  }
  /// Lever arms (world, m) from the centers of mass of row `row`'s first two
  /// bodies to where its force acts: its share of the geometric stiffness
  /// (solver/geometric_stiffness.hpp).
  void setLeverArms(std::size_t row, const Vec3d& arm1, const Vec3d& arm2) {
    rows_.arms.push_back({static_cast<int>(row), arm1, arm2});
  }

 private:
  detail::RowSet& rows_;
};

/// Bodies the step integrates and solves beside the rigid bodies, held by
/// the store in whatever layout suits it (contiguous arrays for particles).
/// The solver sees each one as a detail::SolverBody: velocity, free
/// velocity, inverse mass and inertia (world); a body that cannot turn has a
/// zero inverse inertia.
class BodyStore : public Referenced {
 public:
  [[nodiscard]] const std::string& getName() const { return name_; }
  void setName(std::string name) { name_ = std::move(name); }

  /// The simulation this store was added to, or nullptr.
  [[nodiscard]] const void* getSimulationHandle() const { return simulation_; }

  /// Number of bodies now.
  [[nodiscard]] virtual std::size_t size() const = 0;
  /// Start of a step, before any row is written: the only place a store
  /// may add or remove bodies.
  virtual void beginStep(const StepContext& /*step*/) {}
  /// Each body as the solver sees it at the start of the step: velocity v,
  /// free velocity v* = v + h M⁻¹ f (applied forces, gravity), inverse mass
  /// and inertia, dynamic. `bodies` has size() entries, zero-initialized.
  virtual void writeSolverBodies(std::span<detail::SolverBody> bodies, const StepContext& step) const = 0;
  /// Moves the bodies by one step with the solved velocities
  /// (bodies[i].freeVelocity holds v⁺). A body of an island whose solve was
  /// not finite gets no impulses (v⁺ is its free velocity); unlike a rigid
  /// body it is not frozen: a store that may write non-finite velocities
  /// checks them here.
  virtual void move(std::span<const detail::SolverBody> bodies, const StepContext& step) = 0;
  /// Post-stabilization: displaces the bodies by bodies[i].displacement
  /// ((Δx, Δθ), m and rad), velocities unchanged.
  virtual void displace(std::span<const detail::SolverBody> bodies) = 0;

 protected:
  ~BodyStore() override = default;

 private:
  friend struct detail::SimulationMembership;
  const void* simulation_ = nullptr;
  std::string name_;
};

/// A source of rows: it writes its rows each step and reads back their
/// impulses after the solve; it keeps its own history (warm starts, forces,
/// tensions, persistence).
class RowProducer : public Referenced {
 public:
  [[nodiscard]] const std::string& getName() const { return name_; }
  void setName(std::string name) { name_ = std::move(name); }

  /// The simulation this producer was added to, or nullptr.
  [[nodiscard]] const void* getSimulationHandle() const { return simulation_; }

  /// Simulation::add calls this before it adds anything: a producer that
  /// cannot join (content it cannot simulate, a body that is not in the
  /// simulation: `simulation` answers indexOf for its rigid bodies, its time
  /// step and gravity) throws a spook::Error naming itself, and the
  /// simulation stays unchanged. It may build the bodies it owns here.
  virtual void prepare(const StepContext& /*simulation*/) {}
  /// The store of bodies this producer owns (a wire's lumped nodes), added
  /// to and removed from the simulation with it; none by default.
  [[nodiscard]] virtual BodyStore* getOwnedStore() { return nullptr; }
  /// Start of a step, after the stores' beginStep.
  virtual void beginStep(const StepContext& /*step*/) {}
  /// Appends this step's rows. A row naming a body index outside the step
  /// stops the step with a spook::Error naming the producer.
  virtual void writeRows(RowWriter& rows, const StepContext& step) = 0;
  /// The rows' impulses (N·s) after the solve, in the order written.
  virtual void readBack(std::span<const double> impulses, const StepContext& step) = 0;
  /// Post-stabilization (when the solver projects): holonomic rows at the
  /// moved positions, each with the violation to reach in Row::speed (m or
  /// rad; usually 0); none by default.
  virtual void writeProjectionRows(RowWriter& /*rows*/, const StepContext& /*step*/) {}

 protected:
  ~RowProducer() override = default;

 private:
  friend struct detail::SimulationMembership;
  const void* simulation_ = nullptr;
  std::string name_;
};

inline int StepContext::indexOf(const BodyStore& store, std::size_t i) const {
  for (std::size_t k = 0; k < firstIndex_.size(); ++k)
    if (firstIndex_[k].first == &store) return i < sizes_[k] ? static_cast<int>(firstIndex_[k].second + i) : -1;
  return -1;
}

}  // namespace spook
