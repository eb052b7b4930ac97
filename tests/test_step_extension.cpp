// The step's doors (sim/step_extension.hpp), proven by toys built on them
// alone (toy_particles.hpp): a store of point masses, a beaded string with
// three-body bend rows, and a box of particles in contact.

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "crossing_clock.hpp"
#include "tolerance.hpp"
#include "toy_particles.hpp"

using namespace spook;

namespace {

/// A string of n inner beads of mass m, spacing l and tension T between two
/// fixed ends, released in its k-th mode: its measured angular frequency.
template <class Sim>
double beadedStringOmega(int n, int mode, double bendCompliance, double h, double* tension = nullptr) {
  const double m = 0.01, l = 0.1, T = 10.0, stretchCompliance = 1e-5, amplitude = 1e-4;
  ref_ptr<Sim> sim = new Sim();
  sim->setTimeStep(decltype(sim->getTimeStep())(h));
  ref_ptr<toy::ParticleStore> beads = new toy::ParticleStore();
  beads->setGravity(false);
  for (int i = 0; i <= n + 1; ++i) {
    const double shape = std::sin(mode * std::numbers::pi * i / (n + 1));
    beads->add(toy::Vec3d(i * l, amplitude * shape, 0.0), m, 0.01, i == 0 || i == n + 1);
  }
  ref_ptr<toy::BeadedString> string =
      new toy::BeadedString(beads, l - T * stretchCompliance, stretchCompliance, bendCompliance, toy::Vec3d::UnitX());
  sim->add(beads);
  sim->add(string);
  spook::test::CrossingClock clock;
  const double period = 2.0 * std::numbers::pi * std::sqrt(m * l / T);  // of the fastest mode's scale
  const int steps = int(std::ceil(12.0 * (n + 1) * period / (mode * h)));
  for (int s = 1; s <= steps; ++s) {
    sim->stepForward();
    double q = 0.0;
    for (int i = 1; i <= n; ++i) q += beads->position(std::size_t(i)).y() * std::sin(mode * std::numbers::pi * i / (n + 1));
    clock.add(s * h, q);
  }
  if (tension) *tension = string->tension();
  return clock.omega();
}

}  // namespace

TEST_CASE_TEMPLATE("a beaded string on a particle store oscillates at the lumped frequencies", Sim, Simulation,
                   f32::Simulation) {
  const int n = 9;
  const double m = 0.01, l = 0.1, T = 10.0;
  for (int k = 1; k <= 3; ++k) {
    const double lambda = 4.0 * std::pow(std::sin(k * std::numbers::pi / (2.0 * (n + 1))), 2);
    // Stretch rows alone: ω_k = 2√(T/(m l)) sin(kπ/(2(N+1))).
    double tension = 0.0;
    const double plain = beadedStringOmega<Sim>(n, k, 0.0, 1e-3, &tension);
    const double exact = std::sqrt(lambda * T / (m * l));
    // Within 0.2% at h = 1 ms (measured 0.01-0.04%; the error falls as h²).
    CHECK(plain == doctest::Approx(exact).epsilon(0.002));
    CHECK(tension == doctest::Approx(T).epsilon(0.001));
    // With the three-bead bend rows of compliance c: ω² = λT/(m l) + λ²/(c m)
    // (the bend operator is the square of the string's on sine modes).
    const double c = 1e-2;
    const double bent = beadedStringOmega<Sim>(n, k, c, 1e-3);
    const double exactBent = std::sqrt(lambda * T / (m * l) + lambda * lambda / (c * m));
    CHECK(bent == doctest::Approx(exactBent).epsilon(0.002));
    MESSAGE("mode " << k << ": " << plain << " rad/s (exact " << exact << "), with bend rows " << bent << " (exact "
                    << exactBent << "), tension " << tension << " N");
  }
}

