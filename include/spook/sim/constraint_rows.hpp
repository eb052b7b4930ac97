#pragma once

#include <algorithm>
#include <cstddef>
#include <span>
#include <unordered_map>
#include <vector>

#include <spook/constraints/constraint.hpp>
#include <spook/core/ref_ptr.hpp>
#include <spook/solver/island_problem.hpp>
#include <spook/solver/row.hpp>
#include <spook/solver/solver.hpp>

namespace spook::detail {

/// The enabled constraints' rows, written and read back as a row producer
/// does (sim/step_extension.hpp): each row's last impulse comes from its
/// slot (RowSink: the constraint's own variable), the solved one goes back
/// there, and the constraints' forces follow from the rows they wrote.
///
/// With post-stabilization it also keeps, per holonomic row, what the
/// step's linearization makes of it: the rate G v⁺ + hκ at which the row
/// moves g and the violation g + h·rate it should end with. The projection
/// restores that violation (it removes only the higher-order drift of the
/// step, not the rows' compliant or damped motion), and the rate is the
/// next step's b' term (SecondOrder::lastRate). They are keyed by slot, which
/// identifies a row from step to step whatever rows come and go around it.
template <Scalar S>
class ConstraintRows {
 public:
  using Constraint = ConstraintT<S>;

  /// Appends the rows of the enabled constraints whose bodies are in the
  /// step; bodyIndex(body) is a body's solver index, −1 when it is not in
  /// the simulation.
  template <class BodyIndex>
  void write(const std::vector<ref_ptr<Constraint>>& constraints, BodyIndex bodyIndex, const Solver& solver,
             double h, RowSet& set) {
    std::vector<Row>& rows = set.rows;
    owners_.clear();
    slots_.clear();
    first_ = rows.size();
    for (const auto& c : constraints) {
      RowSink sink;
      if (!c->getEnable() || !sinkFor(*c, bodyIndex, rows, slots_, sink)) continue;
      sink.arms = &set.arms;
      sink.curvatures = &set.secondOrder;
      // The second-order terms (SecondOrder) need the projection: without it
      // their error feeds back (the 1:1e6 chain of test_solvers.cpp diverges).
      sink.secondOrder = solver.projects(c->getSolveType());
      const std::size_t first = rows.size(), firstTerm = set.secondOrder.size();
      ConstraintAccess::addRows(*c, sink, h);
      owners_.resize(rows.size() - first_, c.get());
      for (std::size_t i = first; i < rows.size(); ++i) rows[i].constraint = int(first);
      if (sink.secondOrder) addLastRates(set, first, firstTerm);
    }
    for (const double* slot : slots_) set.impulses.push_back(*slot);
  }

  /// After the solve: `impulses` and `rows` are the ones write() appended,
  /// `bodies` hold v⁺ in freeVelocity. Writes the slots, the forces of the
  /// constraints that compute them, lets each constraint read its rows'
  /// results, and predicts the holonomic rows' violations when `predict`.
  void readBack(const std::vector<ref_ptr<Constraint>>& constraints, const RowSet& set,
                const std::vector<SolverBody>& bodies, double h, bool predict) {
    const auto rows = std::span<const Row>(set.rows).subspan(first_, slots_.size());
    const auto impulses = std::span<const double>(set.impulses).subspan(first_, slots_.size());
    for (std::size_t i = 0; i < slots_.size(); ++i) *slots_[i] = impulses[i];
    for (const auto& c : constraints)
      if (c->getEnableComputeForces()) ConstraintAccess::clearWrench(*c);
    for (std::size_t i = 0; i < owners_.size(); ++i)
      if (owners_[i]->getEnableComputeForces()) ConstraintAccess::addWrench(*owners_[i], rows[i], impulses[i] / h);
    for (const auto& c : constraints) ConstraintAccess::afterSolve(*c, h);

    predicted_.clear();
    if (!predict) return;
    curvatures_.assign(rows.size(), 0.0);
    for (const SecondOrder& term : set.secondOrder)
      if (term.row >= int(first_) && std::size_t(term.row) < first_ + rows.size())
        curvatures_[std::size_t(term.row) - first_] = term.curvature;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const double curvature = curvatures_[i];
      const Row& r = rows[i];
      if (!r.holonomic) continue;
      const auto speed = [&](int body, const Vec6d& J) {
        return body < 0 ? 0.0 : J.dot(bodies[static_cast<std::size_t>(body)].freeVelocity);
      };
      const double rate = speed(r.body1, r.J1) + speed(r.body2, r.J2) + h * curvature;
      predicted_[slots_[i]] = {r.violation + h * rate, rate};
    }
  }

