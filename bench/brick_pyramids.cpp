// Issue 19's brick-pattern pyramids: each unit cube rests on two below, 5 cm
// apart within a level (so that the top cubes carry almost nothing), μ 0.5,
// h = 1/60, 5 s. Bases 10 and 20 (55 and 210 cubes), cubes of 1 and 1000 kg,
// direct and hybrid policies, float and double. Prints per run the largest
// displacement of any cube, the slowest and the mean step, and the direct
// solves that fell back (SolverStatistics::directFallbacks).
//
//   brick_pyramids [steps]      (default 300 = 5 s)

#include <spook/spook.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

template <class S>
void run(int base, double mass, const std::string& policy, int steps) {
  spook::ref_ptr<spook::SimulationT<S>> sim = new spook::SimulationT<S>();
  if (policy == "direct") sim->setSolver(new spook::DirectSolver());
  else sim->setSolver(new spook::HybridSolver());
  spook::ref_ptr<spook::MaterialT<S>> wood = new spook::MaterialT<S>("wood");
  spook::ref_ptr<spook::GeometryT<S>> ground = new spook::GeometryT<S>(new spook::PlaneT<S>(spook::Vec3T<S>::UnitZ()));
  ground->setMaterial(wood);
  sim->add(ground);
  std::vector<spook::ref_ptr<spook::RigidBodyT<S>>> cubes;
  std::vector<spook::Vec3T<S>> start;
  for (int level = 0; level < base; ++level)
    for (int i = 0; i < base - level; ++i) {
      spook::ref_ptr<spook::GeometryT<S>> shape =
          new spook::GeometryT<S>(new spook::BoxT<S>(spook::Vec3T<S>::Constant(S(0.5))));
      shape->setMaterial(wood);
      spook::ref_ptr<spook::RigidBodyT<S>> cube = new spook::RigidBodyT<S>(shape);
      cube->getMassProperties()->setMass(S(mass));
      cube->updateMassProperties();
      cube->setPosition(spook::Vec3T<S>(S(1.05 * (i - (base - 1 - level) / 2.0)), S(0), S(0.5 + level)));
      sim->add(cube);
      cubes.push_back(cube);
      start.push_back(cube->getPosition());
    }
  double slowest = 0.0, total = 0.0;
  int fallbacks = 0, fallbackSteps = 0;
  for (int k = 0; k < steps; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    sim->stepForward();
    const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    slowest = std::max(slowest, dt);
    total += dt;
    const int f = sim->getStatistics().solver.directFallbacks;
    fallbacks += f;
    fallbackSteps += f > 0 ? 1 : 0;
  }
  double drift = 0.0;
  for (std::size_t i = 0; i < cubes.size(); ++i)
    drift = std::max(drift, double((cubes[i]->getPosition() - start[i]).norm()));
  std::printf("| %4zu | %6.0f | %-6s | %-6s | %9.2e | %8.3f | %8.2f | %4d in %3d steps |\n", cubes.size(), mass,
              policy.c_str(), sizeof(S) == 4 ? "float" : "double", drift, slowest, 1e3 * total / steps, fallbacks,
              fallbackSteps);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  const int steps = argc > 1 ? std::atoi(argv[1]) : 300;
  std::printf("brick pyramids, %d steps at 60 Hz\n", steps);
  std::printf("| cubes | kg | policy | scalar | drift (m) | slowest (s) | mean (ms) | direct fallbacks |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  for (const int base : {10, 20})
    for (const double mass : {1.0, 1000.0})
      for (const char* policy : {"direct", "hybrid"}) {
        run<double>(base, mass, policy, steps);
        run<float>(base, mass, policy, steps);
      }
}
