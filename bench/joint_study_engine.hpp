// The joint study's scenes described without any engine (bodies with mass
// and principal inertia, hinges between them or to the world), and the
// small interface through which bench/joint_study steps and measures them:
// spook and, when its package is installed, Bullet
// (bench/joint_study_bullet.cpp), so that both run the same mechanism,
// measured the same way, in one program.
#pragma once

#include <array>
#include <memory>
#include <vector>

namespace joint_study {

using Point = std::array<double, 3>;

/// A body at rest, unrotated at the start: mass (kg), principal moments of
/// inertia about its body axes (kg m²), center of mass (world, m).
struct BodySpec {
  double mass = 1.0;
  Point inertia{};
  Point position{};
};

/// A hinge through `pivot` about `axis` (world, at the start) between
/// bodies[body1] and bodies[body2], or the world when body2 < 0.
struct HingeSpec {
  int body1 = 0;
  int body2 = -1;
  Point pivot{};
  Point axis{0, 1, 0};
};

struct Description {
  std::vector<BodySpec> bodies;
  std::vector<HingeSpec> hinges;
  double gravity = -9.80665;  ///< m/s² along z
  double timeStep = 1.0 / 60.0;
};

/// A description built in one engine with one solver setting; bodies are
/// numbered as in the description.
class Engine {
 public:
  virtual ~Engine() = default;
  virtual void step() = 0;
  /// A point fixed in body `body`, given relative to its center of mass in
  /// the body's start orientation, in world coordinates now (m).
  virtual Point worldPoint(int body, const Point& local) const = 0;
  virtual double kineticEnergy() const = 0;  ///< Σ ½vᵀMv + ½ωᵀIω (J)
};

#ifdef SPOOK_STUDY_BULLET
/// Bullet's btDiscreteDynamicsWorld with its sequential-impulse solver
/// (projected Gauss–Seidel) at `iterations` sweeps and its other defaults.
std::unique_ptr<Engine> makeBulletEngine(const Description& description, int iterations);
#endif

}  // namespace joint_study
