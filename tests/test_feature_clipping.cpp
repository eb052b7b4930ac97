// FeatureClipping: the manifold of two supporting features, against
// overlaps worked out by hand. n = z; the top feature's points are highest
// along n (the shape behind the normal), the bottom one's lowest.

#include <doctest/doctest.h>

#include <algorithm>
#include <vector>

#include <spook/collide/detail/feature_clipping.hpp>

namespace {

using spook::detail::FeatureClipping;
using Point = spook::Vec3;

std::vector<Point> square(double x0, double y0, double x1, double y1, double z) {
  return {Point(x0, y0, z), Point(x1, y0, z), Point(x1, y1, z), Point(x0, y1, z)};
}

bool has(const std::vector<FeatureClipping::Contact>& contacts, const Point& p, double tolerance = 1e-12) {
  return std::any_of(contacts.begin(), contacts.end(),
                     [&](const FeatureClipping::Contact& c) { return (c.point - p).norm() <= tolerance; });
}

}  // namespace

TEST_CASE("two overlapping faces give the corners of their overlap, halfway between them") {
  const FeatureClipping clipping(Point::UnitZ());
  // Top face at z = 0.01 over [0, 1]², bottom face at z = 0 over [0.5, 2]²:
  // the overlap [0.5, 1]², 1 cm deep.
  const auto contacts = clipping.contacts({square(0, 0, 1, 1, 0.01), 1e-6}, {square(0.5, 0.5, 2, 2, 0), 1e-6}, 0.01);
  REQUIRE(contacts.size() == 4);
  for (const Point& corner : square(0.5, 0.5, 1, 1, 0.005)) CHECK(has(contacts, corner));
  for (const auto& c : contacts) CHECK(c.depth == doctest::Approx(0.01).epsilon(1e-12));
}

TEST_CASE("a face tilted across the other gives depths that follow the tilt, the part above it none") {
  const FeatureClipping clipping(Point::UnitZ());
  // Top face from z = 0.01 at x = 0 down to z = -0.01 at x = 1 (it leaves
  // the bottom face at x = 0.5); bottom face z = 0 over [−1, 2] × [0, 1].
  const std::vector<Point> top = {Point(0, 0, 0.01), Point(1, 0, -0.01), Point(1, 1, -0.01), Point(0, 1, 0.01)};
  const auto contacts = clipping.contacts({top, 1e-6}, {square(-1, 0, 2, 1, 0), 1e-6}, 0.01);
  REQUIRE(contacts.size() == 2);
  CHECK(has(contacts, Point(0, 0, 0.005)));
  CHECK(has(contacts, Point(0, 1, 0.005)));
}

TEST_CASE("a segment on a face gives its two ends where they lie over the face, clipped at its edges") {
  const FeatureClipping clipping(Point::UnitZ());
  // A cylinder's line of contact from x = −0.5 to 0.5 at y = 0.2, 2 mm deep,
  // over a face that ends at x = 0.3.
  const std::vector<Point> line = {Point(-0.5, 0.2, 0.002), Point(0.5, 0.2, 0.002)};
  const auto contacts = clipping.contacts({line, 1e-6}, {square(-1, -1, 0.3, 1, 0), 1e-6}, 0.002);
  REQUIRE(contacts.size() == 2);
  CHECK(has(contacts, Point(-0.5, 0.2, 0.001)));
  CHECK(has(contacts, Point(0.3, 0.2, 0.001)));
}

TEST_CASE("a point over a face is the one contact; samples within the merge size are one point") {
  const FeatureClipping clipping(Point::UnitZ());
  const std::vector<Point> cap = {Point(0.1, 0.1, 0.001), Point(0.1 + 2e-5, 0.1, 0.001), Point(0.1, 0.1 - 2e-5, 0.001)};
  const auto contacts = clipping.contacts({cap, 1e-4}, {square(-5, -5, 5, 5, 0), 1e-6}, 0.001);
  REQUIRE(contacts.size() == 1);
  CHECK((contacts[0].point - Point(0.1, 0.1, 0.0005)).norm() < 3e-5);
  CHECK(contacts[0].depth == doctest::Approx(0.001));
}

TEST_CASE("two crossing segments meet at one point; parallel ones along their common range") {
  const FeatureClipping clipping(Point::UnitZ());
  const std::vector<Point> alongX = {Point(-1, 0, 0.01), Point(1, 0, 0.01)};
  const std::vector<Point> alongY = {Point(0.25, -1, 0), Point(0.25, 1, 0)};
  const auto crossing = clipping.contacts({alongX, 1e-6}, {alongY, 1e-6}, 0.01);
  REQUIRE(crossing.size() == 1);
  CHECK(has(crossing, Point(0.25, 0, 0.005)));
  const std::vector<Point> parallel = {Point(0.5, 0, 0), Point(3, 0, 0)};
  const auto along = clipping.contacts({alongX, 1e-6}, {parallel, 1e-6}, 0.01);
  REQUIRE(along.size() == 2);
  CHECK(has(along, Point(0.5, 0, 0.005)));
  CHECK(has(along, Point(1, 0, 0.005)));
}

TEST_CASE("features whose projections do not overlap give no contact") {
  const FeatureClipping clipping(Point::UnitZ());
  CHECK(clipping.contacts({square(0, 0, 1, 1, 0.01), 1e-6}, {square(2, 2, 3, 3, 0), 1e-6}, 0.01).empty());
}
