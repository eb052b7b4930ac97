#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include <spook/collide/geometry_contact.hpp>
#include <spook/dynamics/friction_model.hpp>
#include <spook/dynamics/gravity_field.hpp>
#include <spook/sim/contact_settings.hpp>
#include <spook/sim/material_manager.hpp>
#include <spook/solver/island_problem.hpp>
#include <spook/solver/islands.hpp>
#include <spook/solver/row.hpp>
#include <spook/solver/spook_parameters.hpp>

namespace spook::detail {

/// Turns the solvable contact points into rows (PHYSICS.md §1.4) and reads
/// their forces back, as a row producer does (sim/step_extension.hpp): it
/// appends its rows with their last impulses and reads its own impulses
/// back after the solve. Per point: a unilateral normal row on the gap
/// g = adhesive overlap − depth with compliance 1/E and the contact
/// material's damping (0 ≤ Λn, or down to −adhesive force), and two tangent
/// velocity rows that drive the slip to the surface velocities' difference,
/// with the surface viscosity as compliance and bounds from the friction
/// model. An impact faster than the restitution threshold turns the normal
/// row into a velocity row asking for e times the approach speed (Newton's
/// law, §1.4).
///
/// A gap point (negative depth, a speculative contact: SpaceT::update) is
/// a velocity row instead: the pair may approach along its normal by the
/// gap within the step, G v ≥ −gap/h, with the Σ of the touching row; an
/// approach fast enough to close the gap and above the restitution
/// threshold bounces at once, as a touching impact would. Its friction
/// rows are bounded by its own normal force (none for box friction, whose
/// bound stands alone).
///
/// A point that continues one of the last step's (contact persistence) gives
/// its rows that point's force as their last impulse: the warm start of
/// Gauss–Seidel (when enabled) and the starting active set of the direct
/// solver's pivoting, which a resting contact then keeps in one step.
template <Scalar S>
class ContactRows {
 public:
  /// Rows of the touching pairs `contacts` and then of the pairs with gap
  /// points only, `speculative`.
  template <class BodyIndex>
  void build(std::vector<GeometryContactT<S>>& contacts, std::vector<GeometryContactT<S>>& speculative,
             const MaterialManagerT<S>& materials, const GravityFieldT<S>& gravity, BodyIndex bodyIndex,
             const std::vector<SolverBody>& bodies, double h, const ContactSettings& settings, RowSet& set) {
    points_.clear();
    std::swap(pairs_, lastPairs_);
    std::swap(remembered_, lastRemembered_);
    pairs_.clear();
    remembered_.clear();

    for (auto* list : {&contacts, &speculative})
      for (auto& contact : *list) build(contact, materials, gravity, bodyIndex, bodies, h, settings, set);
  }

  /// From the solved impulses of the rows build() wrote (in their order):
  /// writes each point's force (on the second geometry's body) and keeps the
  /// normal force of each pair for the next step's box friction and each
  /// point's force for its continuation.
  void readBack(std::span<const double> impulses, double h) {
    for (std::size_t i = 0; i < points_.size(); ++i) {
      const PointRows& p = points_[i];
      const double* impulse = &impulses[3 * i];
      const Eigen::Vector3d force = (impulse[0] * p.normal + impulse[1] * p.t1 + impulse[2] * p.t2) / h;
      p.point->force = force.template cast<S>();
      p.point->normalForce = S(impulse[0] / h);
      if (pairs_.empty() || pairs_.back().pair != p.pair) pairs_.push_back({p.pair, 0.0, remembered_.size(), 0});
      pairs_.back().normalForce += impulse[0] / h;
      ++pairs_.back().count;
      remembered_.push_back({p.local, force});
    }
    std::sort(pairs_.begin(), pairs_.end(), [](const PairMemory& a, const PairMemory& b) { return a.pair < b.pair; });
  }

 private:
  using PairKey = std::pair<const void*, const void*>;
  struct PointRows {
    ContactPointT<S>* point;
    PairKey pair;
    Eigen::Vector3d local;  ///< in the first geometry's frame (m)
    Eigen::Vector3d normal, t1, t2;
  };
  struct Remembered {
    Eigen::Vector3d local;  ///< in the first geometry's frame (m)
    Eigen::Vector3d force;  ///< on the second geometry's body (N, world)
  };
  /// A pair's points of the last step: remembered_[first, first + count).
  struct PairMemory {
    PairKey pair;
    double normalForce;  ///< the sum of its points' (N)
    std::size_t first, count;
  };

  [[nodiscard]] const PairMemory* findLastPair(const PairKey& pair) const {
    const auto it = std::lower_bound(lastPairs_.begin(), lastPairs_.end(), pair,
                                     [](const PairMemory& m, const PairKey& key) { return m.pair < key; });
    return it != lastPairs_.end() && it->pair == pair ? &*it : nullptr;
  }

