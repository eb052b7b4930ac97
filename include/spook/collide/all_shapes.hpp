#pragma once

#include <spook/collide/shape_list.hpp>
#include <spook/collide/shapes/box.hpp>
#include <spook/collide/shapes/capsule.hpp>
#include <spook/collide/shapes/composite.hpp>
#include <spook/collide/shapes/convex.hpp>
#include <spook/collide/shapes/cylinder.hpp>
#include <spook/collide/shapes/height_field.hpp>
#include <spook/collide/shapes/line.hpp>
#include <spook/collide/shapes/plane.hpp>
#include <spook/collide/shapes/sphere.hpp>
#include <spook/collide/shapes/trimesh.hpp>

namespace spook {

/// Every shape type, in the order of the seeds' collider table: the default
/// shape list of a Space and a Simulation.
using AllShapes =
    ShapeList<BoxT, CapsuleT, ConvexT, CylinderT, LineT, PlaneT, SphereT, TrimeshT, CompositeT, HeightFieldT>;

}  // namespace spook
