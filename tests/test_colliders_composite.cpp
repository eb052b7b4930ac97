// Composites in the collider matrix (ColliderMatrixT<S, AllShapes>), float
// and double: a composite of a box and a sphere, offset and turned, against a
// plane and against a sphere gives exactly the union of its children's
// contacts, each child collided on its own at the composite's pose times its
// transform (same points, normals and depths to 1e-12 m; the same arithmetic
// makes them equal to the bit), through the type-erased entry and the typed
// one; the reversed pair (other shape first) gives the same contacts with
// the normals negated. The same against a HeightField, whose children's
// contacts come from the mesh colliders. 1,000 random poses each, fixed
// seeds.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include <spook/collide/all_shapes.hpp>
#include <spook/collide/collider_matrix.hpp>
#include "compiled_collide.hpp"

using spook::BoxT;
using spook::CompositeT;
using spook::ContactPointT;
using spook::ContactSinkT;
using spook::PlaneT;
using spook::ref_ptr;
using spook::SphereT;

namespace {

constexpr int kPoses = 1000;
constexpr double kSame = 1e-12;  // m, and for unit normals

using Vec3d = spook::Vec3;
using Transformd = spook::Transform;

Transformd randomPose(std::mt19937_64& rng, double spread) {
  std::normal_distribution<double> g(0.0, 1.0);
  std::uniform_real_distribution<double> u(-spread, spread);
  Transformd X = Transformd::Identity();
  X.linear() = Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
  X.translation() = Vec3d(u(rng), u(rng), u(rng));
  return X;
}

template <class S>
const char* scalarName() {
  return std::is_same_v<S, float> ? "float" : "double";
}

/// Largest difference between two contact lists, point by point in order
/// (normals of `b` times `normalSign`); infinity when the counts differ.
template <class S>
double difference(const std::vector<ContactPointT<S>>& a, const std::vector<ContactPointT<S>>& b, S normalSign) {
  if (a.size() != b.size()) return std::numeric_limits<double>::infinity();
  double worst = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    worst = std::max(worst, double((a[i].point - b[i].point).norm()));
    worst = std::max(worst, double((a[i].normal - normalSign * b[i].normal).norm()));
    worst = std::max(worst, double(std::abs(a[i].depth - b[i].depth)));
  }
  return worst;
}

/// The composite against `other` (at random poses near it) through the
/// matrix, both orders, both entries, against the union of the children.
template <class S, class Other>
void checkComposite(const std::string& name, std::uint64_t seed, const ref_ptr<Other>& other) {
  using Matrix = spook::ColliderMatrixT<S, spook::AllShapes>;
  using Shape = spook::ShapeT<S>;
  using V = spook::Vec3T<S>;
  ref_ptr<CompositeT<S>> composite = new CompositeT<S>();
  composite->add(new BoxT<S>(V(S(0.3), S(0.2), S(0.15))),
                 spook::makeTransform<S>(V(S(0.4), S(0.1), S(-0.1)),
                                         spook::QuatT<S>(Eigen::AngleAxis<S>(S(0.7), V(1, 2, 3).normalized()))));
  composite->add(new SphereT<S>(S(0.25)),
                 spook::makeTransform<S>(V(S(-0.45), S(0.05), S(0.2)), spook::QuatT<S>::Identity()));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> offset(-0.9, 0.9);
  int cases = 0, withContacts = 0, contacts = 0;
  double worstUnion = 0, worstTyped = 0, worstReversed = 0;
  std::vector<ContactPointT<S>> expected, erased, typed, reversed;
  for (int k = 0; k < kPoses; ++k) {
    const Transformd X_WC = randomPose(rng, 1.0);
    Transformd X_WO = randomPose(rng, 0.0);
    X_WO.translation() = X_WC.translation() + Vec3d(offset(rng), offset(rng), offset(rng));
    const spook::TransformT<S> XC = X_WC.cast<S>(), XO = X_WO.cast<S>();
    expected.clear(), erased.clear(), typed.clear(), reversed.clear();
    ContactSinkT<S> expectedSink(expected), erasedSink(erased), typedSink(typed), reversedSink(reversed);
    for (const auto& child : composite->getChildren()) {
      const spook::TransformT<S> X_WChild = XC * child.transform;
      if (child.shape->getType() == spook::ShapeType::BOX)
        spook::test::collideCompiled(static_cast<const BoxT<S>&>(*child.shape), X_WChild, *other, XO, expectedSink);
      else
        spook::test::collideCompiled(static_cast<const SphereT<S>&>(*child.shape), X_WChild, *other, XO, expectedSink);
    }
    CHECK(
        Matrix::collide(static_cast<const Shape&>(*composite), XC, static_cast<const Shape&>(*other), XO, erasedSink));
    Matrix::collide(*composite, XC, *other, XO, typedSink);
    CHECK(Matrix::collide(static_cast<const Shape&>(*other), XO, static_cast<const Shape&>(*composite), XC,
                          reversedSink));
    ++cases;
    withContacts += expected.empty() ? 0 : 1;
    contacts += int(expected.size());
    worstUnion = std::max(worstUnion, difference(expected, erased, S(1)));
    worstTyped = std::max(worstTyped, difference(expected, typed, S(1)));
    worstReversed = std::max(worstReversed, difference(expected, reversed, S(-1)));
  }
  char text[320];
  std::snprintf(text, sizeof text,
                "%s <%s>: %d cases, %d with contacts, %d contacts; worst difference from the children's union %.3g "
                "(typed entry %.3g), reversed with negated normals %.3g",
                name.c_str(), scalarName<S>(), cases, withContacts, contacts, worstUnion, worstTyped, worstReversed);
  MESSAGE(text);
  CHECK(worstUnion <= kSame);
  CHECK(worstTyped <= kSame);
  CHECK(worstReversed <= kSame);
  CHECK(withContacts * 5 >= cases);
}

}  // namespace

TEST_CASE_TEMPLATE("composite: box and sphere children against a plane give the union of the children's contacts", S,
                   float, double) {
  const ref_ptr<PlaneT<S>> plane = new PlaneT<S>(spook::Vec3T<S>(S(0.2), S(-0.3), S(1)), spook::Vec3T<S>::Zero());
  checkComposite<S>("composite-plane", 601, plane);
}

TEST_CASE_TEMPLATE("composite: box and sphere children against a sphere give the union of the children's contacts", S,
                   float, double) {
  const ref_ptr<SphereT<S>> sphere = new SphereT<S>(S(0.4));
  checkComposite<S>("composite-sphere", 602, sphere);
}

TEST_CASE_TEMPLATE("composite: box and sphere children against a HeightField give the union of the children's contacts",
                   S, float, double) {
  std::vector<S> heights;
  for (int i = 0; i < 20; ++i) heights.push_back(S(0.1) * S(std::sin(1.7 * i)));
  const ref_ptr<spook::HeightFieldT<S>> field = new spook::HeightFieldT<S>(5, 4, S(2.4), S(1.8), heights);
  checkComposite<S>("composite-heightfield", 603, field);
}