TEST_CASE_TEMPLATE("1,000 particles without rigid bodies settle in a box", Sim, Simulation, f32::Simulation) {
  const double radius = 0.05, mass = 0.5, half = 0.5;  // box 1 m × 1 m, open at the top
  ref_ptr<Sim> sim = new Sim();
  sim->setSolver(new IterativeSolver());
  ref_ptr<toy::ParticleStore> particles = new toy::ParticleStore();
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> jitter(-0.005, 0.005);
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j)
      for (int k = 0; k < 10; ++k)
        particles->add(toy::Vec3d(-0.45 + 0.1 * i + jitter(rng), -0.45 + 0.1 * j + jitter(rng),
                                  0.1 + 0.12 * k + jitter(rng)),
                       mass, radius);
  using Plane = toy::ParticleContacts::Plane;
  ref_ptr<toy::ParticleContacts> contacts = new toy::ParticleContacts(
      particles, {Plane{toy::Vec3d::UnitZ(), 0.0}, Plane{toy::Vec3d::UnitX(), -half}, Plane{-toy::Vec3d::UnitX(), -half},
                  Plane{toy::Vec3d::UnitY(), -half}, Plane{-toy::Vec3d::UnitY(), -half}});
  sim->add(particles);
  sim->add(contacts);
  const auto worst = [&] {
    struct {
      double outside = 0.0, speed = 0.0, overlap = 0.0;
    } w;
    for (std::size_t i = 0; i < particles->size(); ++i) {
      const toy::Vec3d& p = particles->position(i);
      w.outside = std::max({w.outside, std::abs(p.x()) + radius - half, std::abs(p.y()) + radius - half, radius - p.z()});
      w.speed = std::max(w.speed, particles->velocity(i).norm());
    }
    return w;
  };
  double deepest = 0.0;
  // 4 s; 1 s in the sanitized build, which looks for memory and undefined
  // behaviour faults (the pile has not settled then: only its walls are checked).
  const int steps = spook::test::sweep(240, 60);
  for (int s = 0; s < steps; ++s) {
    sim->stepForward();
    deepest = std::max(deepest, worst().outside);
  }
  const auto end = worst();
  MESSAGE("deepest past a wall " << deepest << " m, fastest particle at 4 s " << end.speed << " m/s, "
                                 << contacts->numContacts() << " contacts");
  CHECK(deepest < 0.01);          // no particle through the floor or a wall
  if (steps == 240) CHECK(end.speed < 0.05);  // settled
  for (std::size_t i = 0; i < particles->size(); ++i) REQUIRE(particles->position(i).z() < 1.0);  // a pile, none thrown out
}

TEST_CASE("stores and producers are added once, and a bad row index is refused by name") {
  ref_ptr<Simulation> sim = new Simulation();
  ref_ptr<toy::ParticleStore> store = new toy::ParticleStore();
  store->add(toy::Vec3d::Zero(), 1.0, 0.1);
  sim->add(store);
  CHECK_THROWS_AS(sim->add(store), Error);
  ref_ptr<Simulation> other = new Simulation();
  CHECK_THROWS_AS(other->add(store), Error);
  CHECK_THROWS_AS(sim->add(ref_ptr<BodyStore>()), Error);

  struct BadProducer : RowProducer {
    void writeRows(RowWriter& rows, const StepContext&) override { rows.add().body1 = 7; }
    void readBack(std::span<const double>, const StepContext&) override {}
  };
  ref_ptr<BadProducer> bad = new BadProducer();
  bad->setName("bad");
  sim->add(ref_ptr<RowProducer>(bad));
  try {
    sim->stepForward();
    FAIL("a row with body index 7 of 1 was accepted");
  } catch (const Error& e) {
    CHECK(std::string(e.what()).find("bad") != std::string::npos);
    CHECK(std::string(e.what()).find('7') != std::string::npos);
  }
  sim->remove(bad.get());
  CHECK_FALSE(sim->contains(bad.get()));
  sim->stepForward();  // the store alone: free fall
  CHECK(store->position(0).z() < 0.0);
  CHECK(sim->contains(store.get()));
}

