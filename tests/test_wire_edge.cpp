// Wires routed over the edges of boxes, convexes, trimeshes and height
// fields (ContactNode on their geometries, wire/edge_wrap.hpp): the wire
// turns at each edge as through an eye that slides along the edge to where
// the wire's path is shortest, and holds a load against a counterweight
// within the capstan ratio e^{μ Σθ} of the angles it turns by, slipping
// beyond.

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <spook/spook.hpp>

using namespace spook;

namespace {

constexpr double kEdgeGravity = 9.80665;  // m/s², the simulation's default

/// The shapes a wire runs over by their edges. Each has two straight top
/// edges along y at x = ±0.5 (shape frame), from y = −0.5 to 0.5, the left
/// one at z = 0.5 and the right one at rightTop(), and its sides fall away
/// below them.
enum class Ridge { BOX, CONVEX, TRIMESH, HEIGHT_FIELD };
constexpr Ridge kRidges[] = {Ridge::BOX, Ridge::CONVEX, Ridge::TRIMESH, Ridge::HEIGHT_FIELD};

double rightTop(Ridge ridge) { return ridge == Ridge::CONVEX || ridge == Ridge::HEIGHT_FIELD ? 0.3 : 0.5; }

std::string nameOf(Ridge ridge) {
  switch (ridge) {
    case Ridge::BOX:
      return "box";
    case Ridge::CONVEX:
      return "convex";
    case Ridge::TRIMESH:
      return "trimesh";
    case Ridge::HEIGHT_FIELD:
      return "height field";
  }
  return "?";
}

/// A 1 m cube (box, or trimesh of its 12 triangles); a convex prism whose
/// top slopes from z = 0.5 on the left to 0.3 on the right and whose
/// cross-section narrows from 1 m at the top to 0.6 m at the bottom; a
/// height field of 3 × 3 samples over 1 m × 1 m sloping as the convex's top
/// (its rim edges are the ridges, each in two cells' edges of 0.5 m).
template <Scalar S>
ShapeT<S>* makeRidge(Ridge ridge) {
  using Vec3 = Vec3T<S>;
  const S h = S(0.5);
  switch (ridge) {
    case Ridge::BOX:
      return new BoxT<S>(Vec3(h, h, h));
    case Ridge::CONVEX:
      return new ConvexT<S>({Vec3(-h, -h, h), Vec3(h, -h, S(0.3)), Vec3(-h, h, h), Vec3(h, h, S(0.3)),
                             Vec3(S(-0.3), -h, -h), Vec3(S(0.3), -h, -h), Vec3(S(-0.3), h, -h), Vec3(S(0.3), h, -h)});
    case Ridge::TRIMESH: {
      std::vector<Vec3> corners;
      for (int k = 0; k < 8; ++k) corners.emplace_back(k & 1 ? h : -h, k & 2 ? h : -h, k & 4 ? h : -h);
      // Counter-clockwise seen from outside.
      return new TrimeshT<S>(corners, {{0, 2, 1},
                                       {1, 2, 3},
                                       {4, 5, 6},
                                       {5, 7, 6},
                                       {0, 1, 4},
                                       {1, 5, 4},
                                       {2, 6, 3},
                                       {3, 6, 7},
                                       {0, 4, 2},
                                       {2, 4, 6},
                                       {1, 3, 5},
                                       {3, 7, 5}});
    }
    case Ridge::HEIGHT_FIELD:
      return new HeightFieldT<S>(3, 3, S(1), S(1), {h, S(0.4), S(0.3), h, S(0.4), S(0.3), h, S(0.4), S(0.3)});
  }
  return nullptr;
}

/// A light limp wire (radius 5 mm, 100 kg/m³, 5 nodes/m unless stated) from a first load
/// 1 cm left of a static ridge shape (makeRidge), up over its two top edges
/// along y and down to a second load 1 cm right of it, both 3 m below its
/// top; the edge nodes are routed `along` the edges (y), the loads at y = 0.
template <Scalar S>
struct OverEdges {
  using Vec3 = Vec3T<S>;
  ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
  ref_ptr<RigidBodyT<S>> first = new RigidBodyT<S>(), second = new RigidBodyT<S>();
  ref_ptr<GeometryT<S>> cube;
  ref_ptr<ContactNodeT<S>> left, right;
  ref_ptr<WireT<S>> wire;