  // The force of the last step's point nearest `local` within `distance`, else zero.
  static Eigen::Vector3d continuedForce(std::span<const Remembered> points, const Eigen::Vector3d& local,
                                        double distance) {
    const Remembered* nearest = nullptr;
    double best = distance * distance;
    for (const Remembered& r : points)
      if (const double d = (r.local - local).squaredNorm(); d <= best) {
        best = d;
        nearest = &r;
      }
    return nearest ? nearest->force : Eigen::Vector3d::Zero();
  }

  // The rows of one pair's enabled points.
  template <class BodyIndex>
  void build(GeometryContactT<S>& contact, const MaterialManagerT<S>& materials, const GravityFieldT<S>& gravity,
             BodyIndex bodyIndex, const std::vector<SolverBody>& bodies, double h, const ContactSettings& settings,
             RowSet& set) {
    if (!solvable(contact)) return;
    std::vector<Row>& rows = set.rows;
    const ContactParametersT<S> p =
        materials.resolve(*contact.geometry(0)->getMaterial(), *contact.geometry(1)->getMaterial());
    const FrictionModelT<S>* model = p.frictionModel;
    const SolveType solveType = model ? model->getSolveType() : SolveType::SPLIT;
    const auto type = model ? model->getType() : FrictionModelT<S>::ITERATIVE_PROJECTED_CONE;
    FrictionBound bound = type == FrictionModelT<S>::BOX         ? FrictionBound::FIXED
                          : type == FrictionModelT<S>::SCALE_BOX ? FrictionBound::SCALED_BOX
                                                                 : FrictionBound::CONE;
    // The projected cone is round: anisotropic friction falls back to the scaled box.
    if (bound == FrictionBound::CONE && p.friction[0] != p.friction[1]) bound = FrictionBound::SCALED_BOX;

    RigidBodyT<S>* body[2] = {contact.rigidBody(0), contact.rigidBody(1)};
    const int index[2] = {body[0] ? bodyIndex(body[0]) : -1, body[1] ? bodyIndex(body[1]) : -1};
    Eigen::Vector3d cm[2], surface[2];
    for (int k = 0; k < 2; ++k) {
      const auto& geometry = *contact.geometry(static_cast<std::size_t>(k));
      cm[k] = body[k] ? Eigen::Vector3d(body[k]->getCmPosition().template cast<double>()) : Eigen::Vector3d::Zero();
      surface[k] =
          geometry.getSurfaceVelocity().isZero(S(0))
              ? Eigen::Vector3d::Zero()
              : Eigen::Vector3d(
                    (geometry.getTransform().linear() * geometry.getSurfaceVelocity()).template cast<double>());
    }
    const PairMemory* lastPair = findLastPair(pairKey(contact));
    const double normalEstimate = estimateNormalForce(contact, model, lastPair, gravity);
    const std::size_t numEnabled = std::max<std::size_t>(contact.getNumEnabledPoints(), 1);
    // Each point's share of the force the pair carried in the last step (N).
    const double lastShare = lastPair ? lastPair->normalForce / double(numEnabled) : 0.0;
    const Eigen::Isometry3d toFirstGeometry =
        Eigen::Isometry3d(contact.geometry(0)->getTransform().template cast<double>().matrix()).inverse();

    for (auto& point : contact.points()) {
      if (!point.enabled) continue;
      const Eigen::Vector3d n = point.normal.template cast<double>();
      const Eigen::Vector3d x = point.point.template cast<double>();
      const Eigen::Vector3d r1 = x - cm[0], r2 = x - cm[1];
      const auto velocityOf = [&](int k, const Eigen::Vector3d& r, bool free) -> Eigen::Vector3d {
        if (index[k] < 0) return Eigen::Vector3d::Zero();
        const SolverBody& b = bodies[static_cast<std::size_t>(index[k])];
        const Vec6d& v = free ? b.freeVelocity : b.velocity;
        return v.head<3>() + v.tail<3>().cross(r);
      };
      const auto makeRow = [&](const Eigen::Vector3d& direction) {
        Row row;
        row.body1 = index[0];
        row.body2 = index[1];
        row.J1 << -direction, -r1.cross(direction);
        row.J2 << direction, r2.cross(direction);
        row.solveType = solveType;
        return row;
      };
      const auto append = [&](const Row& row, double impulse) {
        set.arms.push_back({static_cast<int>(rows.size()), r1, r2});
        rows.push_back(row);
        set.impulses.push_back(impulse);
      };

      const Eigen::Vector3d local = toFirstGeometry * x;
      const Eigen::Vector3d lastForceOfPoint =
          lastPair
              ? continuedForce(std::span<const Remembered>(lastRemembered_).subspan(lastPair->first, lastPair->count),
                               local, settings.persistenceDistance)
              : Eigen::Vector3d::Zero();
      const int normalIndex = static_cast<int>(rows.size());
      Row normal = makeRow(n);
      normal.lower = -double(p.adhesiveForce);
      const double approach = n.dot(velocityOf(1, r2, false) - velocityOf(0, r1, false));
      const double gap = -double(point.depth);  // > 0 for a gap point
      const bool impact = p.restitution > S(0) && approach < -settings.restitutionThreshold &&
                          (gap <= 0.0 || n.dot(velocityOf(1, r2, true) - velocityOf(0, r1, true)) * h < -gap);
      if (impact) {
        normal.holonomic = false;
        normal.speed = -double(p.restitution) * approach;
        if (gap > 0.0) normal.lower = 0.0;
      } else if (gap > 0.0) {
        normal.holonomic = false;
        normal.speed = -gap / h;
        normal.lower = 0.0;
        normal.compliance = h * SpookParameters::holonomic(1.0 / double(p.youngsModulus), double(p.damping), h).sigma;
      } else {
        normal.compliance = 1.0 / double(p.youngsModulus);
        normal.damping = double(p.damping);
        // SPOOK's a·g is the speed at which the overlap is pushed out:
        // capped. The cap is on the push-out, not on the load: a point may
        // also be as deep as g = F·c, the spring's overlap under the force
        // F it carried in the last step (its own or its share of its
        // pair's; a light body's F·c is nanometres). A cap on g alone caps
        // the load a contact bears at g_cap/c: a 1e8 kg box sank through a
        // plane at 14 m/s.
        const SpookParameters spook = SpookParameters::holonomic(normal.compliance, normal.damping, h);
        const double carried = std::max({lastForceOfPoint.dot(n), lastShare, 0.0}) * normal.compliance;
        const double deepest = -(spook.violationForSpeed(settings.maxDepenetrationSpeed) + carried);
        normal.violation = std::max(double(p.adhesiveOverlap - point.depth), deepest);
      }
      append(normal, lastForceOfPoint.dot(n) * h);

      const Eigen::Vector3d slip = velocityOf(1, r2, true) + surface[1] - velocityOf(0, r1, true) - surface[0];
      const auto [t1, t2] = tangents(n, slip, model);
      const Eigen::Vector3d tangent[2] = {t1, t2};
      for (int k = 0; k < 2; ++k) {
        Row row = makeRow(tangent[k]);
        row.holonomic = false;
        row.speed = (surface[0] - surface[1]).dot(tangent[k]);
        row.compliance = double(p.surfaceViscosity[k]);
        const double mu = double(p.friction[k]);
        row.upper = bound == FrictionBound::FIXED && gap > 0.0 ? 0.0 : mu * normalEstimate / double(numEnabled);
        row.lower = -row.upper;
        set.friction.push_back({static_cast<int>(rows.size()), normalIndex,
                                bound == FrictionBound::CONE ? normalIndex + 2 - k : -1, mu, bound, false});
        append(row, lastForceOfPoint.dot(tangent[k]) * h);
      }
      points_.push_back({&point, pairKey(contact), local, n, t1, t2});
    }
  }