  /// Post-stabilization: appends the projection rows of the constraints the
  /// solver projects, at the moved positions, each with the violation
  /// predicted for it in Row::speed. Rows without a prediction (a lock
  /// enabled by a listener after the solve) are left out.
  template <class BodyIndex>
  void writeProjectionRows(const std::vector<ref_ptr<Constraint>>& constraints, BodyIndex bodyIndex,
                           const Solver& solver, std::vector<Row>& rows) {
    projectionSlots_.clear();
    const std::size_t first = rows.size();
    for (const auto& c : constraints) {
      RowSink sink;
      if (!c->getEnable() || !solver.projects(c->getSolveType()) ||
          !sinkFor(*c, bodyIndex, rows, projectionSlots_, sink))
        continue;
      sink.secondOrder = true;
      ConstraintAccess::addProjectionRows(*c, sink);
    }
    RowSink all{&rows, -1, -1, SolveType::DIRECT, true, &projectionSlots_};
    all.keepRows(first, [&](Row& r, std::size_t, const double* slot) {
      const auto it = predicted_.find(slot);
      if (it == predicted_.end()) return false;
      r.speed = it->second.violation;
      return true;
    });
  }

  /// Predictions are keyed by slots that a later constraint may reuse.
  void forgetPredictions() { predicted_.clear(); }

 private:
  struct Prediction {
    double violation = 0.0, rate = 0.0;
  };

  // The predicted rates of the holonomic rows from `first` on become their
  // SecondOrder::lastRate; their terms are those from `firstTerm` on, and
  // rows without one get one.
  void addLastRates(RowSet& set, std::size_t first, std::size_t firstTerm) {
    terms_.assign(set.secondOrder.begin() + std::ptrdiff_t(firstTerm), set.secondOrder.end());
    set.secondOrder.resize(firstTerm);
    std::ranges::sort(terms_, {}, &SecondOrder::row);
    std::size_t k = 0;
    for (std::size_t i = first; i < set.rows.size(); ++i) {
      SecondOrder term{int(i)};
      bool keep = false;
      if (k < terms_.size() && terms_[k].row == int(i)) {
        term = terms_[k++];
        keep = true;
      }
      if (const auto it = predicted_.find(slots_[i - first_]); set.rows[i].holonomic && it != predicted_.end()) {
        term.lastRate = it->second.rate;
        keep = true;
      }
      if (keep) set.secondOrder.push_back(term);
    }
  }

  // A sink for c's rows, false when one of its bodies is not in the step.
  template <class BodyIndex>
  static bool sinkFor(Constraint& c, BodyIndex bodyIndex, std::vector<Row>& rows, std::vector<double*>& slots,
                      RowSink& sink) {
    const int body1 = bodyIndex(c.getBodyAt(0));
    const auto* second = c.getBodyAt(1);
    const int body2 = second ? bodyIndex(second) : -1;
    if (body1 < 0 || (second && body2 < 0)) return false;
    sink = RowSink{&rows, body1, body2, c.getSolveType(), false, &slots};
    return true;
  }

  std::size_t first_ = 0;
  std::vector<Constraint*> owners_;     ///< per row written, from first_ on
  std::vector<double*> slots_;          ///< per row written
  std::vector<double*> projectionSlots_;
  std::vector<SecondOrder> terms_;
  std::vector<double> curvatures_;      ///< per row written, readBack's scratch
  std::unordered_map<const double*, Prediction> predicted_;
};

}  // namespace spook::detail
