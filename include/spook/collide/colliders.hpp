#pragma once

// Every analytic collider. The collider matrix includes them all so that a
// pair means the same collider in every translation unit; only the pairs of
// a shape list that is used get instantiated.

#include <spook/collide/colliders/box_box.hpp>
#include <spook/collide/colliders/box_capsule.hpp>
#include <spook/collide/colliders/box_cylinder.hpp>
#include <spook/collide/colliders/box_line.hpp>
#include <spook/collide/colliders/box_plane.hpp>
#include <spook/collide/colliders/box_sphere.hpp>
#include <spook/collide/colliders/capsule_capsule.hpp>
#include <spook/collide/colliders/capsule_plane.hpp>
#include <spook/collide/colliders/capsule_sphere.hpp>
#include <spook/collide/colliders/convex_round.hpp>
#include <spook/collide/colliders/cylinder_plane.hpp>
#include <spook/collide/colliders/cylinder_sphere.hpp>
#include <spook/collide/colliders/line_plane.hpp>
#include <spook/collide/colliders/line_sphere.hpp>
#include <spook/collide/colliders/mesh.hpp>
#include <spook/collide/colliders/plane_sphere.hpp>
#include <spook/collide/colliders/polytopes.hpp>
#include <spook/collide/colliders/sphere_sphere.hpp>