TEST_CASE("a producer's friction links and lever arms name its own rows, or the step is refused by name") {
  ref_ptr<Simulation> sim = new Simulation();
  ref_ptr<toy::ParticleStore> store = new toy::ParticleStore();
  store->add(toy::Vec3d::Zero(), 1.0, 0.1);
  sim->add(store);
  // One fault per kind: 1 links a friction row to a row it did not write,
  // 2 gives a negative coefficient, 3 lever arms to a foreign row, 4 NaN arms.
  struct Faulty : RowProducer {
    int fault = 0;
    void writeRows(RowWriter& rows, const StepContext& step) override {
      const std::size_t normal = rows.size(), tangent = normal + 1;
      for (int axis : {0, 1}) {
        detail::Row& r = rows.add();
        r.body1 = step.indexOf(*store, 0);
        r.J1[axis] = 1.0;
      }
      if (fault == 1) rows.setFriction(tangent, normal + 2, 0.5, detail::FrictionBound::SCALED_BOX);
      if (fault == 2) rows.setFriction(tangent, normal, -0.5, detail::FrictionBound::SCALED_BOX);
      if (fault == 3) rows.setLeverArms(normal + 5, toy::Vec3d::Zero(), toy::Vec3d::Zero());
      if (fault == 4) rows.setLeverArms(normal, toy::Vec3d::Constant(std::nan("")), toy::Vec3d::Zero());
    }
    void readBack(std::span<const double>, const StepContext&) override {}
    ref_ptr<toy::ParticleStore> store;
  };
  ref_ptr<Faulty> producer = new Faulty();
  producer->store = store;
  producer->setName("faulty");
  sim->add(ref_ptr<RowProducer>(producer));
  for (int fault = 1; fault <= 4; ++fault) {
    CAPTURE(fault);
    producer->fault = fault;
    try {
      sim->stepForward();
      FAIL("the producer's fault was accepted");
    } catch (const Error& e) {
      CHECK(std::string(e.what()).find("faulty") != std::string::npos);
    }
  }
  // Well-formed links step (the rows hold the particle at rest in x and y).
  producer->fault = 0;
  sim->stepForward();
  CHECK(store->position(0).allFinite());
}

TEST_CASE("stores and producers outlive a destroyed simulation and join a new one; errors name them") {
  ref_ptr<Simulation> sim = new Simulation();
  ref_ptr<toy::ParticleStore> store = new toy::ParticleStore();
  store->setName("beads");
  for (int i = 0; i < 3; ++i) store->add(toy::Vec3d(0.1 * i, 0.0, 0.0), 0.01, 0.01);
  ref_ptr<toy::BeadedString> string = new toy::BeadedString(store, 0.1, 1e-6, 0.0, toy::Vec3d::UnitX());
  string->setName("string");
  sim->add(store);
  sim->add(string);
  sim->stepForward();
  try {
    sim->add(string);
    FAIL("a producer was added twice");
  } catch (const Error& e) {
    CHECK(std::string(e.what()).find("RowProducer") != std::string::npos);
    CHECK(std::string(e.what()).find("string") != std::string::npos);
  }
  ref_ptr<Simulation> other = new Simulation();
  try {
    other->remove(store.get());
    FAIL("a store was removed from a simulation it is not in");
  } catch (const Error& e) {
    CHECK(std::string(e.what()).find("BodyStore") != std::string::npos);
    CHECK(std::string(e.what()).find("beads") != std::string::npos);
  }
  CHECK(sim->getBodyStores().size() == 1);
  CHECK(sim->getRowProducers().size() == 1);

  sim = nullptr;  // releases both
  CHECK(store->getReferenceCount() == 2);  // here and in the string
  CHECK(store->getSimulationHandle() == nullptr);
  CHECK(string->getSimulationHandle() == nullptr);
  other->add(store);
  other->add(string);
  CHECK(store->getSimulationHandle() == other.get());
  CHECK(other->contains(store.get()));
  CHECK(other->contains(string.get()));
  const double z = store->position(1).z();
  other->stepForward();
  CHECK(store->position(1).z() < z);  // falls, held by its stretch rows only
  CHECK((store->position(1) - store->position(0)).norm() == doctest::Approx(0.1).epsilon(1e-3));
}
