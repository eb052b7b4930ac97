// Installed spook, found with find_package and linked compiled once
// (spook::spook_compiled): a ball thrown upward in default
// gravity, stepped to t = 1 s with stepTo, against the exact discrete
// solution of symplectic Euler:
//   v_n = v0 + n h g,   x_n = x0 + n h v0 + h² g n(n+1)/2.
#include <spook/spook.hpp>

#include <cstdio>

int main() {
  const double h = 1.0 / 100.0;
  const int n = 100;
  const spook::Vec3 g(0, 0, -9.80665), x0(1, 2, 0), v0(0, -1, 5);

  spook::SimulationRef sim = new spook::Simulation();
  sim->setTimeStep(h);
  spook::RigidBodyRef ball = new spook::RigidBody("ball");
  ball->getMassProperties()->setMass(0.5);
  ball->setPosition(x0);
  ball->setVelocity(v0);
  sim->add(ball);
  sim->stepTo(n * h);

  const spook::Vec3 x = x0 + n * h * v0 + h * h * g * (n * (n + 1) / 2.0);
  const spook::Vec3 v = v0 + n * h * g;
  const double dx = (ball->getPosition() - x).norm(), dv = (ball->getVelocity() - v).norm();
  if (!(dx <= 1e-12 * x.norm() && dv <= 1e-12 * v.norm())) {
    std::printf("FAIL: after %d steps |x - exact| = %.3g m, |v - exact| = %.3g m/s\n", n, dx, dv);
    return 1;
  }
  std::printf("find_package consumer: z(1 s) = %.12f m, exact\n", ball->getPosition().z());
  return 0;
}
