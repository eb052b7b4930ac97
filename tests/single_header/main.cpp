// Built against single_include/ only (not include/): the generated header must
// be complete and compile warning-free on its own. The check is physics: a
// body in uniform gravity follows the exact discrete solution of symplectic
// Euler,
//   v_n = v0 + n h g,   x_n = x0 + n h v0 + h² g n(n+1)/2.
#include <spook/spook.hpp>

#include <cmath>
#include <cstdio>

double boxInertiaX(double a, double b, double c, double m);  // second_tu.cpp

namespace {

int failures = 0;

void expectNear(const char* what, const spook::Vec3& actual, const spook::Vec3& expected, double rel) {
  const double error = (actual - expected).norm();
  if (!(error <= rel * expected.norm())) {
    std::printf("FAIL %s: got (%.17g, %.17g, %.17g), expected (%.17g, %.17g, %.17g), |error| = %.3g > %.1g relative\n",
                what, actual.x(), actual.y(), actual.z(), expected.x(), expected.y(), expected.z(), error, rel);
    ++failures;
  }
}

void expectNear(const char* what, double actual, double expected, double rel) {
  if (!(std::abs(actual - expected) <= rel * std::abs(expected))) {
    std::printf("FAIL %s: got %.17g, expected %.17g\n", what, actual, expected);
    ++failures;
  }
}

}  // namespace

int main() {
  const double h = 1.0 / 60.0;
  const int n = 120;
  const spook::Vec3 g(0, 0, -9.80665);  // default gravity (m/s²)
  const spook::Vec3 x0(0, 0, 10);       // m
  const spook::Vec3 v0(1, 0, 3);        // m/s

  spook::SimulationRef sim = new spook::Simulation();
  sim->setTimeStep(h);
  spook::RigidBodyRef ball = new spook::RigidBody("ball");
  ball->getMassProperties()->setMass(2.0);
  ball->setPosition(x0);
  ball->setVelocity(v0);
  sim->add(ball);
  for (int i = 0; i < n; ++i) sim->stepForward();

  const spook::Vec3 v = v0 + n * h * g;
  const spook::Vec3 x = x0 + n * h * v0 + h * h * g * (n * (n + 1) / 2.0);
  expectNear("velocity after 120 steps", ball->getVelocity(), v, 1e-12);
  expectNear("position after 120 steps", ball->getPosition(), x, 1e-12);
  expectNear("time stamp after 120 steps", sim->getTimeStamp(), n * h, 1e-12);

  // Second TU: a 3 kg box of half extents (0.5, 1, 2) m, I_xx = m (b² + c²) / 3.
  const double inertia = boxInertiaX(0.5, 1.0, 2.0, 3.0), exact = 3.0 * (1.0 + 4.0) / 3.0;
  if (!(std::abs(inertia - exact) <= 1e-12 * exact)) {
    std::printf("FAIL: box inertia from the second translation unit %.17g, exact %.17g\n", inertia, exact);
    ++failures;
  }

  if (failures != 0) {
    std::printf("%d check(s) failed\n", failures);
    return 1;
  }
  std::printf("single header: free fall matches the exact discrete solution\n");
  return 0;
}
