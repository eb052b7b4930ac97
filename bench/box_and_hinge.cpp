// The compile-time probe of the core (issue 19): one box on one hinge to
// the world, stepped 1 s. What a program pays to compile spook, timed on
// its own (spook compiled once, then header-only):
//   /usr/bin/time g++ -std=c++20 -O2 -DSPOOK_EXTERN_TEMPLATES -Iinclude -isystem /usr/include/eigen3
//       bench/box_and_hinge.cpp build/libspook_compiled.a -lccd
//   /usr/bin/time g++ -std=c++20 -O2 -Iinclude -isystem /usr/include/eigen3 bench/box_and_hinge.cpp -lccd
// (CMake targets box_and_hinge and box_and_hinge_header_only, not built by default.)
#include <spook/spook.hpp>

#include <cstdio>

int main() {
  spook::SimulationRef sim = new spook::Simulation();
  spook::RigidBodyRef box = new spook::RigidBody(new spook::Geometry(new spook::Box(spook::Vec3(0.25, 0.05, 0.05))));
  box->setPosition(0.25, 0, 0);
  sim->add(box);
  // The hinge axis is the frame's z axis, turned onto the world's y axis.
  spook::FrameRef frame = new spook::Frame();
  frame->setLocalTranslate(spook::Vec3(-0.25, 0, 0));
  frame->setLocalRotate(spook::Quat(Eigen::AngleAxisd(spook::PI_2, spook::Vec3::UnitX())));
  spook::HingeRef hinge = new spook::Hinge(box.get(), frame.get());
  sim->add(hinge);
  for (int i = 0; i < 60; ++i) sim->stepForward();
  std::printf("box center after 1 s: (%.4f, %.4f, %.4f) m\n", box->getPosition().x(), box->getPosition().y(),
              box->getPosition().z());
  return 0;
}