  static bool solvable(const GeometryContactT<S>& c) { return c.isEnabled() && !c.isSensor(); }
  static PairKey pairKey(const GeometryContactT<S>& c) { return {c.geometry(0), c.geometry(1)}; }

  // N for box friction: the user's, else the pair's normal force of the last
  // step, else the weight of the lighter dynamic body.
  double estimateNormalForce(const GeometryContactT<S>& contact, const FrictionModelT<S>* model,
                             const PairMemory* lastPair, const GravityFieldT<S>& gravity) const {
    if (model && model->getType() == FrictionModelT<S>::BOX) {
      const auto* box = static_cast<const BoxFrictionT<S>*>(model);
      if (box->hasNormalForceMagnitude()) return double(box->getNormalForceMagnitude());
    }
    if (lastPair && lastPair->normalForce > 0.0) return lastPair->normalForce;
    double weight = 0.0;
    for (std::size_t k = 0; k < 2; ++k) {
      const RigidBodyT<S>* body = contact.rigidBody(k);
      if (!body || body->getMotionControl() != RigidBodyT<S>::DYNAMICS) continue;
      const double w =
          double(body->getMassProperties()->getMass() * gravity.calculateGravity(body->getCmPosition()).norm());
      weight = weight > 0.0 ? std::min(weight, w) : w;
    }
    return weight;
  }

  // t1 along the primary direction when the model has one, else along the
  // slip (so that box friction opposes it), else any; t2 = n × t1.
  static std::pair<Eigen::Vector3d, Eigen::Vector3d> tangents(const Eigen::Vector3d& n, const Eigen::Vector3d& slip,
                                                              const FrictionModelT<S>* model) {
    Eigen::Vector3d t1 = Eigen::Vector3d::Zero();
    if (model && model->hasPrimaryDirection()) {
      const Eigen::Vector3d d = model->getPrimaryDirection().template cast<double>();
      t1 = d - d.dot(n) * n;
    }
    if (t1.norm() < 1e-6) t1 = slip - slip.dot(n) * n;
    if (t1.norm() < 1e-9) t1 = n.unitOrthogonal();
    t1.normalize();
    return {t1, n.cross(t1)};
  }

  std::vector<PointRows> points_;
  // The pairs of the step read back last, sorted, and their points; the
  // step's own (last*) while build() runs.
  std::vector<PairMemory> pairs_, lastPairs_;
  std::vector<Remembered> remembered_, lastRemembered_;
};

}  // namespace spook::detail
