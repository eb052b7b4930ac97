#include <doctest/doctest.h>

#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <spook/collide/shapes/box.hpp>
#include <spook/collide/shapes/capsule.hpp>
#include <spook/collide/shapes/composite.hpp>
#include <spook/collide/shapes/cylinder.hpp>
#include <spook/collide/shapes/plane.hpp>
#include <spook/collide/shapes/sphere.hpp>

#include "shape_helpers.hpp"
#include "tolerance.hpp"

using spook::test::at;
using spook::test::checkRejects;

using spook::test::pick;

namespace {

template <class S>
void checkDiagonal(const spook::SPDMat3T<S>& inertia, double xx, double yy, double zz, S tol) {
  const spook::Mat3T<S>& I = inertia.matrix();
  CHECK(std::abs(I(0, 0) - S(xx)) <= tol * S(xx));
  CHECK(std::abs(I(1, 1) - S(yy)) <= tol * S(yy));
  CHECK(std::abs(I(2, 2) - S(zz)) <= tol * S(zz));
  CHECK((I - spook::Mat3T<S>(I.diagonal().asDiagonal())).norm() == S(0));
}

// Points spread over the surface of a convex shape, from its own support
// function along many directions; a support point must beat all of them.
template <class S, class Shape>
void checkSupportIsFarthest(const Shape& shape) {
  std::mt19937 rng(17);
  std::normal_distribution<double> n(0.0, 1.0);
  std::vector<spook::Vec3T<S>> directions, surface;
  for (int i = 0; i < 400; ++i) directions.emplace_back(S(n(rng)), S(n(rng)), S(n(rng)));
  for (const auto& d : directions) surface.push_back(shape.support(d));
  const spook::BoundingBoxT<S> box = shape.getBoundingBox();
  const S tol = pick<S>(1e-12, 1e-5);
  S worstExcess = S(0);  // how far some surface point lies beyond the support plane
  bool allInBox = true;
  for (const auto& d : directions) {
    const spook::Vec3T<S> p = shape.support(d);
    allInBox = allInBox && box.contains(p, tol);
    for (const auto& q : surface) worstExcess = std::max(worstExcess, (q - p).dot(d) / d.norm());
  }
  CHECK(allInBox);
  CHECK(worstExcess <= tol);
}


}  // namespace

TEST_CASE_TEMPLATE("a box has volume 8abc and inertia m/3 (b²+c², a²+c², a²+b²)", S, float, double) {
  const S tol = pick<S>(1e-15, 1e-6);
  spook::ref_ptr<spook::BoxT<S>> box = new spook::BoxT<S>(spook::Vec3T<S>(S(0.5), S(1), S(1.5)));
  CHECK(std::abs(box->getVolume() - S(6)) <= tol * S(6));
  checkDiagonal<S>(box->calculateInertia(S(6)), 6.5, 5.0, 2.5, tol);
  CHECK(box->getBoundingBox().max == spook::Vec3T<S>(S(0.5), S(1), S(1.5)));
  CHECK(box->support(spook::Vec3T<S>(S(-1), S(0.2), S(-3))) == spook::Vec3T<S>(S(-0.5), S(1), S(-1.5)));
  checkSupportIsFarthest<S>(*box);
}

TEST_CASE_TEMPLATE("a sphere has volume 4/3 π r³ and inertia 2/5 m r²", S, float, double) {
  const S tol = pick<S>(1e-15, 1e-6);
  spook::ref_ptr<spook::SphereT<S>> sphere = new spook::SphereT<S>(S(0.5));
  CHECK(std::abs(sphere->getVolume() - S(std::numbers::pi / 6)) <= tol);
  checkDiagonal<S>(sphere->calculateInertia(S(2)), 0.2, 0.2, 0.2, tol);
  checkSupportIsFarthest<S>(*sphere);
}

TEST_CASE_TEMPLATE("a cylinder along y has I_yy = m r²/2 and I_xx = m (3r² + h²)/12", S, float, double) {
  const S tol = pick<S>(1e-15, 1e-6);
  spook::ref_ptr<spook::CylinderT<S>> cylinder = new spook::CylinderT<S>(S(0.5), S(2));
  CHECK(std::abs(cylinder->getVolume() - S(std::numbers::pi / 2)) <= tol);
  checkDiagonal<S>(cylinder->calculateInertia(S(3)), 1.1875, 0.375, 1.1875, tol);
  const spook::BoundingBoxT<S> box = cylinder->getBoundingBox();
  CHECK((box.max - spook::Vec3T<S>(S(0.5), S(1), S(0.5))).norm() <= tol);
  CHECK((box.min + spook::Vec3T<S>(S(0.5), S(1), S(0.5))).norm() <= tol);
  checkSupportIsFarthest<S>(*cylinder);
}

