#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <string>
#include <vector>

#include <spook/collide/shapes/capsule.hpp>
#include <spook/collide/shapes/height_field.hpp>
#include <spook/collide/shapes/trimesh.hpp>

#include "contact_scenes.hpp"
#include "tolerance.hpp"

// Continuous collision detection (collide/continuous.hpp): a fast body that
// opts in is stopped at its first contact instead of passing through.

namespace {

enum class Kind { SPHERE, BOX, CAPSULE };
enum class Wall { BOX, PLANE, TRIMESH };

constexpr std::array<Kind, 3> kKinds = {Kind::SPHERE, Kind::BOX, Kind::CAPSULE};
constexpr std::array<double, 3> kSpeeds = {10.0, 100.0, 500.0};         // m/s
constexpr std::array<double, 3> kThicknesses = {0.01, 0.1, 1.0};         // m
constexpr double kRadius = 0.1;                                          // m, and the box's half extent

const char* nameOf(Kind k) { return k == Kind::SPHERE ? "sphere" : k == Kind::BOX ? "box" : "capsule"; }
const char* nameOf(Wall w) { return w == Wall::BOX ? "box" : w == Wall::PLANE ? "plane" : "trimesh"; }

// A closed box mesh [lo, hi], outward counter-clockwise triangles.
template <class S>
spook::ref_ptr<spook::TrimeshT<S>> boxMesh(const spook::Vec3T<S>& lo, const spook::Vec3T<S>& hi) {
  std::vector<spook::Vec3T<S>> v;
  for (int i = 0; i < 8; ++i)
    v.emplace_back(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
  const std::vector<std::array<int, 3>> t = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                                             {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return new spook::TrimeshT<S>(v, t);
}

// A wall whose near face is the plane x = 0, `thickness` m deep along +x
// (a plane is a half-space: no far side), 4 m tall and wide.
template <class S>
spook::ref_ptr<spook::GeometryT<S>> makeWall(Wall wall, double thickness) {
  using Vec3 = spook::Vec3T<S>;
  if (wall == Wall::PLANE) return new spook::GeometryT<S>(new spook::PlaneT<S>(Vec3(-1, 0, 0)));
  if (wall == Wall::TRIMESH)
    return new spook::GeometryT<S>(boxMesh<S>(Vec3(S(0), S(-2), S(-2)), Vec3(S(thickness), S(2), S(2))));
  auto g = new spook::GeometryT<S>(new spook::BoxT<S>(Vec3(S(thickness / 2), S(2), S(2))));
  g->setPosition(Vec3(S(thickness / 2), S(0), S(0)));
  return g;
}

template <class S>
spook::ShapeT<S>* makeShape(Kind kind) {
  if (kind == Kind::SPHERE) return new spook::SphereT<S>(S(kRadius));
  if (kind == Kind::BOX) return new spook::BoxT<S>(spook::Vec3T<S>::Constant(S(kRadius)));
  return new spook::CapsuleT<S>(S(kRadius), S(3 * kRadius));  // axis along y, across the motion
}

struct Flight {
  double maxCenter = -1e9;  ///< largest center x over the run (m)
  double finalCenter = 0;   ///< center x at the end (m)
  int contactSteps = 0;     ///< steps whose contacts include body–wall
};

// A body launched along +x at `speed` from 2 m in front of the wall, 40 steps at 60 Hz.
template <class S>
Flight fly(Kind kind, Wall wall, double speed, double thickness, bool ccd) {
  spook::ref_ptr<spook::SimulationT<S>> sim = new spook::SimulationT<S>();
  sim->add(makeWall<S>(wall, thickness));
  spook::ref_ptr<spook::RigidBodyT<S>> body = new spook::RigidBodyT<S>("projectile");
  body->add(new spook::GeometryT<S>(makeShape<S>(kind)));
  body->setPosition(spook::Vec3T<S>(S(-2), S(0), S(0)));
  body->setVelocity(spook::Vec3T<S>(S(speed), S(0), S(0)));
  body->setEnableCCD(ccd);
  sim->add(body);
  Flight f;
  for (int step = 0; step < 40; ++step) {
    sim->stepForward();
    f.maxCenter = std::max(f.maxCenter, double(body->getPosition().x()));
    for (const auto& c : sim->getGeometryContacts())
      if (c.rigidBody(0) == body.get() || c.rigidBody(1) == body.get()) {
        ++f.contactSteps;
        break;
      }
  }
  f.finalCenter = double(body->getPosition().x());
  return f;
}

// A body that stays on the near side: its center never reaches the near
// face (the discrete contacts would then push it out the far side), it ends
// in front of the wall, and it touched the wall.
template <class S>
void checkStopped(Wall wall, const std::vector<Kind>& kinds, const std::vector<double>& thicknesses) {
  for (Kind kind : kinds)
    for (double speed : kSpeeds)
      for (double thickness : thicknesses) {
        const std::string what = std::string(nameOf(kind)) + " into a " + nameOf(wall) + " wall";
        CAPTURE(what);
        CAPTURE(speed);
        CAPTURE(thickness);
        const Flight f = fly<S>(kind, wall, speed, thickness, true);
        CHECK(f.maxCenter < 0.0);
        CHECK(f.finalCenter < -kRadius);
        CHECK(f.finalCenter > -2.0);
        CHECK(f.contactSteps > 0);
      }
}

}  // namespace

TEST_CASE_TEMPLATE("fast spheres, boxes and capsules with CCD never pass through static box walls", S, float, double) {
  checkStopped<S>(Wall::BOX, {kKinds.begin(), kKinds.end()}, {kThicknesses.begin(), kThicknesses.end()});
}

TEST_CASE_TEMPLATE("fast spheres, boxes and capsules with CCD stop at a plane and never sink far into it", S, float,
                   double) {
  checkStopped<S>(Wall::PLANE, {kKinds.begin(), kKinds.end()}, {1.0});
}

TEST_CASE_TEMPLATE("fast spheres, boxes and capsules with CCD never pass through closed trimesh walls", S, float,
                   double) {
  checkStopped<S>(Wall::TRIMESH, {kKinds.begin(), kKinds.end()}, {kThicknesses.begin(), kThicknesses.end()});
}

TEST_CASE_TEMPLATE("without CCD a fast sphere tunnels through a 1 m box wall (CCD is opt-in)", S, float, double) {
  CHECK_FALSE(spook::ref_ptr<spook::RigidBodyT<S>>(new spook::RigidBodyT<S>())->getEnableCCD());
  const Flight f = fly<S>(Kind::SPHERE, Wall::BOX, 100.0, 1.0, false);
  MESSAGE("without CCD the sphere ends at x = ", f.finalCenter, " m, the wall spans [0, 1] m");
  CHECK(f.finalCenter > 1.0 + kRadius);
  CHECK(f.contactSteps == 0);
}

// A height field is solid below its surface: the body's center must stay
// above it (the discrete contacts push a center below a face further down
// through a trimesh, but up out of a height field).
TEST_CASE_TEMPLATE("fast spheres, boxes and capsules with CCD dropped onto a height field at 10-500 m/s stay above it",
                   S, float, double) {
  using Vec3 = spook::Vec3T<S>;
  // A 10 m × 10 m field of gentle waves, heights within ±0.1 m.
  constexpr std::size_t n = 21;
  std::vector<S> heights(n * n);
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = 0; i < n; ++i) heights[i + n * j] = S(0.1 * std::sin(0.7 * double(i)) * std::cos(0.9 * double(j)));
  for (Kind kind : kKinds)
    for (double speed : kSpeeds) {
      const std::string what = nameOf(kind);
      CAPTURE(what);
      CAPTURE(speed);
      spook::ref_ptr<spook::SimulationT<S>> sim = new spook::SimulationT<S>();
      spook::ref_ptr<spook::HeightFieldT<S>> field = new spook::HeightFieldT<S>(n, n, S(10), S(10), heights);
      sim->add(new spook::GeometryT<S>(field));
      spook::ref_ptr<spook::RigidBodyT<S>> body = new spook::RigidBodyT<S>("projectile");
      body->add(new spook::GeometryT<S>(makeShape<S>(kind)));
      body->setPosition(Vec3(S(0.3), S(-0.2), S(2)));
      body->setVelocity(Vec3(S(0), S(0), S(-speed)));
      body->setEnableCCD(true);
      sim->add(body);
      double lowest = 1e9;
      for (int step = 0; step < 40; ++step) {
        sim->stepForward();
        const Vec3 p = body->getPosition();
        lowest = std::min(lowest, double(p.z() - field->heightAt(p.x(), p.y())));
      }
      MESSAGE(what, " at ", speed, " m/s: lowest center height above the surface ", lowest, " m");
      CHECK(lowest > 0.0);
    }
}

namespace {

// Positions and velocities of every step, for bit-for-bit comparisons.
template <class S>
std::vector<spook::Vec3T<S>> trajectory(spook::SimulationT<S>& sim, spook::RigidBodyT<S>& body, int steps) {
  std::vector<spook::Vec3T<S>> out;
  for (int step = 0; step < steps; ++step) {
    sim.stepForward();
    out.push_back(body.getPosition());
    out.push_back(body.getVelocity());
    out.push_back(body.getAngularVelocity());
  }
  return out;
}

}  // namespace

TEST_CASE_TEMPLATE("enabling CCD leaves slow bodies, free flight and fast sliding bit-for-bit unchanged", S, float,
                   double) {
  using Vec3 = spook::Vec3T<S>;
  struct Scene {
    const char* name;
    Kind kind;
    Vec3 position, velocity;
  };
  const std::vector<Scene> scenes = {
      {"sphere dropped from 1 m", Kind::SPHERE, Vec3(S(0), S(0), S(1)), Vec3::Zero()},
      {"box thrown at 5 m/s", Kind::BOX, Vec3(S(0), S(0), S(0.5)), Vec3(S(5), S(0), S(1))},
      {"sphere in free flight at 100 m/s", Kind::SPHERE, Vec3(S(0), S(0), S(100)), Vec3(S(100), S(0), S(0))},
      {"box sliding on the ground at 30 m/s", Kind::BOX, Vec3(S(0), S(0), S(kRadius)), Vec3(S(30), S(0), S(0))},
      {"capsule rolling on the ground at 30 m/s", Kind::CAPSULE, Vec3(S(0), S(0), S(kRadius)), Vec3(S(30), S(0), S(0))}};
  for (const Scene& scene : scenes) {
    CAPTURE(scene.name);
    std::array<std::vector<Vec3>, 2> runs;
    for (int ccd = 0; ccd < 2; ++ccd) {
      spook::ref_ptr<spook::SimulationT<S>> sim = new spook::SimulationT<S>();
      spook::ref_ptr<spook::MaterialT<S>> ground = new spook::MaterialT<S>("ground");
      spook::test::addGround(*sim, ground);
      auto body = spook::test::addBody(*sim, "body", makeShape<S>(scene.kind), ground, scene.position);
      body->setVelocity(scene.velocity);
      body->setEnableCCD(ccd == 1);
      runs[std::size_t(ccd)] = trajectory(*sim, *body, 120);
    }
    CHECK(runs[0] == runs[1]);
  }
}
