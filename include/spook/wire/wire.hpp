#pragma once

// A wire (agxWire's Wire; PHYSICS.md §3): lumped mass nodes at the wire's
// resolution joined by stretch rows and, over each three consecutive
// points, bend rows, with compliances from its material's wire moduli. It is
// routed with nodes (wire/wire_node.hpp) before it joins a simulation:
//
//   ref_ptr<Wire> wire = new Wire(0.02, 2.0);  // radius 2 cm, 2 nodes per meter
//   wire->add(new BodyFixedNode(nullptr, Vec3(0, 0, 10)));  // fixed to the world
//   wire->add(new FreeNode(0, 0, 5));                       // a free end
//   simulation->add(wire);
//
// Its length is that of the route. A row producer (sim/step_extension.hpp)
// that owns its node store: the simulation adds and removes both together.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include <spook/core/error.hpp>
#include <spook/core/implementation.hpp>
#include <spook/core/math.hpp>
#include <spook/core/ref_ptr.hpp>
#include <spook/core/scalar.hpp>
#include <spook/dynamics/material.hpp>
#include <spook/dynamics/rigid_body.hpp>
#include <spook/sim/step_extension.hpp>
#include <spook/wire/wire_node.hpp>
#include <spook/wire/wire_nodes.hpp>

namespace spook {

template <Scalar S>
class WireT : public RowProducer {
 public:
  using Vec3 = Vec3T<S>;
  using Node = WireNodeT<S>;
  using Material = MaterialT<S>;
  using Body = RigidBodyT<S>;

  /// A wire of `radius` (m) and `resolution` lumped nodes per meter, both
  /// finite and > 0, made of `material` (a material of its own, named
  /// "wire", when nullptr).
  WireT(S radius, S resolutionPerUnitLength, ref_ptr<Material> material = nullptr);

  /// Appends a node to the route, before the wire is added to a simulation.
  void add(ref_ptr<Node> node);
  /// The route as given.
  [[nodiscard]] const std::vector<ref_ptr<Node>>& getRoute() const { return route_; }

  /// Radius (m); setting it changes the wire's mass and stiffness.
  [[nodiscard]] S getRadius() const { return S(radius_); }
  void setRadius(S radius);
  /// Lumped nodes per meter of the route.
  [[nodiscard]] S getResolutionPerUnitLength() const { return S(resolution_); }
  [[nodiscard]] Material* getMaterial() const { return material_.get(); }
  /// Changes the material; its density sets the mass of a wire already
  /// routed into a simulation.
  void setMaterial(ref_ptr<Material> material);

  /// Total unstretched length (m): the length of the route.
  [[nodiscard]] S getRestLength() const;
  /// Length along the current points (m).
  [[nodiscard]] S getCurrentLength() const;
  /// Mass (kg): density × πr² × rest length.
  [[nodiscard]] S getMass() const;
  /// Tension (N, > 0 pulling) at `distance` (m of rest length) from the
  /// start, that of the segment there in the last step; 0 before any step.
  [[nodiscard]] S getTension(S distanceFromStart) const;
  /// The wire's points from its start to its end (world, m): attached ends
  /// and lumped nodes, for rendering and inspection. Empty until the wire
  /// joins a simulation.
  [[nodiscard]] std::vector<Vec3> getPoints() const;
  /// Number of lumped mass nodes (0 until the wire joins a simulation).
  [[nodiscard]] std::size_t getNumMassNodes() const { return nodes_->size(); }

  // RowProducer.
  void prepare(const StepContext& simulation) override;
  [[nodiscard]] BodyStore* getOwnedStore() override { return nodes_.get(); }
  void beginStep(const StepContext& step) override;
  void writeRows(RowWriter& rows, const StepContext& step) override;
  void readBack(std::span<const double> impulses, const StepContext& step) override;

 protected:
  ~WireT() override = default;

