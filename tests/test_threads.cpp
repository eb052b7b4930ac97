#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include <spook/constraints/joints/hinge.hpp>

#include "contact_scenes.hpp"
#include "error_message.hpp"
#include "policies.hpp"
#include "tolerance.hpp"

// SimulationT::setNumThreads: the narrow phase's pairs and the islands'
// solves spread over threads, with results the same bit for bit for any
// number of threads (issue 20).

using spook::test::Policy;

namespace {

/// Every body's pose and velocities after the run, in the simulation's order.
template <class S>
std::vector<S> stateOf(const spook::SimulationT<S>& sim) {
  std::vector<S> state;
  for (const auto& body : sim.getRigidBodies()) {
    const auto& x = body->getPosition();
    const auto q = body->getRotation();
    const auto& v = body->getVelocity();
    const auto& w = body->getAngularVelocity();
    for (S value : {x.x(), x.y(), x.z(), q.w(), q.x(), q.y(), q.z(), v.x(), v.y(), v.z(), w.x(), w.y(), w.z()})
      state.push_back(value);
  }
  return state;
}

template <class S>
bool sameBits(const std::vector<S>& a, const std::vector<S>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(S)) == 0;
}

/// 200 spheres of radius 8-12 cm (density 1000 kg/m³ and 3000 for every
/// third) dropped from a jittered grid into a 1.2 m × 1.2 m box open at the
/// top: separate islands while they fall, one pile once they land.
template <class S>
struct SpherePile {
  static constexpr int kSpheres = 200;
  static constexpr double kHalfWidth = 0.6;
  spook::ref_ptr<spook::SimulationT<S>> sim = new spook::SimulationT<S>();
  spook::ref_ptr<spook::MaterialT<S>> light = new spook::MaterialT<S>("light");
  spook::ref_ptr<spook::MaterialT<S>> heavy = new spook::MaterialT<S>("heavy");
  std::vector<S> radii;
  int mostIslands = 0;
  std::size_t lastContacts = 0;

  SpherePile(Policy policy, int threads) {
    sim->setSolver(spook::test::makeSolver(policy));
    sim->setNumThreads(threads);
    heavy->getBulkMaterial()->setDensity(S(3000));
    spook::test::addGround(*sim, light);
    const S wall = S(kHalfWidth + 0.1);
    for (int side = 0; side < 4; ++side) {
      const S along = side < 2 ? S(0.1) : S(kHalfWidth + 0.2);
      const S across = side < 2 ? S(kHalfWidth + 0.2) : S(0.1);
      const spook::Vec3T<S> at = side == 0   ? spook::Vec3T<S>(wall, 0, 1)
                                 : side == 1 ? spook::Vec3T<S>(-wall, 0, 1)
                                 : side == 2 ? spook::Vec3T<S>(0, wall, 1)
                                             : spook::Vec3T<S>(0, -wall, 1);
      spook::ref_ptr<spook::GeometryT<S>> g = new spook::GeometryT<S>(
          new spook::BoxT<S>(spook::Vec3T<S>(along, across, S(1))), spook::TransformT<S>(Eigen::Translation<S, 3>(at)));
      g->setMaterial(light);
      sim->add(g);
    }
    std::mt19937 random(20);
    std::uniform_real_distribution<double> jitter(-0.02, 0.02), radius(0.08, 0.12);
    for (int i = 0; i < kSpheres; ++i) {
      const int layer = i / 25, column = i % 5, row = (i / 5) % 5;
      radii.push_back(S(radius(random)));
      const spook::Vec3T<S> at(S(-0.48 + 0.24 * column + jitter(random)), S(-0.48 + 0.24 * row + jitter(random)),
                               S(0.15 + 0.26 * layer));
      spook::test::addBody(*sim, "sphere", new spook::SphereT<S>(radii.back()), i % 3 == 0 ? heavy : light, at);
    }
  }

  void run(int steps) {
    for (int i = 0; i < steps; ++i) {
      sim->stepForward();
      mostIslands = std::max(mostIslands, sim->getStatistics().solver.numIslands);
    }
    lastContacts = sim->getGeometryContacts().size();
  }

  /// Deepest penetration into the floor (m) and whether every sphere is
  /// still inside the box.
  [[nodiscard]] double deepest() const {
    double deepest = 0.0;
    for (std::size_t i = 0; i < radii.size(); ++i)
      deepest = std::max(deepest, double(radii[i] - sim->getRigidBodies()[i]->getPosition().z()));
    return deepest;
  }
  [[nodiscard]] bool allInside() const {
    for (const auto& b : sim->getRigidBodies()) {
      const auto& x = b->getPosition();
      if (!(std::abs(double(x.x())) < kHalfWidth && std::abs(double(x.y())) < kHalfWidth && x.z() > S(0))) return false;
    }
    return true;
  }
};

}  // namespace