  OverEdges(double firstMass, double secondMass, double mu, double along = 0.0, Ridge ridge = Ridge::BOX,
            double resolution = 5.0)
      : cube(new GeometryT<S>(makeRidge<S>(ridge))),
        left(new ContactNodeT<S>(cube.get(), Vec3(S(-0.5), S(along), S(0.5)))),
        right(new ContactNodeT<S>(cube.get(), Vec3(S(0.5), S(along), S(rightTop(ridge))))),
        wire(new WireT<S>(S(0.005), S(resolution))) {
    sim->add(cube);
    first->getMassProperties()->setMass(S(firstMass));
    first->setPosition(S(-0.51), S(0), S(-2.5));
    second->getMassProperties()->setMass(S(secondMass));
    second->setPosition(S(0.51), S(0), S(-2.5));
    sim->add(first);
    sim->add(second);
    wire->getMaterial()->getBulkMaterial()->setDensity(S(100));
    wire->getMaterial()->getWireMaterial()->setYoungsModulusBend(S(0));
    left->setFrictionCoefficient(S(mu));
    right->setFrictionCoefficient(S(mu));
    wire->add(new BodyFixedNodeT<S>(first.get(), Vec3::Zero()));
    wire->add(left);
    wire->add(right);
    wire->add(new BodyFixedNodeT<S>(second.get(), Vec3::Zero()));
  }
};

}  // namespace

TEST_CASE_TEMPLATE(
    "a wire over two edges of a box, a convex, a trimesh or a height field holds within e^(mu theta) "
    "and slips beyond",
    S, double, float) {
  // The loads swing in under the edges: the wire turns by a quarter turn at
  // each (more by the sag of the wire between them, 0.06% here).
  const double mu = 0.25, light = 10.0, theta = std::numbers::pi;
  const double ratio = std::exp(mu * theta);
  for (const Ridge ridge : kRidges)
    for (const double share : {0.98, 1.02}) {
      CAPTURE(nameOf(ridge));
      CAPTURE(share);
      const double heavy = share * ratio * light;
      OverEdges<S> rig(light, heavy, mu, 0.0, ridge);
      rig.sim->add(rig.wire);
      for (int s = 0; s < 60; ++s) rig.sim->stepForward();
      const double wrapped = double(rig.left->getWrapAngle() + rig.right->getWrapAngle());
      const double drop = -2.5 - double(rig.second->getPosition().z()), speed = -double(rig.second->getVelocity().z());
      const double length = double(rig.wire->getRestLength());
      const double low = double(rig.wire->getTension(S(0.1))), high = double(rig.wire->getTension(S(length - 0.1)));
      const auto points = rig.wire->getPoints();
      double farthest = 0.0;  // from the plane y = 0, where the path over the edges is shortest
      for (const auto& p : points) farthest = std::max(farthest, std::abs(double(p.y())));
      MESSAGE(nameOf(ridge) << ", load " << share << " e^(mu theta) x the light one: drop " << drop << " m in 1 s at "
                            << speed << " m/s, tensions " << high << " N and " << low << " N (ratio " << high / low
                            << " against " << ratio << "), wrap " << wrapped << " rad against " << theta
                            << ", points within " << farthest << " m of y = 0");
      CHECK(wrapped == doctest::Approx(theta).epsilon(2e-3));
      CHECK(farthest < 1e-3);
      if (share < 1.0) {
        CHECK(std::abs(drop) < 5e-3);
        CHECK(std::abs(speed) < 1e-3);
        CHECK(high == doctest::Approx(heavy * kEdgeGravity).epsilon(0.01));
        CHECK(low == doctest::Approx(light * kEdgeGravity).epsilon(0.01));
      } else {
        CHECK(drop > 0.01);
        CHECK(speed > 0.05);
        CHECK(high / low == doctest::Approx(std::exp(mu * wrapped)).epsilon(0.01));
      }
    }
}