 private:
  using Vec3d = Eigen::Vector3d;
  /// A point of the built wire: a lumped node, or an end fixed to a body or
  /// the world at `local` (the body's model frame, or world).
  struct Point {
    int node = -1;
    Body* body = nullptr;
    Vec3d local = Vec3d::Zero();
  };

  template <class T>
  [[nodiscard]] Error error(const char* what, const T& value) const {
    return detail::makeError("Wire", getName(), what, value);
  }
  [[nodiscard]] Error error(const char* what) const { return detail::makeError("Wire", getName(), what); }
  [[nodiscard]] bool built() const { return !points_.empty(); }
  void checkRoute(const StepContext& simulation) const;
  void build();
  void updateMasses();
  /// Adaptive resolution (beginStep): nodes the step cannot resolve leave,
  /// and return where the tension allows.
  void removeNode(std::size_t point);
  void splitSegment(std::size_t segment);
  void renumberNodes();
  [[nodiscard]] double linearDensity() const;
  [[nodiscard]] Vec3d worldPosition(const Point& p) const;
  [[nodiscard]] Vec3d worldVelocity(const Point& p) const;

  double radius_;
  double resolution_;
  ref_ptr<Material> material_;
  std::vector<ref_ptr<Node>> route_;
  ref_ptr<detail::WireNodes> nodes_ = new detail::WireNodes();
  std::vector<Point> points_;
  std::vector<double> restLengths_;    ///< per segment (points_[k], points_[k+1])
  std::vector<double> stretchImpulse_;  ///< per segment, last step (N·s)
  std::vector<double> bendImpulse_;     ///< two per inner point, last step (N·s)
  std::vector<char> bent_;              ///< per point: its bend rows were written this step
  std::vector<double> tension_;         ///< per segment (N)
};

template <Scalar S>
WireT<S>::WireT(S radius, S resolutionPerUnitLength, ref_ptr<Material> material)
    : radius_(double(radius)), resolution_(double(resolutionPerUnitLength)),
      material_(material ? std::move(material) : ref_ptr<Material>(new Material("wire"))) {
  if (!(std::isfinite(radius) && radius > S(0))) throw error("radius must be finite and > 0 m", radius);
  if (!(std::isfinite(resolutionPerUnitLength) && resolutionPerUnitLength > S(0)))
    throw error("resolution must be finite and > 0 nodes per m", resolutionPerUnitLength);
}

template <Scalar S>
void WireT<S>::add(ref_ptr<Node> node) {
  if (!node) throw error("cannot route a null node", "nullptr");
  if (built()) throw error("is in a simulation: its route is fixed", route_.size());
  route_.push_back(std::move(node));
}

template <Scalar S>
void WireT<S>::setRadius(S radius) {
  if (!(std::isfinite(radius) && radius > S(0))) throw error("radius must be finite and > 0 m", radius);
  radius_ = double(radius);
  updateMasses();
}

template <Scalar S>
void WireT<S>::setMaterial(ref_ptr<Material> material) {
  if (!material) throw error("cannot use a null material", "nullptr");
  material_ = std::move(material);
  updateMasses();
}

template <Scalar S>
double WireT<S>::linearDensity() const {
  return double(material_->getBulkMaterial()->getDensity()) * std::numbers::pi * radius_ * radius_;
}

template <Scalar S>
S WireT<S>::getRestLength() const {
  double length = 0.0;
  if (built()) {
    for (double l : restLengths_) length += l;
  } else {
    for (std::size_t k = 0; k + 1 < route_.size(); ++k)
      length += (route_[k + 1]->getWorldPosition() - route_[k]->getWorldPosition()).template cast<double>().norm();
  }
  return S(length);
}

template <Scalar S>
S WireT<S>::getCurrentLength() const {
  double length = 0.0;
  for (std::size_t k = 0; k + 1 < points_.size(); ++k)
    length += (worldPosition(points_[k + 1]) - worldPosition(points_[k])).norm();
  return built() ? S(length) : getRestLength();
}

template <Scalar S>
S WireT<S>::getMass() const {
  return S(linearDensity() * double(getRestLength()));
}

template <Scalar S>
S WireT<S>::getTension(S distanceFromStart) const {
  if (tension_.empty()) return S(0);
  double along = double(distanceFromStart);
  std::size_t k = 0;
  while (k + 1 < tension_.size() && along > restLengths_[k]) along -= restLengths_[k++];
  return S(tension_[k]);
}

template <Scalar S>
auto WireT<S>::getPoints() const -> std::vector<Vec3> {
  std::vector<Vec3> points;
  points.reserve(points_.size());
  for (const Point& p : points_) points.push_back(worldPosition(p).template cast<S>());
  return points;
}

template <Scalar S>
auto WireT<S>::worldPosition(const Point& p) const -> Vec3d {
  if (p.node >= 0) return nodes_->position(std::size_t(p.node));
  if (p.body) return p.body->getFrame()->transformPointToWorld(p.local.template cast<S>()).template cast<double>();
  return p.local;
}

template <Scalar S>
auto WireT<S>::worldVelocity(const Point& p) const -> Vec3d {
  if (p.node >= 0) return nodes_->velocity(std::size_t(p.node));
  if (p.body) return p.body->getVelocityAtPoint(worldPosition(p).template cast<S>()).template cast<double>();
  return Vec3d::Zero();
}

template <Scalar S>
void WireT<S>::checkRoute(const StepContext& simulation) const {
  if (route_.size() < 2) throw error("needs at least two route nodes", route_.size());
  for (std::size_t k = 0; k < route_.size(); ++k) {
    const Node& node = *route_[k];
    if (node.getType() == Node::Type::BODY_FIXED && k != 0 && k + 1 != route_.size())
      throw error("a BodyFixedNode may only be the first or last route node; it is node", k);
    if (node.getRigidBody() && simulation.indexOf(*node.getRigidBody()) < 0)
      throw error(("route node " + std::to_string(k) + " is fixed to a body not in the simulation").c_str(),
                  node.getRigidBody()->getName());
    if (k > 0 && !((node.getWorldPosition() - route_[k - 1]->getWorldPosition()).norm() > S(0)))
      throw error("consecutive route nodes coincide at", node.getWorldPosition());
  }
  // Hostile resolutions would allocate without bound.
  const double nodes = double(getRestLength()) * resolution_ + double(route_.size());
  if (!(nodes <= 1e6)) throw error("would have more than 1e6 lumped nodes (length x resolution)", nodes);
}

template <Scalar S>
void WireT<S>::prepare(const StepContext& simulation) {
  checkRoute(simulation);
  if (!built()) build();
}

template <Scalar S>
void WireT<S>::build() {
  const auto endPoint = [&](const Node& node) {
    Point p;
    if (node.getType() == Node::Type::BODY_FIXED) {
      p.body = node.getRigidBody();
      p.local = node.getPosition().template cast<double>();
    } else {
      p.node = int(nodes_->add(node.getWorldPosition().template cast<double>(), 0.0));
    }
    return p;
  };
  points_.push_back(endPoint(*route_.front()));
  for (std::size_t k = 0; k + 1 < route_.size(); ++k) {
    const Vec3d a = route_[k]->getWorldPosition().template cast<double>();
    const Vec3d b = route_[k + 1]->getWorldPosition().template cast<double>();
    const double length = (b - a).norm();
    const int segments = std::max(1, int(std::ceil(length * resolution_ - 1e-9)));
    for (int i = 1; i < segments; ++i) {
      Point p;
      p.node = int(nodes_->add(a + (b - a) * (double(i) / segments), 0.0));
      points_.push_back(p);
    }
    for (int i = 0; i < segments; ++i) restLengths_.push_back(length / segments);
    if (k + 2 < route_.size()) {
      Point p;
      p.node = int(nodes_->add(b, 0.0));
      points_.push_back(p);
    } else {
      points_.push_back(endPoint(*route_.back()));
    }
  }
  stretchImpulse_.assign(restLengths_.size(), 0.0);
  bendImpulse_.assign(2 * points_.size(), 0.0);
  bent_.assign(points_.size(), 0);
  tension_.assign(restLengths_.size(), 0.0);
  updateMasses();
}

// A lumped node carries half of each segment beside it (ends fixed to a body
// or the world carry theirs into it).
template <Scalar S>
void WireT<S>::updateMasses() {
  if (!built()) return;
  const double density = linearDensity();
  for (std::size_t k = 0; k < points_.size(); ++k) {
    if (points_[k].node < 0) continue;
    double length = 0.0;
    if (k > 0) length += 0.5 * restLengths_[k - 1];
    if (k < restLengths_.size()) length += 0.5 * restLengths_[k];
    nodes_->setMass(std::size_t(points_[k].node), density * length);
  }
}

// Adaptive resolution (agxWire's dynamic resolution; PHYSICS.md §3.3). A
// node of mass m between segments of length L under tension T is a
// transverse spring the velocity-level step integrates explicitly (the
// stretch rows turn with the geometry of the step's start); the wire's
// fastest mode, the zig-zag, has ω² = 4T/(L m), unstable once h²ω² > 4.
// A node with ρ = h²(T₁/L₁ + T₂/L₂)/m > 2 (that zig-zag bound) leaves: its
// two segments merge (rest lengths add), its mass and momentum go to its
// neighbours. A segment longer than the wire's resolution asks for splits
// again where the node it would gain has ρ < 1 (hysteresis). The
// geometric-stiffness rows of writeRows hold what is left over (a node that
// cannot leave: next to both ends, or a tension that jumps within a step).
template <Scalar S>
void WireT<S>::beginStep(const StepContext& step) {
  if (points_.size() < 2) return;
  const double h2 = step.getTimeStep() * step.getTimeStep();
  const auto span = [&](std::size_t segment) {
    return (worldPosition(points_[segment + 1]) - worldPosition(points_[segment])).norm();
  };
  const auto pull = [&](std::size_t segment) {
    const double length = span(segment);
    return length > 0.0 ? std::max(tension_[segment], 0.0) / length : 0.0;
  };
  bool changed = false;
  for (std::size_t k = 1; k + 1 < points_.size(); ++k) {
    const Point& p = points_[k];
    if (p.node < 0) continue;
    const double rho = h2 * (pull(k - 1) + pull(k)) / nodes_->mass(std::size_t(p.node));
    if (rho > 2.0) {
      removeNode(k);
      changed = true;
    }
  }
  const double target = 1.0 / resolution_, density = linearDensity();
  for (std::size_t k = 0; k + 1 < points_.size(); ++k) {
    if (restLengths_[k] < 1.999 * target) continue;
    // The node a split would add: mass ρ_l r/2, between halves of L/2.
    const double rho = h2 * 4.0 * pull(k) / (density * restLengths_[k] / 2.0);
    if (rho < 1.0) {
      splitSegment(k);
      changed = true;
      ++k;
    }
  }
  if (changed) updateMasses();
}

template <Scalar S>
void WireT<S>::removeNode(std::size_t k) {
  const std::size_t node = std::size_t(points_[k].node);
  const double mass = nodes_->mass(node);
  const Vec3d momentum = 0.5 * mass * nodes_->velocity(node);
  for (const std::size_t other : {k - 1, k + 1}) {
    if (points_[other].node < 0) continue;  // a body's or the world's end: that half is lost
    const std::size_t n = std::size_t(points_[other].node);
    nodes_->setVelocity(n, (nodes_->mass(n) * nodes_->velocity(n) + momentum) / (nodes_->mass(n) + 0.5 * mass));
    nodes_->setMass(n, nodes_->mass(n) + 0.5 * mass);
  }
  restLengths_[k - 1] += restLengths_[k];
  stretchImpulse_[k - 1] = 0.5 * (stretchImpulse_[k - 1] + stretchImpulse_[k]);
  tension_[k - 1] = 0.5 * (tension_[k - 1] + tension_[k]);
  restLengths_.erase(restLengths_.begin() + std::ptrdiff_t(k));
  stretchImpulse_.erase(stretchImpulse_.begin() + std::ptrdiff_t(k));
  tension_.erase(tension_.begin() + std::ptrdiff_t(k));
  bendImpulse_.erase(bendImpulse_.begin() + std::ptrdiff_t(2 * k), bendImpulse_.begin() + std::ptrdiff_t(2 * k + 2));
  bent_.erase(bent_.begin() + std::ptrdiff_t(k));
  nodes_->erase(node);
  points_.erase(points_.begin() + std::ptrdiff_t(k));
  renumberNodes();
}

template <Scalar S>
void WireT<S>::splitSegment(std::size_t k) {
  std::size_t node = 0;  // the new node's index: the mass nodes before it
  for (std::size_t i = 0; i <= k; ++i) node += points_[i].node >= 0 ? 1 : 0;
  const Vec3d position = 0.5 * (worldPosition(points_[k]) + worldPosition(points_[k + 1]));
  const Vec3d velocity = 0.5 * (worldVelocity(points_[k]) + worldVelocity(points_[k + 1]));
  nodes_->insert(node, position, velocity, 0.0);
  Point p;
  p.node = int(node);
  points_.insert(points_.begin() + std::ptrdiff_t(k + 1), p);
  restLengths_[k] *= 0.5;
  restLengths_.insert(restLengths_.begin() + std::ptrdiff_t(k + 1), restLengths_[k]);
  stretchImpulse_.insert(stretchImpulse_.begin() + std::ptrdiff_t(k + 1), stretchImpulse_[k]);
  tension_.insert(tension_.begin() + std::ptrdiff_t(k + 1), tension_[k]);
  bendImpulse_.insert(bendImpulse_.begin() + std::ptrdiff_t(2 * (k + 1)), 2, 0.0);
  bent_.insert(bent_.begin() + std::ptrdiff_t(k + 1), 0);
  renumberNodes();
}

template <Scalar S>
void WireT<S>::renumberNodes() {
  int next = 0;
  for (Point& p : points_)
    if (p.node >= 0) p.node = next++;
}

namespace detail {
/// Up to three (body, Jacobian block) terms of one row, merged per body: a
/// point on a body contributes (a, r × a) for a world direction a at lever
/// arm r; the world contributes nothing.
struct WireRowBodies {
  int index[3] = {-1, -1, -1};
  Vec6d J[3] = {Vec6d::Zero(), Vec6d::Zero(), Vec6d::Zero()};
  int count = 0;
  void add(int body, const Eigen::Vector3d& a, const Eigen::Vector3d& arm) {
    if (body < 0) return;
    int k = 0;
    while (k < count && index[k] != body) ++k;
    if (k == count) index[count++] = body;
    J[k].head<3>() += a;
    J[k].tail<3>() += arm.cross(a);
  }
  void write(RowWriter& rows, Row& row) const {
    row.body1 = index[0];
    row.J1 = J[0];
    row.body2 = index[1];
    row.J2 = J[1];
    if (count == 3) rows.setThirdBody(rows.size() - 1, index[2], J[2]);
  }
};
}  // namespace detail

template <Scalar S>
void WireT<S>::writeRows(RowWriter& rows, const StepContext& step) {
  const std::size_t n = points_.size();
  std::vector<Vec3d> x(n), arm(n), v(n), centripetal(n);
  std::vector<int> index(n);
  for (std::size_t k = 0; k < n; ++k) {
    const Point& p = points_[k];
    x[k] = worldPosition(p);
    v[k] = worldVelocity(p);
    arm[k].setZero();
    centripetal[k].setZero();
    if (p.node >= 0) {
      index[k] = step.indexOf(*nodes_, std::size_t(p.node));
    } else if (p.body) {
      index[k] = step.indexOf(*p.body);
      if (index[k] < 0) throw error("is fixed to a body that left the simulation", p.body->getName());
      arm[k] = x[k] - p.body->getCmPosition().template cast<double>();
      const Vec3d w = p.body->getAngularVelocity().template cast<double>();
      centripetal[k] = w.cross(w.cross(arm[k]));
    } else {
      index[k] = -1;
    }
  }
  const typename Material::WireMaterial& wire = *material_->getWireMaterial();
  const double area = std::numbers::pi * radius_ * radius_;
  const double stretchStiffness = double(wire.getYoungsModulusStretch()) * area;
  for (std::size_t k = 0; k + 1 < n; ++k) {
    const Vec3d d = x[k + 1] - x[k];
    const double length = d.norm();
    const Vec3d u = length > 0.0 ? Vec3d(d / length) : Vec3d::UnitX();
    detail::WireRowBodies bodies;
    bodies.add(index[k], -u, arm[k]);
    bodies.add(index[k + 1], u, arm[k + 1]);
    detail::Row& r = rows.add(stretchImpulse_[k]);
    bodies.write(rows, r);
    r.violation = length - restLengths_[k];
    r.compliance = restLengths_[k] / stretchStiffness;
    r.damping = double(wire.getDampingStretch());
    // κ = ½vᵀ∇²g v = ½(|ḋ⊥|²/|d| + u·(p̈_b − p̈_a)) with the body points'
    // centripetal accelerations ω×(ω×r) (SecondOrder::curvature): a segment
    // turning at speed lengthens at second order, which the step then holds.
    if (length > 0.0) {
      const Vec3d rate = v[k + 1] - v[k];
      const Vec3d across = rate - u * u.dot(rate);
      const double relative = u.dot(centripetal[k + 1] - centripetal[k]);
      rows.setCurvature(rows.size() - 1, 0.5 * (across.squaredNorm() / length + relative));
    }
  }
  // Bend: g = e·(t₂ − t₁) for the two directions e across the mean tangent;
  // ½(EI/l̄)|t₂ − t₁|² is the bending energy of the turn (curvature |t₂ − t₁|/l̄
  // over the length l̄), so the compliance is l̄/(E I).
  const double bendStiffness = double(wire.getYoungsModulusBend()) * std::numbers::pi * std::pow(radius_, 4) / 4.0;
  for (std::size_t k = 1; k + 1 < n; ++k) {
    const Vec3d d1 = x[k] - x[k - 1], d2 = x[k + 1] - x[k];
    const double l1 = d1.norm(), l2 = d2.norm();
    bent_[k] = bendStiffness > 0.0 && l1 > 0.0 && l2 > 0.0;
    if (!bent_[k]) continue;
    const Vec3d t1 = d1 / l1, t2 = d2 / l2;
    const Vec3d mean = t1 + t2;
    const Vec3d axis = mean.norm() > 1e-6 ? Vec3d(mean.normalized()) : t1;
    const Vec3d turn = (t2 - t1) - axis * axis.dot(t2 - t1);
    const Vec3d across[2] = {turn.norm() > 1e-9 ? Vec3d(turn.normalized()) : Vec3d(axis.unitOrthogonal()),
                             Vec3d::Zero()};
    const Vec3d across2 = axis.cross(across[0]);
    const double compliance = 0.5 * (restLengths_[k - 1] + restLengths_[k]) / bendStiffness;
    for (int i = 0; i < 2; ++i) {
      const Vec3d e = i == 0 ? across[0] : across2;
      const Vec3d a0 = (e - t1 * t1.dot(e)) / l1, a2 = (e - t2 * t2.dot(e)) / l2;
      detail::WireRowBodies bodies;
      bodies.add(index[k], -(a0 + a2), arm[k]);
      bodies.add(index[k - 1], a0, arm[k - 1]);
      bodies.add(index[k + 1], a2, arm[k + 1]);
      detail::Row& r = rows.add(bendImpulse_[2 * k + std::size_t(i)]);
      bodies.write(rows, r);
      r.violation = e.dot(t2 - t1);
      r.compliance = compliance;
      r.damping = double(wire.getDampingBend());
    }
  }
  // Geometric stiffness (Tournier et al., SIGGRAPH 2015; Andrews et al.
  // 2017): a segment under tension T resists its ends' motion across it
  // with stiffness K = (T/L)(I − uuᵀ). The stretch row turns with the step's
  // start geometry, which integrates that stiffness explicitly: unstable
  // once h²K/m passes ~1, for nodes that beginStep could not remove. Its
  // implicit part −h²K v⁺ is two velocity rows across the segment, target
  // 0, viscosity L/(hT) (row.hpp: force −G v⁺/γ), from last step's tension: backward Euler in
  // the geometry, which damps only the ends' relative motion across the
  // segment. Weighted by max(0, 1 − 1/ρ), ρ = h²(T/L)(1/m_a + 1/m_b), as
  // solver/geometric_stiffness.hpp does for rigid bodies: a segment the
  // explicit step resolves keeps its undamped dynamics.
  const double h = step.getTimeStep();
  const auto inverseMass = [&](const Point& p) {
    if (p.node >= 0) return 1.0 / nodes_->mass(std::size_t(p.node));
    if (p.body && p.body->getMotionControl() == Body::MotionControl::DYNAMICS)
      return 1.0 / double(p.body->getMassProperties()->getMass());
    return 0.0;
  };
  for (std::size_t k = 0; k + 1 < n; ++k) {
    const Vec3d d = x[k + 1] - x[k];
    const double length = d.norm(), tension = tension_[k];
    if (!(length > 0.0 && tension > 0.0)) continue;
    const double rho = h * h * tension / length * (inverseMass(points_[k]) + inverseMass(points_[k + 1]));
    if (!(rho > 1.0)) continue;
    const double weight = 1.0 - 1.0 / rho;
    const Vec3d u = d / length, e1 = u.unitOrthogonal(), e2 = u.cross(e1);
    for (const Vec3d& e : {e1, e2}) {
      detail::WireRowBodies bodies;
      bodies.add(index[k], -e, arm[k]);
      bodies.add(index[k + 1], e, arm[k + 1]);
      if (bodies.count == 0) continue;
      detail::Row& r = rows.add();
      bodies.write(rows, r);
      r.holonomic = false;
      r.speed = 0.0;
      r.compliance = length / (weight * h * tension);
    }
  }
}

template <Scalar S>
void WireT<S>::readBack(std::span<const double> impulses, const StepContext& step) {
  const std::size_t segments = restLengths_.size();
  for (std::size_t k = 0; k < segments; ++k) {
    stretchImpulse_[k] = impulses[k];
    tension_[k] = -impulses[k] / step.getTimeStep();
  }
  std::size_t next = segments;
  for (std::size_t k = 1; k + 1 < points_.size(); ++k) {
    if (!bent_[k]) continue;
    bendImpulse_[2 * k] = impulses[next++];
    bendImpulse_[2 * k + 1] = impulses[next++];
  }
}

SPOOK_COMPILED_ONCE(class, WireT)

using Wire = WireT<double>;
using WireRef = ref_ptr<Wire>;
namespace f32 {
using Wire = WireT<float>;
using WireRef = ref_ptr<Wire>;
}  // namespace f32

}  // namespace spook
