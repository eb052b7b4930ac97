// Cost of one unconstrained step: N free bodies under gravity, spinning
// about skewed axes so that the free-rotation solve does real work.
#include <benchmark/benchmark.h>

#include <spook/solver/free_rotation.hpp>
#include <spook/spook.hpp>

namespace {

template <class S>
void stepFreeBodies(benchmark::State& state) {
  spook::ref_ptr<spook::SimulationT<S>> sim = new spook::SimulationT<S>();
  const auto count = static_cast<int>(state.range(0));
  for (int i = 0; i < count; ++i) {
    spook::ref_ptr<spook::RigidBodyT<S>> body = new spook::RigidBodyT<S>();
    body->getMassProperties()->setInertiaTensor(spook::Vec3T<S>(S(1), S(2), S(3)));
    body->setPosition(spook::Vec3T<S>(S(i), S(0), S(0)));
    body->setAngularVelocity(spook::Vec3T<S>(S(0.3), S(2), S(-0.5)));
    sim->add(body);
  }
  for (auto _ : state) sim->stepForward();
  state.SetItemsProcessed(state.iterations() * count);
}

template <class S>
void freeRotationStep(benchmark::State& state) {
  const spook::Mat3T<S> inverse = spook::Vec3T<S>(S(1), S(0.5), S(1) / S(3)).asDiagonal();
  spook::Vec3T<S> momentum(S(0.3), S(4), S(-1.5));
  for (auto _ : state) {
    auto r = spook::detail::rotateFreely<S>(inverse, momentum, S(1) / S(60));
    benchmark::DoNotOptimize(r);
    momentum = r.momentum;
  }
}

}  // namespace

BENCHMARK(stepFreeBodies<double>)->Arg(1)->Arg(64)->Arg(4096);
BENCHMARK(stepFreeBodies<float>)->Arg(1)->Arg(64)->Arg(4096);
BENCHMARK(freeRotationStep<double>);
BENCHMARK(freeRotationStep<float>);
BENCHMARK_MAIN();
