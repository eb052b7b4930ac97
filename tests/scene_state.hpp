#pragma once

// A snapshot of everything a user can observe of a simulation and of the
// collections and bodies around it, compared for exact equality. Tests use it
// to show that a call which threw changed nothing:
//
//   const auto before = spook::test::SceneState<S>::capture(*sim);
//   CHECK_THROWS_AS(body->getMassProperties()->setMass(-1), spook::Error);
//   CHECK(spook::test::firstDifference(before, spook::test::SceneState<S>::capture(*sim)) == "");

#include <cstdint>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include <spook/sim/simulation.hpp>

namespace spook::test {

/// Largest entry of the difference of two poses (m for the translation).
template <class S>
S poseError(const TransformT<S>& a, const TransformT<S>& b) {
  return (a.matrix() - b.matrix()).cwiseAbs().maxCoeff();
}

template <class S>
struct BodyState {
  const RigidBodyT<S>* body = nullptr;
  std::string name;
  bool enable = false;
  int motionControl = 0;
  bool movingToTarget = false;
  bool inSimulation = false;  // in the captured simulation
  Eigen::Matrix<S, 4, 4> transform;
  Eigen::Matrix<S, 4, 4> cmLocal;  // CM frame relative to the model frame
  Vec3T<S> velocity, angularVelocity, force, torque;
  S mass = S(0);
  Mat3T<S> inertia;
  Vec3T<S> massCoefficients, linearDamping, angularDamping;
};

template <class S>
struct ListenerState {
  const StepEventListenerT<S>* listener = nullptr;
  std::uint32_t mask = 0;
  int priority = 0;
  bool enable = false;
  const SimulationT<S>* simulation = nullptr;
};

template <class S>
struct CollectionState {
  const CollectionT<S>* collection = nullptr;
  std::string name;
  std::vector<const void*> bodies, listeners, children;
};

template <class S>
struct SceneState {
  S timeStamp = S(0);
  S timeStep = S(0);
  std::uint64_t numSteps = 0;
  const void* gravityField = nullptr;
  std::vector<const void*> bodies, listeners, collections;  // the simulation's lists, in order
  std::vector<BodyState<S>> bodyStates;                     // sim bodies, then collection bodies, then extras
  std::vector<ListenerState<S>> listenerStates;
  std::vector<CollectionState<S>> collectionStates;  // sim collections and `extra`, nested ones included

  /// Captures `sim`, the collections in it and in `extra` (recursively), and
  /// the bodies in `extraBodies` (e.g. bodies of another simulation).
  static SceneState capture(const SimulationT<S>& sim, std::initializer_list<const CollectionT<S>*> extra = {},
                            std::initializer_list<const RigidBodyT<S>*> extraBodies = {}) {
    SceneState s;
    s.timeStamp = sim.getTimeStamp();
    s.timeStep = sim.getTimeStep();
    s.numSteps = sim.getStatistics().numSteps;
    s.gravityField = sim.getGravityField();
    for (const auto& b : sim.getRigidBodies()) {
      s.bodies.push_back(b.get());
      s.addBody(sim, *b);
    }
    for (const auto& l : sim.getEventListeners()) {
      s.listeners.push_back(l.get());
      s.addListener(*l);
    }
    for (const auto& c : sim.getCollections()) {
      s.collections.push_back(c.get());
      s.addCollection(sim, *c);
    }
    for (const CollectionT<S>* c : extra) s.addCollection(sim, *c);
    for (const RigidBodyT<S>* b : extraBodies) s.addBody(sim, *b);
    return s;
  }

