#pragma once

// A wire's contacts with the geometries it touches (agxWire's dynamic
// contact model, PHYSICS.md §3.4): each straight segment is a capsule of the
// wire's radius between its two points, collided with every geometry of the
// simulation through the space's colliders, so that a segment cannot pass
// through an edge while both its points are outside. A contact point at
// t ∈ [0, 1] along the segment acts on its two points with weights 1 − t
// and t (the lumped model's interpolation): one unilateral normal row on
// the gap g = −depth with the contact material's compliance and damping,
// and two friction rows, along the wire and across it, within the cone of
// the wire material's friction coefficient (an explicit contact material
// between the wire's and the geometry's materials overrides it). Each row
// couples at most three bodies: the segment's two points and the geometry's
// body.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <functional>
#include <iterator>
#include <limits>
#include <span>
#include <vector>

#include <Eigen/Core>

#include <spook/collide/shapes/capsule.hpp>
#include <spook/collide/space.hpp>
#include <spook/core/math.hpp>
#include <spook/core/ref_ptr.hpp>
#include <spook/core/scalar.hpp>
#include <spook/sim/material_manager.hpp>
#include <spook/sim/simulation.hpp>
#include <spook/sim/step_extension.hpp>
#include <spook/solver/spook_parameters.hpp>
#include <spook/wire/wire_row_bodies.hpp>

namespace spook::detail {

template <Scalar S>
class WireGeometryContacts {
 public:
  using Vec3d = Eigen::Vector3d;
  using Geometry = GeometryT<S>;
  using Body = RigidBodyT<S>;

  /// A straight segment of the wire as the step starts: its ends (world, m),
  /// their solver indices (−1: the world) and lever arms from their bodies'
  /// centers of mass, and where it starts along the wire (m of rest length)
  /// and its rest length, which identify a contact from step to step.
  struct Segment {
    Vec3d a, b;
    int indexA = -1, indexB = -1;
    Vec3d armA = Vec3d::Zero(), armB = Vec3d::Zero();
    double start = 0.0, rest = 0.0;
    /// Whether the cap at a is also the end cap of the segment before (its
    /// points there are that segment's).
    bool sharedStart = false;
  };

  /// A contact after the step's solve (world, N and m).
  struct Point {
    const Geometry* geometry = nullptr;
    Vec3d point = Vec3d::Zero();
    Vec3d normal = Vec3d::Zero();  ///< from the wire toward the geometry
    double depth = 0.0;
    double distance = 0.0;          ///< along the wire from its start (m of rest length)
    Vec3d force = Vec3d::Zero();    ///< on the geometry
  };

