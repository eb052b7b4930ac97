#pragma once

// spook: header-only SPOOK multibody dynamics. Include this umbrella header,
// or single_include/spook/spook.hpp, its generated amalgamation.

#include <spook/collide/all_shapes.hpp>
#include <spook/collide/bounding_box.hpp>
#include <spook/collide/collider_matrix.hpp>
#include <spook/collide/contact_reduction.hpp>
#include <spook/collide/geometry.hpp>
#include <spook/collide/geometry_contact.hpp>
#include <spook/collide/shapes/box.hpp>
#include <spook/collide/shapes/capsule.hpp>
#include <spook/collide/shapes/composite.hpp>
#include <spook/collide/shapes/cylinder.hpp>
#include <spook/collide/shapes/shape.hpp>
#include <spook/collide/shapes/sphere.hpp>
#include <spook/collide/space.hpp>
#include <spook/constraints/constraint.hpp>
#include <spook/constraints/joints/ball_joint.hpp>
#include <spook/constraints/joints/cylindrical_joint.hpp>
#include <spook/constraints/joints/distance_joint.hpp>
#include <spook/constraints/joints/dot1_joint.hpp>
#include <spook/constraints/joints/hinge.hpp>
#include <spook/constraints/joints/lock_joint.hpp>
#include <spook/constraints/joints/prismatic.hpp>
#include <spook/constraints/joints/slack_joints.hpp>
#include <spook/constraints/joints/universal_joint.hpp>
#include <spook/constraints/regularization.hpp>
#include <spook/core/error.hpp>
#include <spook/core/frame.hpp>
#include <spook/core/math.hpp>
#include <spook/core/observer_ptr.hpp>
#include <spook/core/ref_ptr.hpp>
#include <spook/core/referenced.hpp>
#include <spook/core/scalar.hpp>
#include <spook/dynamics/gravity_field.hpp>
#include <spook/dynamics/material.hpp>
#include <spook/dynamics/mass_properties.hpp>
#include <spook/dynamics/rigid_body.hpp>
#include <spook/sim/assembly.hpp>
#include <spook/sim/collection.hpp>
#include <spook/sim/contact_event_listener.hpp>
#include <spook/sim/simulation.hpp>
#include <spook/sim/statistics.hpp>
#include <spook/sim/step_event_listener.hpp>
#include <spook/solver/solver.hpp>