 private:
  void addBody(const SimulationT<S>& sim, const RigidBodyT<S>& b) {
    const MassPropertiesT<S>& m = *b.getMassProperties();
    bodyStates.push_back({&b, b.getName(), b.getEnable(), static_cast<int>(b.getMotionControl()), b.isMovingToTarget(),
                          sim.contains(&b), b.getTransform().matrix(), b.getCmFrame()->getLocalMatrix().matrix(),
                          b.getVelocity(), b.getAngularVelocity(), b.getForce(), b.getTorque(), m.getMass(),
                          m.getInertiaTensor(), m.getMassCoefficients(), b.getLinearVelocityDamping(),
                          b.getAngularVelocityDamping()});
  }
  void addListener(const StepEventListenerT<S>& l) {
    listenerStates.push_back({&l, l.getMask(), l.getPriority(), l.getEnable(), l.getSimulation()});
  }
  void addCollection(const SimulationT<S>& sim, const CollectionT<S>& c) {
    CollectionState<S> state{&c, c.getName(), {}, {}, {}};
    for (const auto& b : c.getRigidBodies()) state.bodies.push_back(b.get());
    for (const auto& l : c.getEventListeners()) state.listeners.push_back(l.get());
    for (const auto& child : c.getCollections()) state.children.push_back(child.get());
    collectionStates.push_back(state);
    for (const auto& b : c.getRigidBodies()) addBody(sim, *b);
    for (const auto& l : c.getEventListeners()) addListener(*l);
    for (const auto& child : c.getCollections()) addCollection(sim, *child);
  }
};

/// The first difference between two captures, e.g. "body 'crate' velocity",
/// or "" when they are identical (bit for bit).
template <class S>
std::string firstDifference(const SceneState<S>& a, const SceneState<S>& b) {
  if (a.timeStamp != b.timeStamp) return "time stamp";
  if (a.timeStep != b.timeStep) return "time step";
  if (a.numSteps != b.numSteps) return "number of steps";
  if (a.gravityField != b.gravityField) return "gravity field";
  if (a.bodies != b.bodies) return "list of bodies";
  if (a.listeners != b.listeners) return "list of listeners";
  if (a.collections != b.collections) return "list of collections";
  if (a.bodyStates.size() != b.bodyStates.size()) return "number of captured bodies";
  for (std::size_t i = 0; i < a.bodyStates.size(); ++i) {
    const BodyState<S>& x = a.bodyStates[i];
    const BodyState<S>& y = b.bodyStates[i];
    const std::string body = "body '" + x.name + "' ";
    if (x.body != y.body) return "captured body " + std::to_string(i);
    const std::pair<bool, const char*> checks[] = {
        {x.name == y.name, "name"},
        {x.enable == y.enable, "enable"},
        {x.motionControl == y.motionControl, "motion control"},
        {x.movingToTarget == y.movingToTarget, "moveTo target"},
        {x.inSimulation == y.inSimulation, "membership"},
        {x.transform == y.transform, "transform"},
        {x.cmLocal == y.cmLocal, "center-of-mass frame"},
        {x.velocity == y.velocity, "velocity"},
        {x.angularVelocity == y.angularVelocity, "angular velocity"},
        {x.force == y.force, "force"},
        {x.torque == y.torque, "torque"},
        {x.mass == y.mass, "mass"},
        {x.inertia == y.inertia, "inertia tensor"},
        {x.massCoefficients == y.massCoefficients, "mass coefficients"},
        {x.linearDamping == y.linearDamping, "linear damping"},
        {x.angularDamping == y.angularDamping, "angular damping"},
    };
    for (const auto& [same, what] : checks)
      if (!same) return body + what;
  }
  if (a.listenerStates.size() != b.listenerStates.size()) return "number of captured listeners";
  for (std::size_t i = 0; i < a.listenerStates.size(); ++i) {
    const ListenerState<S>& x = a.listenerStates[i];
    const ListenerState<S>& y = b.listenerStates[i];
    if (x.listener != y.listener || x.mask != y.mask || x.priority != y.priority || x.enable != y.enable ||
        x.simulation != y.simulation)
      return "listener " + std::to_string(i);
  }
  if (a.collectionStates.size() != b.collectionStates.size()) return "number of captured collections";
  for (std::size_t i = 0; i < a.collectionStates.size(); ++i) {
    const CollectionState<S>& x = a.collectionStates[i];
    const CollectionState<S>& y = b.collectionStates[i];
    if (x.collection != y.collection || x.name != y.name || x.bodies != y.bodies || x.listeners != y.listeners ||
        x.children != y.children)
      return "collection '" + x.name + "'";
  }
  return "";
}

}  // namespace spook::test