  /// Finds the contacts of `segments` with the simulation's geometries
  /// (those `touches` accepts) and appends their rows; `wireMaterial` is
  /// the wire's material.
  /// Shapes closer than `margin` (m) count as in contact, with a gap that
  /// the normal row lets close within the step (a speculative contact):
  /// else a wire lifted off a geometry by a hair in one step has no row in
  /// the next, and its tension pulls its nodes into the geometry.
  template <class Accept>
  void writeRows(RowWriter& rows, const StepContext& step, std::span<const Segment> segments, double radius,
                 double margin, const MaterialT<S>& wireMaterial, double persistence,
                 Accept touches) {
    points_.clear();
    found_.clear();
    tangents_.clear();
    rowsWritten_ = 0;
    last_.swap(remembered_);
    remembered_.clear();
    const SimulationT<S>* simulation = step.getSimulation<S>();
    if (!simulation || segments.empty()) return;
    Vec3d low = Vec3d::Constant(std::numeric_limits<double>::infinity()), high = -low;
    for (const Segment& s : segments) {
      low = low.cwiseMin(s.a).cwiseMin(s.b);
      high = high.cwiseMax(s.a).cwiseMax(s.b);
    }
    if (!(low.allFinite() && high.allFinite())) return;
    low.array() -= radius + margin;
    high.array() += radius + margin;
    const SpaceT<S>& space = *simulation->getSpace();
    const auto visit = [&](const Geometry& geometry) {
      if (!geometry.getEnable() || !geometry.getEnableCollisions() || geometry.isSensor() || !touches(geometry)) return;
      const BoundingBoxT<S> box = geometry.getBoundingBox();
      const Vec3d boxLow = box.min.template cast<double>(), boxHigh = box.max.template cast<double>();
      if ((boxLow.array() > high.array()).any() || (boxHigh.array() < low.array()).any()) return;
      collideWith(geometry, boxLow, boxHigh, segments, radius, margin, *simulation);
    };
    for (const auto& geometry : space.getGeometries()) visit(*geometry);
    for (const auto& body : simulation->getRigidBodies())
      if (body->getEnable())
        for (const auto& geometry : body->getGeometries()) visit(*geometry);
    if (found_.empty()) return;

    const double h = step.getTimeStep();
    const MaterialManagerT<S>& materials = *simulation->getMaterialManager();
    // found_ holds each geometry's points together: its parameters once.
    const Geometry* resolved = nullptr;
    ContactParametersT<S> p{};
    double mu = 0.0;
    for (const Found& f : found_) {
      const Segment& s = segments[f.segment];
      const Geometry& geometry = *f.geometry;
      if (resolved != &geometry) {
        resolved = &geometry;
        p = materials.resolve(wireMaterial, *geometry.getMaterial());
        mu = materials.getContactMaterial(&wireMaterial, geometry.getMaterial())
                 ? double(p.friction[0])
                 : double(wireMaterial.getWireMaterial()->getFrictionCoefficient());
      }
      const Body* body = geometry.getRigidBody();
      const int bodyIndex = body ? step.indexOf(*body) : -1;
      const Vec3d arm = body ? Vec3d(f.point - body->getCmPosition().template cast<double>()) : Vec3d::Zero();
      const Vec3d& n = f.normal;
      // Along the wire (its slide over the geometry) and across it.
      const Vec3d along = s.b - s.a;
      Vec3d t1 = along - n * n.dot(along);
      t1 = t1.norm() > 1e-12 * (1.0 + along.norm()) ? Vec3d(t1.normalized()) : Vec3d(n.unitOrthogonal());
      const Vec3d t2 = n.cross(t1);
      const double distance = s.start + f.t * s.rest;
      const Remembered* was = continued(geometry, distance, persistence);
      const auto write = [&](const Vec3d& direction, double impulse) -> Row& {
        WireRowBodies bodies;
        bodies.add(s.indexA, -(1.0 - f.t) * direction, s.armA);
        bodies.add(s.indexB, -f.t * direction, s.armB);
        bodies.add(bodyIndex, direction, arm);
        Row& row = rows.add(impulse);
        bodies.write(rows, row);
        return row;
      };
      const std::size_t normal = rows.size();
      Row& n0 = write(n, was ? was->impulse[0] : 0.0);
      n0.lower = 0.0;
      n0.compliance = 1.0 / double(p.youngsModulus);
      n0.damping = double(p.damping);
      const SpookParameters spook = SpookParameters::holonomic(n0.compliance, n0.damping, h);
      n0.violation = std::max(-f.depth, -spook.violationForSpeed(1.0));  // a gap when > 0
      for (int k = 0; k < 2; ++k) {
        Row& row = write(k == 0 ? t1 : t2, was ? was->impulse[1 + k] : 0.0);
        row.holonomic = false;
        row.speed = 0.0;
        row.compliance = double(p.surfaceViscosity[std::size_t(k)]);
        rows.setFriction(rows.size() - 1, normal, mu, FrictionBound::CONE, int(normal) + (k == 0 ? 2 : 1));
      }
      rowsWritten_ += 3;
      Point point;
      point.geometry = &geometry;
      point.point = f.point;
      point.normal = n;
      point.depth = f.depth;
      point.distance = distance;
      points_.push_back(point);
      tangents_.push_back({t1, t2});
    }
  }

  /// The impulses of the rows writeRows appended (in order).
  void readBack(std::span<const double> impulses, double h) {
    touched_.clear();
    for (std::size_t i = 0; i < points_.size(); ++i) {
      const double* impulse = &impulses[3 * i];
      Point& p = points_[i];
      p.force = (impulse[0] * p.normal + impulse[1] * tangents_[i][0] + impulse[2] * tangents_[i][1]) / h;
      // (A distance that is not finite could match nothing, and would break the sort.)
      if (std::isfinite(p.distance))
        remembered_.push_back({p.geometry, p.distance, {impulse[0], impulse[1], impulse[2]}});
      if (touching(p)) touched_.push_back(p.distance);
    }
    std::sort(touched_.begin(), touched_.end());
    std::sort(remembered_.begin(), remembered_.end(), Remembered::before);
  }

  /// Whether the wire touched a geometry in the last step strictly between
  /// `from` and `to` (m of rest length from its start).
  [[nodiscard]] bool touchedBetween(double from, double to) const {
    const auto first = std::upper_bound(touched_.begin(), touched_.end(), from);
    return first != touched_.end() && *first < to;
  }
  /// A point that touched (within the collider's touching gap) or pushed.
  [[nodiscard]] static bool touching(const Point& p) { return p.depth >= 0.0 || p.force.squaredNorm() > 0.0; }
  [[nodiscard]] std::size_t rowsWritten() const { return rowsWritten_; }
  [[nodiscard]] const std::vector<Point>& points() const { return points_; }
  void clear() {
    points_.clear();
    touched_.clear();
    remembered_.clear();
    rowsWritten_ = 0;
  }

