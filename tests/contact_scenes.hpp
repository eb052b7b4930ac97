#pragma once

// Small contact scenes shared by the contact tests and their solver policies.

#include <string>
#include <vector>

#include <spook/collide/shapes/box.hpp>
#include <spook/collide/shapes/plane.hpp>
#include <spook/collide/shapes/sphere.hpp>
#include <spook/sim/simulation.hpp>

#include "policies.hpp"

namespace spook::test {

/// A static ground plane through the origin with normal `up`.
template <class S>
ref_ptr<GeometryT<S>> addGround(SimulationT<S>& sim, const ref_ptr<MaterialT<S>>& material,
                                const Vec3T<S>& up = Vec3T<S>::UnitZ()) {
  ref_ptr<GeometryT<S>> ground = new GeometryT<S>(new PlaneT<S>(up), TransformT<S>::Identity(), "ground");
  ground->setMaterial(material);
  sim.add(ground);
  return ground;
}

/// A dynamic body of one shape (mass from the material's density).
template <class S>
ref_ptr<RigidBodyT<S>> addBody(SimulationT<S>& sim, const char* name, ShapeT<S>* shape,
                               const ref_ptr<MaterialT<S>>& material, const Vec3T<S>& position,
                               const QuatT<S>& rotation = QuatT<S>::Identity()) {
  ref_ptr<GeometryT<S>> geometry = new GeometryT<S>(shape, TransformT<S>::Identity(), name);
  geometry->setMaterial(material);
  ref_ptr<RigidBodyT<S>> body = new RigidBodyT<S>(name);
  body->add(geometry);
  body->setPosition(position);
  body->setRotation(rotation);
  sim.add(body);
  return body;
}

/// A 4 × 4 × 4 lattice of spheres of radius 0.1 m at a pitch of 0.22 m,
/// its columns staggered by a few millimetres (so that the pile does not
/// stand as a lattice), above a box of four walls (static planes) 1.2 cm
/// wider than the lattice: a pile of 64 spheres once they fall.
template <class S>
std::vector<ref_ptr<RigidBodyT<S>>> addSpherePile(SimulationT<S>& sim, const ref_ptr<MaterialT<S>>& wallMaterial,
                                                  const ref_ptr<MaterialT<S>>& ballMaterial) {
  const S radius = S(0.1), pitch = S(0.22);
  constexpr int kGrid = 4;
  const S wall = pitch * S(kGrid - 1) / S(2) + radius + S(0.012);
  for (int axis = 0; axis < 2; ++axis)
    for (const S side : {S(-1), S(1)}) {
      Vec3T<S> inward = Vec3T<S>::Zero();
      inward[axis] = -side;
      ref_ptr<GeometryT<S>> plane = new GeometryT<S>(new PlaneT<S>(inward, -wall), TransformT<S>::Identity(), "wall");
      plane->setMaterial(wallMaterial);
      sim.add(plane);
    }
  std::vector<ref_ptr<RigidBodyT<S>>> balls;
  for (int i = 0; i < kGrid * kGrid * kGrid; ++i) {
    const int column = i % kGrid, row = (i / kGrid) % kGrid, layer = i / (kGrid * kGrid);
    const S shift = S(0.006) * S((i * 7) % 5 - 2);
    balls.push_back(
        addBody(sim, "ball", new SphereT<S>(radius), ballMaterial,
                Vec3T<S>((S(column) - S(kGrid - 1) / S(2)) * pitch + shift,
                         (S(row) - S(kGrid - 1) / S(2)) * pitch - shift, S(2) * radius + S(layer) * S(0.25))));
  }
  return balls;
}

/// Sum of the normal forces (N) of the contacts that involve `geometry`'s body.
template <class S>
S normalForceOn(const SimulationT<S>& sim, const RigidBodyT<S>* body) {
  S sum = S(0);
  for (const auto& c : sim.getGeometryContacts())
    if (c.rigidBody(0) == body || c.rigidBody(1) == body)
      for (const auto& p : c.points())
        if (p.enabled) sum += p.getNormalForceMagnitude();
  return sum;
}

}  // namespace spook::test