// The acceptance check of issue 20: 300 steps (5 s) of a 200-sphere pile,
// under the default policy and the iterative one, with 1, 2 and 3 threads.
TEST_CASE_TEMPLATE("a 200-sphere pile steps to the same bits with 1, 2 and 3 threads", S, float, double) {
  for (const Policy policy : {Policy::HYBRID, Policy::ITERATIVE}) {
    CAPTURE(spook::test::policyName(policy));
    const int steps = spook::test::sweep(300, 40);
    SpherePile<S> one(policy, 1);
    one.run(steps);
    const std::vector<S> reference = stateOf(*one.sim);
    REQUIRE(std::all_of(reference.begin(), reference.end(), [](S x) { return std::isfinite(double(x)); }));
    // Both parallel parts ran: islands while the spheres fell, enough pairs
    // for the narrow phase's threads.
    CHECK(one.mostIslands > 1);
    CHECK(one.lastContacts >= spook::SpaceT<S>::kPairsWorthThreads);
    CHECK(one.allInside());
    CHECK(one.deepest() < 5e-3);
    for (const int threads : {2, 3}) {
      CAPTURE(threads);
      SpherePile<S> many(policy, threads);
      many.run(steps);
      CHECK(sameBits(reference, stateOf(*many.sim)));
      CHECK(many.sim->getStatistics().solver.numIslands == one.sim->getStatistics().solver.numIslands);
    }
  }
}

// Islands solved by the direct policy on both threads, with post-stabilization
// (the projection's islands run on the threads too): 8 stacks of 4 boxes
// and 2 hinge chains of 6 links, each its own island.
TEST_CASE_TEMPLATE("separate stacks and hinge chains step to the same bits with 1 and 2 threads (direct)", S, float,
                   double) {
  const auto build = [](int threads) {
    spook::ref_ptr<spook::SimulationT<S>> sim = new spook::SimulationT<S>();
    sim->setSolver(new spook::DirectSolver());
    sim->setNumThreads(threads);
    spook::ref_ptr<spook::MaterialT<S>> wood = new spook::MaterialT<S>("wood");
    spook::test::addGround(*sim, wood);
    for (int stack = 0; stack < 8; ++stack)
      for (int level = 0; level < 4; ++level)
        spook::test::addBody(*sim, "box", new spook::BoxT<S>(spook::Vec3T<S>(S(0.3), S(0.2), S(0.25))), wood,
                             spook::Vec3T<S>(S(1.5 * stack), S(0.01 * level), S(0.25 + 0.5 * level)));
    for (int chain = 0; chain < 2; ++chain) {
      spook::RigidBodyT<S>* previous = nullptr;
      const S y = S(-3 - 2 * chain);
      for (int link = 0; link < 6; ++link) {
        spook::ref_ptr<spook::RigidBodyT<S>> body =
            spook::test::addBody(*sim, "link", new spook::BoxT<S>(spook::Vec3T<S>(S(0.25), S(0.05), S(0.05))), wood,
                                 spook::Vec3T<S>(S(0.5 * link + 0.25), y, S(4)));
        sim->add(spook::ConstraintT<S>::template createFromWorld<spook::HingeT<S>>(
            spook::Vec3T<S>(S(0.5 * link), y, S(4)), spook::Vec3T<S>::UnitY(), body.get(), previous));
        previous = body.get();
      }
    }
    return sim;
  };
  const int steps = spook::test::sweep(120, 30);
  spook::ref_ptr<spook::SimulationT<S>> one = build(1), two = build(2);
  int mostIslands = 0;
  for (int i = 0; i < steps; ++i) {
    one->stepForward();
    two->stepForward();
    mostIslands = std::max(mostIslands, one->getStatistics().solver.numIslands);
  }
  CHECK(mostIslands >= 10);
  const std::vector<S> reference = stateOf(*one);
  REQUIRE(std::all_of(reference.begin(), reference.end(), [](S x) { return std::isfinite(double(x)); }));
  CHECK(sameBits(reference, stateOf(*two)));
}

TEST_CASE("a number of threads outside [1, 256] is refused and changes nothing") {
  spook::SimulationRef sim = new spook::Simulation();
  sim->setNumThreads(2);
  for (const int n : {0, -3, spook::Simulation::kMaxThreads + 1}) {
    const std::string message = spook::test::errorMessage([&] { sim->setNumThreads(n); });
    CHECK(message.find("Simulation") != std::string::npos);
    CHECK(message.find("threads") != std::string::npos);
    CHECK(message.find(std::to_string(n)) != std::string::npos);
    CHECK(sim->getNumThreads() == 2);
  }
}
