// The contact study's scenes described without any engine, and the small
// interface through which bench/contact_study steps and measures them: spook
// and, when their packages are installed, Bullet and ODE (one adapter each,
// bench/study_engine_bullet.cpp and bench/study_engine_ode.cpp), so that all
// engines run the same bodies, measured the same way, in one program.
#pragma once

#include <array>
#include <cstddef>
#include <memory>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

namespace study {

using Point = std::array<double, 3>;

enum class ShapeType { PLANE, BOX, SPHERE };

/// One body of a scene. PLANE: the ground z = 0, solid below (always
/// static). BOX: half extents (m). SPHERE: radius (m). A dynamic body has
/// density `SceneDescription::density`; a static one never moves.
struct BodySpec {
  ShapeType shape = ShapeType::BOX;
  Point halfExtents{};  ///< BOX
  double radius = 0.0;  ///< SPHERE
  Point position{};     ///< center, world (m)
  bool dynamic = true;
};

/// The volume of a box or sphere (m³); a plane has none.
inline double volumeOf(const BodySpec& spec) {
  switch (spec.shape) {
    case ShapeType::BOX:
      return 8.0 * spec.halfExtents[0] * spec.halfExtents[1] * spec.halfExtents[2];
    case ShapeType::SPHERE:
      return 4.0 / 3.0 * std::numbers::pi * spec.radius * spec.radius * spec.radius;
    case ShapeType::PLANE:
      break;
  }
  return 0.0;
}

struct SceneDescription {
  std::vector<BodySpec> bodies;
  double friction = 0.5;         ///< Coulomb coefficient of every pair
  double density = 1000.0;       ///< kg/m³
  double gravity = -9.80665;     ///< m/s² along z
  double timeStep = 1.0 / 60.0;  ///< s
};

/// Enabled contact points after the last step and the deepest (m, ≥ 0).
struct ContactSummary {
  std::size_t points = 0;
  double deepest = 0.0;
};

/// Time an engine's constraint solver spent and the row updates it made
/// (rows × sweeps), summed over the steps taken; `sweepsOnly` false where a
/// step solved rows otherwise (spook's direct parts), which makes the time
/// per row update meaningless.
struct SolverCost {
  double seconds = 0.0;
  double rowUpdates = 0.0;
  bool sweepsOnly = true;
};

/// A scene built in one engine with one solver setting. Dynamic bodies are
/// numbered in the order they appear in the description.
class Engine {
 public:
  virtual ~Engine() = default;
  virtual void step() = 0;
  virtual Point position(std::size_t dynamicIndex) const = 0;  ///< center of mass, world (m)
  virtual double kineticEnergy() const = 0;                    ///< Σ ½vᵀMv + ½ωᵀIω (J)
  virtual ContactSummary contacts() const = 0;
  /// False once the engine reports a failure of its own (spook: an island
  /// dropped or a body frozen); non-finite states are checked by the caller.
  virtual bool healthy() const { return true; }
  /// Zero where the engine does not tell.
  virtual SolverCost solverCost() const { return {}; }
};

/// A solver setting of another engine: its name in the study's table and a
/// factory for a scene.
struct ReferenceEngine {
  std::string name;
  std::unique_ptr<Engine> (*make)(const SceneDescription&);
};

/// The settings of each reference engine built in (empty when its package
/// was not found at configure time).
std::vector<ReferenceEngine> bulletEngines();
std::vector<ReferenceEngine> odeEngines();

}  // namespace study
