// spook via add_subdirectory: two bodies, 90 steps at h = 1/30 s. The heavy
// one falls in default gravity, the light one floats in a zero uniform field
// of a second simulation; both against the exact discrete solution of
// symplectic Euler:
//   v_n = v0 + n h g,   x_n = x0 + n h v0 + h² g n(n+1)/2.
#include <spook/spook.hpp>

#include <cstdio>

namespace {

bool matches(const char* name, const spook::RigidBody& body, const spook::Vec3& x0, const spook::Vec3& v0,
             const spook::Vec3& g, int n, double h) {
  const spook::Vec3 x = x0 + n * h * v0 + h * h * g * (n * (n + 1) / 2.0);
  const spook::Vec3 v = v0 + n * h * g;
  const double dx = (body.getPosition() - x).norm(), dv = (body.getVelocity() - v).norm();
  if (dx <= 1e-12 * x.norm() && dv <= 1e-12 * v.norm()) return true;
  std::printf("FAIL %s: after %d steps |x - exact| = %.3g m, |v - exact| = %.3g m/s\n", name, n, dx, dv);
  return false;
}

}  // namespace

int main() {
  const double h = 1.0 / 30.0;
  const int n = 90;
  const spook::Vec3 x0(0, 0, 100), v0(2, 1, 0);

  spook::SimulationRef falling = new spook::Simulation();
  spook::SimulationRef floating = new spook::Simulation();
  spook::RigidBodyRef heavy = new spook::RigidBody("heavy");
  spook::RigidBodyRef light = new spook::RigidBody("light");
  heavy->getMassProperties()->setMass(1000.0);
  light->getMassProperties()->setMass(0.001);
  for (auto* sim : {falling.get(), floating.get()}) sim->setTimeStep(h);
  floating->setUniformGravity(spook::Vec3::Zero());
  for (auto* body : {heavy.get(), light.get()}) {
    body->setPosition(x0);
    body->setVelocity(v0);
  }
  falling->add(heavy);
  floating->add(light);
  for (int i = 0; i < n; ++i) {
    falling->stepForward();
    floating->stepForward();
  }

  const bool ok = matches("heavy body in gravity", *heavy, x0, v0, spook::Vec3(0, 0, -9.80665), n, h) &&
                  matches("light body without gravity", *light, x0, v0, spook::Vec3::Zero(), n, h);
  if (!ok) return 1;
  std::printf("add_subdirectory consumer: both bodies on the exact discrete trajectory\n");
  return 0;
}
