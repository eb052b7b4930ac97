// The single header alone, compiled once (spook_implementation.cpp): a 2 kg
// ball thrown from 10 m, 120 steps at h = 1/60 s in default gravity, against
// the exact discrete solution of symplectic Euler:
//   v_n = v0 + n h g,   x_n = x0 + n h v0 + h² g n(n+1)/2.
#include <spook/spook.hpp>

#include <cmath>
#include <cstdio>

int main() {
  const double h = 1.0 / 60.0;
  const int n = 120;
  const spook::Vec3 g(0, 0, -9.80665), x0(0, 0, 10), v0(1, 0, 3);

  spook::SimulationRef sim = new spook::Simulation();
  sim->setTimeStep(h);
  spook::RigidBodyRef ball = new spook::RigidBody("ball");
  ball->getMassProperties()->setMass(2.0);
  ball->setPosition(x0);
  ball->setVelocity(v0);
  sim->add(ball);
  for (int i = 0; i < n; ++i) sim->stepForward();

  const spook::Vec3 x = x0 + n * h * v0 + h * h * g * (n * (n + 1) / 2.0);
  const spook::Vec3 v = v0 + n * h * g;
  const double dx = (ball->getPosition() - x).norm(), dv = (ball->getVelocity() - v).norm();
  const double dt = std::abs(sim->getTimeStamp() - n * h);
  if (!(dx <= 1e-12 * x.norm() && dv <= 1e-12 * v.norm() && dt <= 1e-12 * n * h)) {
    std::printf("FAIL: after %d steps |x - exact| = %.3g m, |v - exact| = %.3g m/s, |t - nh| = %.3g s\n", n, dx, dv,
                dt);
    return 1;
  }
  std::printf("single-header consumer: x(2 s) = (%.12f, %.12f, %.12f) m, exact\n", x.x(), x.y(), x.z());
  return 0;
}
