#pragma once

// Small contact scenes shared by the contact tests and their solver policies.

#include <string>

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
