// A crank–rocker four-bar with solid links, the way machines are drawn:
// 1 kg box links 6 cm thick that overlap at their pins (crank 0.2 m,
// coupler 1 m, rocker 0.8 m, ground pins 0.9 m apart), the crank driven by
// its hinge motor at 2 rad/s under gravity. Jointed bodies do not collide
// with each other (issue 25), so the joints close. Prints the motor torque
// over one revolution beside the power balance τ·ω = d/dt(kinetic +
// potential energy of the links), and exits non-zero unless the two agree,
// averaged over 0.1 s windows, within 1% of the motor's RMS power, and the
// pins stay closed within 1e-5 m.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <spook/spook.hpp>

namespace {

constexpr double kG = 9.80665;     // m/s²
constexpr double kSpeed = 2.0;     // motor speed, rad/s
constexpr double kThickness = 0.06;  // m

spook::RigidBodyRef addLink(spook::Simulation& sim, const spook::Vec3& a, const spook::Vec3& b, const char* name) {
  const spook::Vec3 d = b - a;
  spook::RigidBodyRef body = new spook::RigidBody(
      new spook::Geometry(new spook::Box(spook::Vec3(0.5 * (d.norm() + kThickness), 0.5 * kThickness, 0.5 * kThickness))),
      name);
  body->getMassProperties()->setMass(1.0);
  body->setPosition(0.5 * (a + b));
  body->setRotation(spook::rotate(spook::Vec3(spook::X_AXIS), d));
  sim.add(body);
  return body;
}

spook::HingeRef addPin(spook::Simulation& sim, const spook::Vec3& point, spook::RigidBody* body1,
                       spook::RigidBody* body2 = nullptr) {
  spook::HingeRef hinge =
      spook::Constraint::createFromWorld<spook::Hinge>(point, spook::Vec3(spook::Y_AXIS), body1, body2);
  sim.add(spook::ConstraintRef(hinge.get()));
  return hinge;
}

// Kinetic plus potential energy of the links (J), gravity along −z. The
// stepper's velocities are those of the step just taken, half a step
// behind its positions (x⁺ = x + h v⁺, symplectic Euler), so the potential
// energy is taken half a step back too, at x − h v/2, where the velocities
// and the motor's impulse belong; at the step's end it would lead the
// kinetic energy by h/2 and the balance by h/2 · dP/dt (2.6% of the RMS
// power here).
double energy(const std::vector<spook::RigidBodyRef>& links, double h) {
  double sum = 0.0;
  for (const auto& link : links) {
    const double m = link->getMassProperties()->getMass();
    const spook::Mat3 R = link->getCmRotation().toRotationMatrix();
    const spook::Vec3 omega = R.transpose() * link->getAngularVelocity();
    const double height = link->getCmPosition().z() - 0.5 * h * link->getVelocity().z();
    sum += 0.5 * m * link->getVelocity().squaredNorm() +
           0.5 * omega.dot(link->getMassProperties()->getInertiaTensor() * omega) + m * kG * height;
  }
  return sum;
}

}  // namespace

int main() {
  spook::SimulationRef sim = new spook::Simulation();
  sim->setSolver(new spook::DirectSolver());  // the pins to 1e-5 m (the default hybrid: 1e-3 m)
  const double h = sim->getTimeStep();
  // Pins: a (crank to ground) at the origin, b (crank–coupler) above it,
  // d (rocker to ground) at 0.9 m, c (coupler–rocker) where |c − b| = 1 and
  // |c − d| = 0.8 above the ground line.
  const spook::Vec3 a(0, 0, 0), b(0, 0, 0.2), d(0.9, 0, 0);
  const double bd = (d - b).norm(), along = (1.0 + bd * bd - 0.64) / (2.0 * bd);
  const spook::Vec3 u = (d - b) / bd, up(-u.z(), 0, u.x());
  const spook::Vec3 c = b + along * u + std::sqrt(1.0 - along * along) * up;

  std::vector<spook::RigidBodyRef> links = {addLink(*sim, a, b, "crank"), addLink(*sim, b, c, "coupler"),
                                            addLink(*sim, d, c, "rocker")};
  std::vector<spook::HingeRef> pins = {addPin(*sim, a, links[0]), addPin(*sim, b, links[0], links[1]),
                                       addPin(*sim, c, links[1], links[2]), addPin(*sim, d, links[2])};
  spook::Motor1D* motor = pins[0]->getMotor1D();
  motor->setEnable(true);
  motor->setSpeed(kSpeed);

  // Settle for 1 s, then one revolution in 0.1 s windows.
  sim->stepTo(1.0);
  const int windowSteps = int(std::lround(0.1 / h));
  const int windows = int(std::ceil(2.0 * spook::PI / kSpeed / (windowSteps * h)));
  std::vector<double> motorPower, energyRate;
  double worstGap = 0.0, worstSpeed = 0.0;
  std::printf("  t (s)   crank (rad)   torque (N m)   tau*omega (W)   dE/dt (W)\n");
  for (int w = 0; w < windows; ++w) {
    const double before = energy(links, h);
    double work = 0.0, torque = 0.0;
    for (int k = 0; k < windowSteps; ++k) {
      sim->stepForward();
      // The motor's impulse over the step, as a torque, does work at the
      // crank's speed at the end of the step (at which the impulse acts).
      torque = motor->getCurrentForce();
      work += torque * pins[0]->getCurrentSpeed() * h;
      for (const auto& pin : pins) {
        const double gap = (pin->getAttachmentFrame(0)->getTranslate() - pin->getAttachmentFrame(1)->getTranslate()).norm();
        worstGap = std::max(worstGap, gap);
      }
      worstSpeed = std::max(worstSpeed, std::abs(std::abs(pins[0]->getCurrentSpeed()) - kSpeed) / kSpeed);
    }
    const double seconds = windowSteps * h;
    motorPower.push_back(work / seconds);
    energyRate.push_back((energy(links, h) - before) / seconds);
    std::printf("%7.2f %12.3f %14.4f %15.4f %11.4f\n", sim->getTimeStamp(), pins[0]->getAngle(), torque,
                motorPower.back(), energyRate.back());
  }
  double rms = 0.0, worstMismatch = 0.0;
  for (std::size_t w = 0; w < motorPower.size(); ++w) {
    rms += motorPower[w] * motorPower[w];
    worstMismatch = std::max(worstMismatch, std::abs(motorPower[w] - energyRate[w]));
  }
  rms = std::sqrt(rms / double(motorPower.size()));
  const double relative = worstMismatch / rms;
  std::printf("motor RMS power %.4f W; worst window mismatch %.3g W (%.3g%% of RMS); worst pin gap %.3g m; "
              "crank speed within %.3g%% of %g rad/s\n",
              rms, worstMismatch, 100.0 * relative, worstGap, 100.0 * worstSpeed, kSpeed);
  return relative <= 0.01 && worstGap <= 1e-5 && worstSpeed <= 0.005 ? 0 : 1;
}