 private:
  struct Found {
    const Geometry* geometry;
    std::size_t segment;
    double t;
    Vec3d point, normal;
    double depth;
  };
  struct Remembered {
    const Geometry* geometry;
    double distance;
    double impulse[3];
    /// By geometry, then distance along the wire.
    static bool before(const Remembered& a, const Remembered& b) {
      return std::less<const Geometry*>()(a.geometry, b.geometry) ||
             (a.geometry == b.geometry && a.distance < b.distance);
    }
  };

  // The last step's contact on `geometry` nearest along the wire, within
  // `persistence` (m): last_ is sorted by geometry, then distance.
  const Remembered* continued(const Geometry& geometry, double distance, double persistence) const {
    const auto next =
        std::lower_bound(last_.begin(), last_.end(), Remembered{&geometry, distance, {}}, Remembered::before);
    const Remembered* nearest = nullptr;
    double best = persistence;
    for (auto it = next; it != last_.end() && it->geometry == &geometry && it->distance - distance <= best; ++it)
      if (const double d = std::abs(it->distance - distance); d <= best) {
        best = d;
        nearest = &*it;
      }
    for (auto it = next; it != last_.begin() && std::prev(it)->geometry == &geometry;) {
      --it;
      if (const double d = distance - it->distance; d <= best) {
        best = d;
        nearest = &*it;
      } else {
        break;
      }
    }
    return nearest;
  }

  void collideWith(const Geometry& geometry, const Vec3d& boxLow, const Vec3d& boxHigh,
                   std::span<const Segment> segments, double wireRadius, double margin,
                   const SimulationT<S>& simulation) {
    const double radius = wireRadius + margin;
    const SpaceT<S>& space = *simulation.getSpace();
    const TransformT<S> X_WG = geometry.getTransform();
    for (std::size_t k = 0; k < segments.size(); ++k) {
      const Segment& s = segments[k];
      const Vec3d low = s.a.cwiseMin(s.b).array() - radius, high = s.a.cwiseMax(s.b).array() + radius;
      if ((boxLow.array() > high.array()).any() || (boxHigh.array() < low.array()).any()) continue;
      const Vec3d d = s.b - s.a;
      const double length = d.norm();
      // Beyond the scalar's range (float), the capsule has no placement.
      if (!(std::isfinite(S(length)) && (S(0.5) * (s.a + s.b).template cast<S>()).allFinite())) continue;
      // The capsule's axis is its y axis.
      if (!capsule_) capsule_ = new CapsuleT<S>(S(radius), S(1));
      if (capsule_->getRadius() != S(radius)) capsule_->setRadius(S(radius));
      const S height = std::max(S(length), S(1e-6) * S(radius));
      if (capsule_->getHeight() != height) capsule_->setHeight(height);
      const Vec3d y = length > 0.0 ? Vec3d(d / length) : Vec3d::UnitY();
      const QuatT<double> q = detail::shortestArc<double>(Vec3d::UnitY(), y);
      TransformT<S> X_WC = TransformT<S>::Identity();
      X_WC.linear() = q.toRotationMatrix().template cast<S>();
      X_WC.translation() = (0.5 * (s.a + s.b)).template cast<S>();
      scratch_.clear();
      ContactSinkT<S> sink(scratch_);
      for (const auto& entry : geometry.getShapes())
        space.collideShapes(*capsule_, X_WC, *entry.shape, X_WG * entry.transform, sink);
      for (const ContactPointT<S>& c : scratch_) {
        const Vec3d x = c.point.template cast<double>(), n = c.normal.template cast<double>();
        const double t = length > 0.0 ? std::clamp((x - s.a).dot(d) / (length * length), 0.0, 1.0) : 0.0;
        // The shared cap belongs to the segment before.
        if (s.sharedStart && t <= 0.0) continue;
        if (!(x.allFinite() && n.allFinite() && std::abs(n.norm() - 1.0) < 1e-3)) continue;
        found_.push_back({&geometry, k, t, x, n, double(c.depth) - margin});
      }
    }
  }

  std::vector<Found> found_;
  std::vector<Point> points_;
  std::vector<double> touched_;  ///< distances of the points that touched, ascending
  std::vector<std::array<Vec3d, 2>> tangents_;
  std::vector<Remembered> remembered_, last_;
  std::vector<ContactPointT<S>> scratch_;
  ref_ptr<CapsuleT<S>> capsule_;
  std::size_t rowsWritten_ = 0;
};

}  // namespace spook::detail
