// The default narrow phase (every shape type) asks the higher-ranked shape
// of a pair for its contacts (ShapeT::collideWithLowerRank, dispatchRank),
// so that a program compiles the colliders of the shape types it
// constructs only. It must mean the same collider as the collider matrix
// for every ordered pair: the same contacts to the bit (points, normals,
// depths, triangle indices), the same pairs without a collider, the
// composite's children included. 6 random poses per ordered pair of the
// ten shape types, float and double, fixed seeds.

#include <doctest/doctest.h>

#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include <spook/collide/all_shapes.hpp>
#include <spook/collide/collider_matrix.hpp>
#include <spook/collide/space.hpp>

namespace {

constexpr int kPosesPerPair = 6;

template <class S>
std::vector<spook::ref_ptr<spook::ShapeT<S>>> oneShapeOfEachType() {
  using V = spook::Vec3T<S>;
  std::vector<spook::ref_ptr<spook::ShapeT<S>>> shapes;
  shapes.push_back(new spook::BoxT<S>(V(S(0.4), S(0.3), S(0.2))));
  shapes.push_back(new spook::CapsuleT<S>(S(0.2), S(0.6)));
  shapes.push_back(new spook::ConvexT<S>(std::vector<V>{V(S(-0.4), S(-0.3), S(-0.2)), V(S(0.4), S(-0.3), S(-0.2)),
                                                        V(S(0), S(0.4), S(-0.2)), V(S(0.1), S(0), S(0.4))}));
  shapes.push_back(new spook::CylinderT<S>(S(0.3), S(0.5)));
  shapes.push_back(new spook::LineT<S>(V(S(-0.5), S(0), S(0)), V(S(0.5), S(0.1), S(0))));
  shapes.push_back(new spook::PlaneT<S>(V(S(0.1), S(-0.2), S(1)), V::Zero()));
  shapes.push_back(new spook::SphereT<S>(S(0.35)));
  using Triangle = typename spook::TrimeshT<S>::Triangle;
  shapes.push_back(new spook::TrimeshT<S>(
      std::vector<V>{V(S(-0.5), S(-0.5), S(0)), V(S(0.5), S(-0.5), S(0)), V(S(0.5), S(0.5), S(0.1)),
                     V(S(-0.5), S(0.5), S(-0.1)), V(S(0), S(0), S(0.3))},
      std::vector<Triangle>{{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}, {0, 2, 1}, {0, 3, 2}}));
  spook::ref_ptr<spook::CompositeT<S>> composite = new spook::CompositeT<S>();
  composite->add(new spook::BoxT<S>(V(S(0.2), S(0.15), S(0.1))),
                 spook::makeTransform<S>(V(S(0.25), S(0), S(0)),
                                         spook::QuatT<S>(Eigen::AngleAxis<S>(S(0.6), V(1, 2, 3).normalized()))));
  composite->add(new spook::SphereT<S>(S(0.2)),
                 spook::makeTransform<S>(V(S(-0.25), S(0.05), S(0.1)), spook::QuatT<S>::Identity()));
  shapes.push_back(composite);
  shapes.push_back(new spook::HeightFieldT<S>(
      3, 3, S(1.2), S(1.2), std::vector<S>{S(0), S(0.05), S(0.1), S(0.1), S(0.2), S(0.05), S(0), S(0.15), S(0.1)}));
  return shapes;
}

template <class S>
bool same(const std::vector<spook::ContactPointT<S>>& a, const std::vector<spook::ContactPointT<S>>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i].point != b[i].point || a[i].normal != b[i].normal || a[i].depth != b[i].depth ||
        a[i].faceIndex1 != b[i].faceIndex1 || a[i].faceIndex2 != b[i].faceIndex2)
      return false;
  return true;
}

}  // namespace

TEST_CASE_TEMPLATE("shape dispatch: every ordered pair gives the collider matrix's contacts to the bit", S, float,
                   double) {
  using Matrix = spook::ColliderMatrixT<S, spook::AllShapes>;
  using Transform = spook::TransformT<S>;
  const auto shapes = oneShapeOfEachType<S>();
  REQUIRE(shapes.size() == spook::kNumShapeTypes);
  std::mt19937_64 rng(std::is_same_v<S, float> ? 91 : 92);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::uniform_real_distribution<double> offset(-0.15, 0.15);
  // Both shapes within 0.15 m of the origin along each axis: most poses overlap.
  const auto randomPose = [&] {
    Transform X = Transform::Identity();
    X.linear() = Eigen::Quaternion<double>(gauss(rng), gauss(rng), gauss(rng), gauss(rng))
                     .normalized()
                     .toRotationMatrix()
                     .template cast<S>();
    X.translation() = Eigen::Vector3d(offset(rng), offset(rng), offset(rng)).template cast<S>();
    return X;
  };
  int pairs = 0, mismatched = 0, unsupportedMismatch = 0, silent = 0;
  std::string report;
  std::vector<spook::ContactPointT<S>> byShapes, byMatrix;
  for (const auto& a : shapes)
    for (const auto& b : shapes) {
      const bool supported = Matrix::supports(a->getType(), b->getType());
      int withContacts = 0, differing = 0;
      for (int k = 0; k < kPosesPerPair; ++k) {
        const Transform X_WA = randomPose();
        const Transform X_WB = randomPose();
        byShapes.clear(), byMatrix.clear();
        spook::ContactSinkT<S> shapesSink(byShapes), matrixSink(byMatrix);
        const bool dispatched = spook::detail::collideThrough<S, spook::AllShapes>(*a, X_WA, *b, X_WB, shapesSink);
        const bool tabled = Matrix::collide(*a, X_WA, *b, X_WB, matrixSink);
        if (dispatched != tabled || dispatched != supported) ++unsupportedMismatch;
        if (!same(byShapes, byMatrix)) ++differing;
        withContacts += byShapes.empty() ? 0 : 1;
      }
      ++pairs;
      const std::string name =
          std::string(spook::shapeTypeName(a->getType())) + "-" + std::string(spook::shapeTypeName(b->getType()));
      if (differing) {
        ++mismatched;
        report += name + ": " + std::to_string(differing) + " poses differ; ";
      }
      // Two segments (lines) touch on a set of poses of measure zero.
      const bool lines = a->getType() == spook::ShapeType::LINE && b->getType() == spook::ShapeType::LINE;
      if (supported && !lines && withContacts == 0) {
        ++silent;
        report += name + ": no contacts in " + std::to_string(kPosesPerPair) + " poses; ";
      }
    }
  MESSAGE(pairs << " ordered pairs: " << (report.empty() ? std::string("all alike") : report));
  CHECK(pairs == int(spook::kNumShapeTypes * spook::kNumShapeTypes));
  CHECK(mismatched == 0);
  CHECK(unsupportedMismatch == 0);
  CHECK(silent == 0);
}

TEST_CASE("shape dispatch: the ranks order every shape type, the composite last") {
  int seen = 0;
  for (std::size_t t = 0; t < spook::kNumShapeTypes; ++t) {
    const int rank = spook::dispatchRank(static_cast<spook::ShapeType>(t));
    CHECK(rank >= 0);
    CHECK(rank < int(spook::kNumShapeTypes));
    seen |= 1 << rank;
  }
  CHECK(seen == (1 << spook::kNumShapeTypes) - 1);
  CHECK(spook::dispatchRank(spook::ShapeType::COMPOSITE) == int(spook::kNumShapeTypes) - 1);
}