TEST_CASE_TEMPLATE("a frictionless edge is an Atwood machine's pulley, the wire sliding along it", S, double, float) {
  // 20 kg against 5 kg over the two frictionless edges: a = (m₁ − m₂) g/(m₁ + m₂).
  // Routed 0.4 m along the edges from the loads' plane, the wire slides
  // back along them towards the shortest path over them.
  for (const Ridge ridge : kRidges)
    for (const double along : {0.0, 0.4}) {
      CAPTURE(nameOf(ridge));
      CAPTURE(along);
      OverEdges<S> rig(5.0, 20.0, 0.0, along, ridge);
      rig.sim->add(rig.wire);
      const int steps = 30;
      for (int s = 0; s < steps; ++s) rig.sim->stepForward();
      const double t = steps * double(rig.sim->getTimeStep());
      const double expected = (20.0 - 5.0) * kEdgeGravity / 25.0 * t;
      const double speed = -double(rig.second->getVelocity().z());
      // Where the wire crosses the edges now (y: along them).
      double across = 0.0;
      int crossings = 0;
      for (const auto& p : rig.wire->getPoints())
        if (std::abs(std::abs(double(p.x())) - 0.5) < 1e-6 &&
            std::abs(double(p.z()) - (p.x() < 0 ? 0.5 : rightTop(ridge))) < 1e-6) {
          across = std::max(across, std::abs(double(p.y())));
          ++crossings;
        }
      MESSAGE(nameOf(ridge) << ", routed " << along << " m along: after " << t << " s the heavy load falls at " << speed
                            << " m/s against " << expected << "; the wire crosses the edges within " << across
                            << " m of the loads' plane");
      CHECK(speed == doctest::Approx(expected).epsilon(0.01));
      CHECK(crossings == 2);  // one point on each edge: the check below measures them
      // Built 0.3 m along (the shortest path from the loads to the routed points), it slid back.
      CHECK(across < 0.1);
    }
}

TEST_CASE_TEMPLATE("a load pulled up to the edge stops there, held by the wire", S, double, float) {
  // The frictionless Atwood machine run on: the light load rises 3 m, reaches
  // the edge after about 1 s at 6 m/s (5 kg against 20) or 7.6 m/s (1 kg
  // against 100) and stops there, the heavy one hanging still. On the way its
  // speed is the Atwood machine's, a t (the wire's 0.2% of the mass
  // neglected; from 0.1 s on, when the nodes the tension cannot resolve have
  // left, taking their momentum): nothing is lost where the wire runs over
  // the edges (a node on the wire between them that passed the lower edge
  // threw the loads back and blew the wire up). A wire cannot push, so the
  // load passes the edge by up to one step's travel v h before the wire
  // pulls it back. The heavy load's jolt as the light one stops (1:100:
  // tension peaks near 20 kN) leaves the wire slack, where it gains nodes
  // between the edges that the next jolt's tension cannot resolve: they
  // leave (kept beside the edges, they were flung off the box and the wire
  // blew up). Also with nodes between the edges (20 per meter).
  const double rise = 3.0;  // from z = -2.5 to the edge
  for (const auto& loads : {std::pair(5.0, 20.0), std::pair(1.0, 100.0)})
    for (const Ridge ridge : kRidges)
      for (const double resolution : {5.0, 20.0}) {
        const double light = loads.first, heavy = loads.second;
        CAPTURE(nameOf(ridge));
        CAPTURE(resolution);
        CAPTURE(heavy / light);
        const double a = (heavy - light) * kEdgeGravity / (heavy + light), arrival = std::sqrt(2.0 * a * rise);
        OverEdges<S> rig(light, heavy, 0.0, 0.0, ridge, resolution);
        rig.sim->add(rig.wire);
        const double h = double(rig.sim->getTimeStep());
        double highest = -1e9, worstSpeed = 0.0;  // relative error of the speed on the way up
        for (int s = 1; s <= 180; ++s) {
          rig.sim->stepForward();
          highest = std::max(highest, double(rig.first->getPosition().z()));
          const double v = double(rig.first->getVelocity().z());
          if (s >= 6 && highest < 0.4) worstSpeed = std::max(worstSpeed, std::abs(v / (a * s * h) - 1.0));
        }
        const double top = double(rig.first->getPosition().z()), speed = double(rig.second->getVelocity().norm());
        const double tension = double(rig.wire->getTension(rig.wire->getRestLength() - S(0.1)));
        MESSAGE(light << " kg against " << heavy << " over a " << nameOf(ridge) << ", " << resolution
                      << " nodes/m: on the way up the light load's speed within " << worstSpeed
                      << " of the Atwood machine's; after 3 s it is at z = " << top << " (highest " << highest
                      << ", the edge at 0.5, a step's travel at arrival " << arrival * h << "), the heavy one moves at "
                      << speed << " m/s, its wire pulls " << tension << " N (its weight " << heavy * kEdgeGravity
                      << ")");
        REQUIRE(std::isfinite(top));
        CHECK(worstSpeed < 0.01);
        CHECK(highest < 0.5 + arrival * h);
        CHECK(std::abs(top - 0.5) < 0.01);
        CHECK(speed < 0.05);
        CHECK(tension == doctest::Approx(heavy * kEdgeGravity).epsilon(0.02));
      }
}