// r = 1, h = 2, density 1: m = 10π/3; worked by hand as a cylinder of mass 2π
// and two hemispheres of 2π/3 with centroids 3r/8 beyond the cylinder ends:
// I_yy = π + (2/5)(4π/3) = 23π/15, I_xx = 7π/6 + (4π/3)(2/5 + 1 + 3/4) = 121π/30.
TEST_CASE_TEMPLATE("a capsule's inertia is a cylinder's plus two offset hemispheres'", S, float, double) {
  const S tol = pick<S>(1e-15, 1e-6);
  const double pi = std::numbers::pi;
  spook::ref_ptr<spook::CapsuleT<S>> capsule = new spook::CapsuleT<S>(S(1), S(2));
  CHECK(std::abs(capsule->getVolume() - S(10 * pi / 3)) <= tol * S(10));
  checkDiagonal<S>(capsule->calculateInertia(S(10 * pi / 3)), 121 * pi / 30, 23 * pi / 15, 121 * pi / 30,
                   pick<S>(1e-14, 1e-6));
  const spook::BoundingBoxT<S> box = capsule->getBoundingBox();
  CHECK((box.max - spook::Vec3T<S>(S(1), S(2), S(1))).norm() <= tol * S(2));
  checkSupportIsFarthest<S>(*capsule);
}

TEST_CASE("a capsule shrinking to zero height tends to a sphere") {
  spook::CapsuleRef capsule = new spook::Capsule(0.3, 1e-9);
  spook::SphereRef sphere = new spook::Sphere(0.3);
  CHECK(capsule->getVolume() == doctest::Approx(sphere->getVolume()).epsilon(1e-8));
  CHECK((capsule->calculateInertia(2.0).matrix() - sphere->calculateInertia(2.0).matrix()).norm() < 1e-9);
}

TEST_CASE_TEMPLATE("shapes reject zero, negative and non-finite dimensions", S, float, double) {
  const S nan = std::numeric_limits<S>::quiet_NaN();
  checkRejects([] { spook::ref_ptr<spook::SphereT<S>> s = new spook::SphereT<S>(S(0)); }, "Sphere", "0");
  checkRejects([] { spook::ref_ptr<spook::SphereT<S>> s = new spook::SphereT<S>(S(-2)); }, "Sphere", "-2");
  checkRejects([&] { spook::ref_ptr<spook::CapsuleT<S>> s = new spook::CapsuleT<S>(S(1), nan); }, "Capsule", "nan");
  checkRejects([] { spook::ref_ptr<spook::CylinderT<S>> s = new spook::CylinderT<S>(S(-1), S(1)); }, "Cylinder", "-1");
  checkRejects([] { spook::ref_ptr<spook::BoxT<S>> s = new spook::BoxT<S>(spook::Vec3T<S>(S(1), S(0), S(1))); }, "Box",
               "(1, 0, 1)");
  spook::ref_ptr<spook::BoxT<S>> box = new spook::BoxT<S>(spook::Vec3T<S>::Ones());
  checkRejects([&] { box->setHalfExtents(spook::Vec3T<S>(S(1), S(1), S(-0.5))); }, "Box", "(1, 1, -0.5)");
  CHECK(box->getHalfExtents() == spook::Vec3T<S>::Ones());
  checkRejects([&] { (void)box->calculateInertia(S(0)); }, "Box", "0");
}

namespace {

template <class S>
spook::ref_ptr<spook::BoxT<S>> box(double x, double y, double z) {
  return new spook::BoxT<S>(spook::Vec3T<S>(S(x), S(y), S(z)));
}
template <class S>
S difference(const spook::SPDMat3T<S>& a, const spook::SPDMat3T<S>& b) {
  return (a.matrix() - b.matrix()).norm() / b.matrix().norm();
}

}  // namespace

// Two unit cubes side by side are one 2×1×1 box: an independent check of
// the parallel-axis theorem, I = Σ (Iᵢ + mᵢ(|pᵢ|² 1 − pᵢ pᵢᵀ)).
TEST_CASE_TEMPLATE("two cubes side by side have the volume and inertia of one long box", S, float, double) {
  const S tol = pick<S>(1e-12, 1e-6);
  spook::ref_ptr<spook::CompositeT<S>> pair = new spook::CompositeT<S>();
  auto cube = box<S>(0.5, 0.5, 0.5);
  pair->add(cube, at<S>(-0.5, 0, 0));
  pair->add(cube, at<S>(0.5, 0, 0));
  const auto whole = box<S>(1, 0.5, 0.5);
  CHECK(std::abs(pair->getVolume() - whole->getVolume()) <= tol);
  CHECK(difference<S>(pair->calculateInertia(S(3)), whole->calculateInertia(S(3))) <= tol);
  CHECK((pair->getBoundingBox().max - spook::Vec3T<S>(S(1), S(0.5), S(0.5))).norm() <= tol);
  CHECK(pair->getCenterOfVolume().norm() <= tol);
}

