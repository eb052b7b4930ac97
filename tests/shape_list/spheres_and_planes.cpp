// A scene declared with spheres and planes only. Built three ways:
//   (default)              spheres and planes: compiles, runs, checks a contact
//   -DSPOOK_ADD_A_BOX      collides a box through the same list: must NOT
//                          compile (a static_assert names the problem)
//   -DSPOOK_ALL_SHAPES     the same scene with every shape type, for the
//                          compile-time and binary-size comparison in bench/
#include <cstdio>
#include <vector>

#include <spook/collide/space.hpp>

#ifdef SPOOK_ALL_SHAPES
using Shapes = spook::AllShapes;
#else
using Shapes = spook::ShapeList<spook::SphereT, spook::PlaneT>;
#endif
using Matrix = spook::ColliderMatrixT<double, Shapes>;

int main() {
  spook::SpaceRef space = new spook::Space(Shapes{});
  space->add(new spook::Geometry(new spook::Plane(spook::Vec3::UnitZ())));
  spook::RigidBodyRef body = new spook::RigidBody("ball");
  spook::GeometryRef ball = new spook::Geometry(new spook::Sphere(0.5));
  body->add(ball);
  body->setPosition(0, 0, 0.4);
  space->update({body});
  std::vector<spook::ContactPointT<double>> points;
  spook::ContactSinkT<double> sink(points);
  const spook::Transform X = spook::Transform::Identity();
#ifdef SPOOK_ADD_A_BOX
  spook::BoxRef box = new spook::Box(spook::Vec3::Ones());
  Matrix::collide(*box, X, *static_cast<spook::Sphere*>(ball->getShape()), X, sink);
#else
  spook::PlaneRef ground = new spook::Plane(spook::Vec3::UnitZ());
  Matrix::collide(*static_cast<spook::Sphere*>(ball->getShape()), X, *ground, X, sink);
#endif
  const bool ok = space->getGeometryContacts().size() == 1 && points.size() == 1;
  std::printf("%s\n", ok ? "spheres and planes collide" : "unexpected contacts");
  return ok ? 0 : 1;
}
