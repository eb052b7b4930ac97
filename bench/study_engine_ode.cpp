// The contact study's scenes in ODE (compiled when CMake finds the `ode`
// package): a hash space, contact joints with a Coulomb friction pyramid, and
// the world stepped by QuickStep (SOR, 20 iterations) or by dWorldStep (the
// Dantzig LCP), with ODE's default ERP (0.2) and CFM (1e-10 in the double
// precision build, 1e-5 in the single one).
#include <algorithm>
#include <array>
#include <memory>
#include <type_traits>
#include <vector>

#include <ode/ode.h>

#include "study_engine.hpp"

namespace {

enum class OdeStepper { QUICK_STEP, WORLD_STEP };

/// ODE's global data: initialised before the first engine, released at exit.
void initialiseOde() {
  struct OdeLibrary {
    OdeLibrary() { dInitODE2(0); }
    ~OdeLibrary() { dCloseODE(); }
  };
  static const OdeLibrary library;
}

struct WorldDeleter {
  void operator()(dWorldID world) const { dWorldDestroy(world); }
};
struct SpaceDeleter {
  void operator()(dSpaceID space) const { dSpaceDestroy(space); }
};
struct JointGroupDeleter {
  void operator()(dJointGroupID group) const { dJointGroupDestroy(group); }
};
using WorldPtr = std::unique_ptr<std::remove_pointer_t<dWorldID>, WorldDeleter>;
using SpacePtr = std::unique_ptr<std::remove_pointer_t<dSpaceID>, SpaceDeleter>;
using JointGroupPtr = std::unique_ptr<std::remove_pointer_t<dJointGroupID>, JointGroupDeleter>;

// Box-box and box-plane pairs give up to 4 points for a resting face, more
// while an edge crosses a face.
constexpr int kMaxContactsPerPair = 8;

class OdeEngine final : public study::Engine {
 public:
  OdeEngine(const study::SceneDescription& scene, OdeStepper stepper)
      : stepper_(stepper), timeStep_(scene.timeStep), friction_(scene.friction) {
    initialiseOde();
    dAllocateODEDataForThread(dAllocateMaskAll);
    world_.reset(dWorldCreate());
    space_.reset(dHashSpaceCreate(nullptr));
    contactJoints_.reset(dJointGroupCreate(0));
    dWorldSetGravity(world_.get(), 0, 0, scene.gravity);
    for (const study::BodySpec& spec : scene.bodies) add(spec, scene.density);
  }

  void step() override {
    lastContacts_ = {};
    dSpaceCollide(space_.get(), this, &OdeEngine::nearCallback);
    const int stepped = stepper_ == OdeStepper::QUICK_STEP ? dWorldQuickStep(world_.get(), timeStep_)
                                                           : dWorldStep(world_.get(), timeStep_);
    healthy_ = healthy_ && stepped != 0;  // 0: ODE could not allocate the step's memory
    dJointGroupEmpty(contactJoints_.get());
  }

  study::Point position(std::size_t dynamicIndex) const override {
    const dReal* p = dBodyGetPosition(bodies_[dynamicIndex]);
    return {p[0], p[1], p[2]};
  }

  double kineticEnergy() const override {
    double energy = 0.0;
    for (dBodyID body : bodies_) {
      dMass mass;
      dBodyGetMass(body, &mass);
      const dReal* v = dBodyGetLinearVel(body);
      const dReal* omega = dBodyGetAngularVel(body);
      dVector3 bodyOmega;  // mass.I is about the body axes
      dBodyVectorFromWorld(body, omega[0], omega[1], omega[2], bodyOmega);
      energy += 0.5 * mass.mass * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
      for (int row = 0; row < 3; ++row)
        for (int column = 0; column < 3; ++column)
          energy += 0.5 * bodyOmega[row] * mass.I[4 * row + column] * bodyOmega[column];
    }
    return energy;
  }

  /// The contacts of the last step's collision pass, which ODE runs on the
  /// positions at the start of the step.
  study::ContactSummary contacts() const override { return lastContacts_; }

  bool healthy() const override { return healthy_; }

 private:
  void add(const study::BodySpec& spec, double density) {
    dGeomID geom = nullptr;
    dMass mass;
    switch (spec.shape) {
      case study::ShapeType::PLANE:
        dCreatePlane(space_.get(), 0, 0, 1, 0);
        return;
      case study::ShapeType::BOX: {
        const auto& half = spec.halfExtents;
        geom = dCreateBox(space_.get(), 2 * half[0], 2 * half[1], 2 * half[2]);
        dMassSetBox(&mass, density, 2 * half[0], 2 * half[1], 2 * half[2]);
        break;
      }
      case study::ShapeType::SPHERE:
        geom = dCreateSphere(space_.get(), spec.radius);
        dMassSetSphere(&mass, density, spec.radius);
        break;
    }
    const auto& p = spec.position;
    if (!spec.dynamic) {
      dGeomSetPosition(geom, p[0], p[1], p[2]);
      return;
    }
    dBodyID body = dBodyCreate(world_.get());
    dBodySetMass(body, &mass);
    dBodySetPosition(body, p[0], p[1], p[2]);
    dGeomSetBody(geom, body);
    bodies_.push_back(body);
  }

  static void nearCallback(void* engine, dGeomID a, dGeomID b) { static_cast<OdeEngine*>(engine)->collide(a, b); }

  void collide(dGeomID a, dGeomID b) {
    const dBodyID bodyA = dGeomGetBody(a), bodyB = dGeomGetBody(b);
    if (bodyA == nullptr && bodyB == nullptr) return;
    std::array<dContact, kMaxContactsPerPair> found{};
    const int count = dCollide(a, b, kMaxContactsPerPair, &found[0].geom, sizeof(dContact));
    for (int i = 0; i < count; ++i) {
      dContact& contact = found[std::size_t(i)];
      // Approx1: mu is a Coulomb coefficient, the friction pyramid's bound
      // scaled by the contact's normal force (without it, mu is a force).
      // No dContactBounce, and the contact keeps the world's ERP and CFM.
      contact.surface.mode = dContactApprox1;
      contact.surface.mu = friction_;
      dJointAttach(dJointCreateContact(world_.get(), contactJoints_.get(), &contact), bodyA, bodyB);
      ++lastContacts_.points;
      lastContacts_.deepest = std::max(lastContacts_.deepest, double(contact.geom.depth));
    }
  }

  OdeStepper stepper_;
  dReal timeStep_, friction_;
  // Destroyed bottom-up: the contact joints, then the space with its geoms,
  // then the world with its bodies.
  WorldPtr world_;
  SpacePtr space_;
  JointGroupPtr contactJoints_;
  std::vector<dBodyID> bodies_;
  study::ContactSummary lastContacts_;
  bool healthy_ = true;
};

}  // namespace

std::vector<study::ReferenceEngine> study::odeEngines() {
  return {
      {"ode quick",
       [](const SceneDescription& scene) -> std::unique_ptr<Engine> {
         return std::make_unique<OdeEngine>(scene, OdeStepper::QUICK_STEP);
       }},
      {"ode world",
       [](const SceneDescription& scene) -> std::unique_ptr<Engine> {
         return std::make_unique<OdeEngine>(scene, OdeStepper::WORLD_STEP);
       }},
  };
}