TEST_CASE_TEMPLATE("a child turned a quarter turn swaps its principal moments", S, float, double) {
  const S tol = pick<S>(1e-12, 1e-6);
  spook::ref_ptr<spook::CompositeT<S>> turned = new spook::CompositeT<S>();
  turned->add(box<S>(1, 0.5, 0.25), at<S>(0, 0, 0, spook::rotate<S>(spook::Vec3T<S>::UnitX(), spook::Vec3T<S>::UnitY())));
  CHECK(difference<S>(turned->calculateInertia(S(2)), box<S>(0.5, 1, 0.25)->calculateInertia(S(2))) <= tol);
  CHECK((turned->getBoundingBox().max - spook::Vec3T<S>(S(0.5), S(1), S(0.25))).norm() <= tol);
}

// Sphere of r = 0.5, m = 2 at (2, 0, 0): I = 2/5 m r² + m(|p|² 1 − p pᵀ)
// = diag(0.2, 8.2, 8.2) about the composite origin.
TEST_CASE_TEMPLATE("an offset child adds m d² about the composite origin", S, float, double) {
  const S tol = pick<S>(1e-12, 1e-6);
  spook::ref_ptr<spook::CompositeT<S>> arm = new spook::CompositeT<S>();
  arm->add(new spook::SphereT<S>(S(0.5)), at<S>(2, 0, 0));
  checkDiagonal<S>(arm->calculateInertia(S(2)), 0.2, 8.2, 8.2, tol);
  CHECK((arm->getCenterOfVolume() - spook::Vec3T<S>(S(2), S(0), S(0))).norm() <= tol);
}

// A composite whose own center is off its origin, nested in another: its
// tensor must be moved to its center before being moved again.
TEST_CASE_TEMPLATE("nested composites transfer inertia through each center of volume", S, float, double) {
  const S tol = pick<S>(1e-12, 1e-6);
  spook::ref_ptr<spook::CompositeT<S>> inner = new spook::CompositeT<S>();
  inner->add(box<S>(0.5, 0.5, 0.5), at<S>(1, 0, 0));
  spook::ref_ptr<spook::CompositeT<S>> outer = new spook::CompositeT<S>();
  outer->add(inner, at<S>(0, 3, 0));
  spook::ref_ptr<spook::CompositeT<S>> flat = new spook::CompositeT<S>();
  flat->add(box<S>(0.5, 0.5, 0.5), at<S>(1, 3, 0));
  CHECK(difference<S>(outer->calculateInertia(S(5)), flat->calculateInertia(S(5))) <= tol);
  CHECK((outer->getCenterOfVolume() - spook::Vec3T<S>(S(1), S(3), S(0))).norm() <= tol);
}

TEST_CASE_TEMPLATE("composites reject null and self-containing children and non-rigid placements", S, float, double) {
  spook::ref_ptr<spook::CompositeT<S>> a = new spook::CompositeT<S>(), b = new spook::CompositeT<S>();
  b->add(a);
  checkRejects([&] { a->add(b); }, "Composite", "a composite of its own chain");
  checkRejects([&] { a->add(a); }, "Composite", "a composite of its own chain");
  checkRejects([&] { a->add(nullptr); }, "Composite", "nullptr");
  spook::TransformT<S> scaled = spook::TransformT<S>::Identity();
  scaled.linear() *= S(2);
  checkRejects([&] { a->add(box<S>(1, 1, 1), scaled); }, "Composite", "(2, 0, 0");
  CHECK(a->getChildren().empty());
  checkRejects([&] { (void)a->calculateInertia(S(1)); }, "Composite", "0");
}

TEST_CASE_TEMPLATE("a composite with a plane child is unbounded, weighs only its solid children", S, float, double) {
  spook::ref_ptr<spook::CompositeT<S>> floorAndBox = new spook::CompositeT<S>();
  floorAndBox->add(new spook::PlaneT<S>(spook::Vec3T<S>::UnitZ()));
  floorAndBox->add(box<S>(0.5, 0.5, 0.5), at<S>(0, 0, 2));
  const spook::BoundingBoxT<S> bounds = floorAndBox->getBoundingBox();
  CHECK((bounds.min.array() == -std::numeric_limits<S>::infinity()).all());
  CHECK((bounds.max.array() == std::numeric_limits<S>::infinity()).all());
  CHECK(floorAndBox->getVolume() == S(1));
  CHECK((floorAndBox->getCenterOfVolume() - spook::Vec3T<S>(S(0), S(0), S(2))).norm() <= pick<S>(1e-12, 1e-6));
  CHECK(floorAndBox->calculateInertia(S(6)).matrix().allFinite());
}
