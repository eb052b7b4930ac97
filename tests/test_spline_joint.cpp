#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include <spook/constraints/joints/spline_joint.hpp>
#include <spook/core/cubic_spline.hpp>

#include "joint_scenes.hpp"
#include "tolerance.hpp"

using namespace spook;
using spook::test::frameAt;
using spook::test::kG;
using spook::test::makeBody;
using spook::test::pick;

namespace {

constexpr double kSplinePi = std::numbers::pi;

// Points of a circle of radius `radius` about (0, 0, radius) in the xz plane,
// at angles φ from the bottom (x = R sin φ, z = R − R cos φ), from `from` to
// `to` (rad) in `count` points: a bowl when the angles straddle 0.
template <class S>
ref_ptr<CubicSplineT<S>> splineBowl(double radius, double from, double to, int count) {
  ref_ptr<CubicSplineT<S>> spline = new CubicSplineT<S>();
  for (int i = 0; i < count; ++i) {
    const double phi = from + (to - from) * i / (count - 1);
    spline->add(Vec3T<S>(S(radius * std::sin(phi)), S(0), S(radius - radius * std::cos(phi))));
  }
  return spline;
}

// A bead: a body of mass 1 kg centered on the spline at parameter t, its
// attachment frame at the center with z along the tangent, joined to the
// world by a SplineJoint, in a simulation with the direct solver.
template <class S>
struct SplineBead {
  ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
  ref_ptr<CubicSplineT<S>> spline;
  ref_ptr<RigidBodyT<S>> body;
  ref_ptr<SplineJointT<S>> joint;
  ref_ptr<DirectSolver> solver = new DirectSolver();

  SplineBead(ref_ptr<CubicSplineT<S>> curve, S t, bool postStabilization = false, S inertia = S(0.004))
      : spline(std::move(curve)) {
    solver->setEnablePostStabilization(postStabilization);
    sim->setSolver(solver);
    body = makeBody<S>(*sim, "bead", S(1), spline->getPosition(t), inertia);
    joint = new SplineJointT<S>(body.get(), frameAt<S>(Vec3T<S>::Zero(), spline->getUnitTangent(t)).get(), spline.get());
    sim->add(joint);
  }
  /// Distance of the bead's center from the curve (m), by a search over the whole curve.
  [[nodiscard]] double offCurve() const {
    const Vec3T<S> p = body->getPosition();
    return double((spline->getPosition(spline->findNearestParameter(p)) - p).norm());
  }
  /// Arc length of the point of the curve nearest the bead (m).
  [[nodiscard]] double arcLength() const {
    return double(spline->getLength(spline->findNearestParameter(body->getPosition(), joint->getParameter())));
  }
  /// Kinetic plus potential energy (J), gravity along −z.
  [[nodiscard]] double energy() const {
    return double(body->getKineticEnergy()) + kG * double(body->getPosition().z());
  }
};

}  // namespace

// ---------------------------------------------------------------------------
// The curve.

TEST_CASE_TEMPLATE("a cubic spline passes through its control points with continuous tangents", S, float, double) {
  ref_ptr<CubicSplineT<S>> spline = new CubicSplineT<S>();
  const std::vector<Vec3T<S>> points{Vec3T<S>(0, 0, 0), Vec3T<S>(0, 2, 1), Vec3T<S>(0, 4, 5), Vec3T<S>(1, 5, 6),
                                    Vec3T<S>(3, 5, 6)};
  for (const auto& p : points) spline->add(p);
  spline->updateTangents();
  REQUIRE(spline->getNumPoints() == points.size());
  CHECK(spline->getMaxParameter() == S(points.size() - 1));
  const S tol = pick<S>(1e-12, 1e-5);
  for (std::size_t i = 0; i < points.size(); ++i) CHECK((spline->getPosition(S(i)) - points[i]).norm() <= tol * S(10));
  // Catmull–Rom: the tangent at an inner point is half the chord of its neighbours.
  CHECK((spline->getPointTangent(2) - S(0.5) * (points[3] - points[1])).norm() <= tol * S(10));
  // The derivative is continuous across a knot and matches finite differences.
  const S e = pick<S>(1e-6, 1e-2);
  for (S t : {S(0.3), S(1.5), S(2.9)}) {
    const Vec3T<S> fd = (spline->getPosition(t + e) - spline->getPosition(t - e)) / (S(2) * e);
    CHECK((fd - spline->getFirstDerivative(t)).norm() <= pick<S>(1e-8, 1e-2) * spline->getFirstDerivative(t).norm());
    const Vec3T<S> fd2 = (spline->getFirstDerivative(t + e) - spline->getFirstDerivative(t - e)) / (S(2) * e);
    CHECK((fd2 - spline->getSecondDerivative(t)).norm() <= pick<S>(1e-7, 2e-2) * (S(1) + spline->getSecondDerivative(t).norm()));
  }
  CHECK((spline->getFirstDerivative(S(2) - S(1e-4)) - spline->getFirstDerivative(S(2) + S(1e-4))).norm() <= S(1e-2));
}

TEST_CASE_TEMPLATE("the arc length of a straight spline is exact and inverts to the parameter", S, float, double) {
  ref_ptr<CubicSplineT<S>> segment = new CubicSplineT<S>();
  segment->add(Vec3T<S>(1, 1, 1));
  segment->add(Vec3T<S>(4, 5, 1));
  const S tol = pick<S>(1e-14, 1e-6);
  CHECK(std::abs(segment->getLength() - S(5)) <= S(5) * tol);
  CHECK(std::abs(segment->getLength(S(0.3)) - S(1.5)) <= S(5) * tol);
  CHECK(std::abs(segment->getParameterAtLength(S(4)) - S(0.8)) <= S(10) * tol);
  // Three equally spaced collinear points: the same line, 2 m per segment.
  ref_ptr<CubicSplineT<S>> line = new CubicSplineT<S>();
  for (int i = 0; i < 3; ++i) line->add(Vec3T<S>(S(2 * i), 0, 0));
  CHECK(std::abs(line->getLength() - S(4)) <= S(4) * tol);
  CHECK(std::abs(line->getLength(S(1.5)) - S(3)) <= S(4) * tol);
  CHECK(std::abs(line->getParameterAtLength(S(1)) - S(0.5)) <= S(10) * tol);
}

TEST_CASE("the quadrature of a curved spline agrees with a fine polygon and approximates the circle") {
  // 49 points on 240° of a unit circle: Catmull–Rom with 5° chords.
  auto spline = splineBowl<double>(1.0, -2.0 * kSplinePi / 3.0, 2.0 * kSplinePi / 3.0, 49);
  const double tMax = spline->getMaxParameter();
  double polygon = 0.0;
  const int n = 200000;
  for (int k = 0; k < n; ++k)
    polygon += (spline->getPosition(tMax * (k + 1) / n) - spline->getPosition(tMax * k / n)).norm();
  // The polygon underestimates by about L h²κ²/24 with h = L/n: 1e-11 here.
  CHECK(std::abs(spline->getLength() - polygon) <= 1e-9);
  MESSAGE("240° bowl spline length " << spline->getLength() << " m, circle arc " << 4.0 * kSplinePi / 3.0 << " m");
  CHECK(std::abs(spline->getLength() - 4.0 * kSplinePi / 3.0) <= 1e-4);
  for (double s : {0.1, 1.7, 4.0}) CHECK(std::abs(spline->getLength(spline->getParameterAtLength(s)) - s) <= 1e-12);
}

TEST_CASE_TEMPLATE("the nearest parameter is the foot of the perpendicular and stays on its branch", S, float, double) {
  auto spline = splineBowl<S>(1.0, -2.0 * kSplinePi / 3.0, 2.0 * kSplinePi / 3.0, 49);
  for (S t0 : {S(3.3), S(24), S(40.7)}) {
    const Vec3T<S> p = spline->getPosition(t0);
    const Vec3T<S> away = spline->getUnitTangent(t0).cross(Vec3T<S>::UnitY());  // across the curve, in its plane
    for (S offset : {S(-0.2), S(0.05), S(0.3)}) {
      const Vec3T<S> x = p + offset * away;
      CHECK(std::abs(spline->findNearestParameter(x, t0 + S(0.4)) - t0) <= pick<S>(1e-9, 2e-4));
      CHECK(std::abs(spline->findNearestParameter(x) - t0) <= pick<S>(1e-9, 2e-4));
    }
  }
  // A hairpin: two parallel branches 0.2 m apart. A point 0.12 m from the
  // lower branch is nearer the upper one, yet the search from the lower
  // branch keeps the lower branch's local minimum.
  ref_ptr<CubicSplineT<S>> hairpin = new CubicSplineT<S>();
  for (int i = 0; i <= 10; ++i) hairpin->add(Vec3T<S>(S(0.2 * i), 0, 0));
  for (int i = 10; i >= 0; --i) hairpin->add(Vec3T<S>(S(0.2 * i - 0.0001), 0, S(0.2)));
  const Vec3T<S> x(S(0.9), 0, S(0.12));
  const S lower = hairpin->findNearestParameter(x, S(4));
  CHECK(std::abs(lower - S(4.5)) <= pick<S>(1e-6, 1e-3));
  CHECK(std::abs(hairpin->getPosition(lower).z()) <= pick<S>(1e-9, 1e-5));
  CHECK(hairpin->getPosition(hairpin->findNearestParameter(x)).z() > S(0.19));
}

TEST_CASE("bad spline input throws spook::Error naming the value") {
  CubicSplineRef spline = new CubicSpline();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH_AS(spline->add(Vec3T<double>(0, nan, 0)), doctest::Contains("CubicSpline"), spook::Error);
  CHECK_THROWS_WITH_AS(static_cast<void>(spline->getPosition(0.0)), doctest::Contains("at least two points"), spook::Error);
  spline->add(Vec3T<double>(0, 0, 0));
  CHECK_THROWS_WITH_AS(spline->add(Vec3T<double>(0, 0, 0)), doctest::Contains("differ"), spook::Error);
  CHECK_THROWS_WITH_AS(spline->add(Vec3T<double>(1, 0, 0), Vec3T<double>::Zero()), doctest::Contains("tangent"),
                       spook::Error);
  CHECK_THROWS_WITH_AS(spline->setTension(1.0), doctest::Contains("1"), spook::Error);
  CHECK(spline->getNumPoints() == 1);
  spline->add(Vec3T<double>(1, 0, 0));
  CHECK_THROWS_AS((void)spline->findNearestParameter(Vec3T<double>(nan, 0, 0), 0.0), spook::Error);
  CHECK_THROWS_AS((void)spline->getPoint(2), spook::Error);
}

// ---------------------------------------------------------------------------
// The joint's rows are the derivatives of its violations.

// The bead on a three-dimensional spline fixed in a second, moving body:
// central differences of each row's violation, and of the arc length and
// the angle about the tangent, along the bodies' velocities must match J·v.
TEST_CASE("the spline joint's rows and coordinates have the Jacobians of their rates") {
  SimulationRef sim = new Simulation();
  CubicSplineRef spline = new CubicSpline();
  for (int i = 0; i < 12; ++i) spline->add(Vec3T<double>(std::cos(0.6 * i), std::sin(0.6 * i), 0.15 * i + 0.02 * i * i));
  RigidBodyRef carrier = makeBody<double>(*sim, "carrier", 3.0, Vec3T<double>(0.2, -0.1, 0.3), 0.3);
  carrier->setRotation(QuatT<double>(Eigen::AngleAxisd(0.4, Vec3T<double>(1, 1, 0).normalized())));
  const double t0 = 4.3;
  const Vec3T<double> p0 = carrier->getTransform() * spline->getPosition(t0);
  const Vec3T<double> tangent = carrier->getRotation() * spline->getUnitTangent(t0);
  RigidBodyRef bead = makeBody<double>(*sim, "bead", 1.0, p0 + Vec3T<double>(0.1, 0.05, -0.2), 0.01);
  bead->setRotation(QuatT<double>(Eigen::AngleAxisd(-0.7, Vec3T<double>(0.3, 1, 0.2).normalized())));
  const Vec3T<double> frameOrigin = bead->getFrame()->transformPointToLocal(p0);
  const Vec3T<double> frameAxis = bead->getRotation().conjugate() * tangent;
  SplineJointRef joint = new SplineJoint(bead.get(), frameAt<double>(frameOrigin, frameAxis).get(), spline.get(), carrier.get());
  const Vec3T<double> v1(0.3, -0.2, 0.5), w1(0.4, 0.9, -0.3), v2(-0.1, 0.2, 0.1), w2(0.2, -0.5, 0.6);
  bead->setVelocity(v1);
  bead->setAngularVelocity(w1);
  carrier->setVelocity(v2);
  carrier->setAngularVelocity(w2);
  const auto pose1 = bead->getTransform();
  const auto pose2 = carrier->getTransform();
  auto moveBy = [&](double e) {
    TransformT<double> X1 = pose1, X2 = pose2;
    X1.translation() += e * v1;
    X1.linear() = Eigen::AngleAxisd(e * w1.norm(), w1.normalized()) * pose1.linear();
    X2.translation() += e * v2;
    X2.linear() = Eigen::AngleAxisd(e * w2.norm(), w2.normalized()) * pose2.linear();
    bead->setTransform(X1);
    carrier->setTransform(X2);
  };
  auto rowsAt = [&](double e) {
    moveBy(e);
    std::vector<detail::Row> rows;
    detail::RowSink sink{&rows, 0, 1, SolveType::DIRECT, false};
    // A tiny step: the rows' centripetal term (∝ h) drops out of the violation.
    detail::ConstraintAccess::addRows(static_cast<Constraint&>(*joint), sink, 1e-9);
    return rows;
  };
  const std::vector<detail::Row> rows = rowsAt(0.0);
  REQUIRE(rows.size() == 4);
  const detail::Vec6d V1 = detail::linearAngular(v1, w1), V2 = detail::linearAngular(v2, w2);
  const double e = 1e-6;
  const std::vector<detail::Row> plus = rowsAt(e), minus = rowsAt(-e);
  for (std::size_t k = 0; k < 4; ++k) {
    const double fd = (plus[k].violation - minus[k].violation) / (2 * e);
    const double Jv = rows[k].J1.dot(V1) + rows[k].J2.dot(V2);
    CAPTURE(k);
    CHECK(fd == doctest::Approx(Jv).epsilon(1e-6).scale(1.0));
  }
  moveBy(0.0);
  for (int index : {SplineJoint::FIRST, SplineJoint::SECOND}) {
    moveBy(e);
    const double up = joint->getAngle(index);
    moveBy(-e);
    const double down = joint->getAngle(index);
    moveBy(0.0);
    CAPTURE(index);
    // The angle's reference normal is carried by minimal rotations between
    // samples an eighth of a segment apart: its twist rate is second order.
    CHECK((up - down) / (2 * e) == doctest::Approx(joint->getCurrentSpeed(index)).epsilon(1e-4).scale(1.0));
  }
}

// ---------------------------------------------------------------------------
// Physics.

TEST_CASE_TEMPLATE("a bead on a straight spline down a 30 degree incline slides at g sin 30", S, float, double) {
  const double angle = kSplinePi / 6.0;
  ref_ptr<CubicSplineT<S>> spline = new CubicSplineT<S>();
  spline->add(Vec3T<S>(0, 0, 0));
  spline->add(Vec3T<S>(S(20 * std::cos(angle)), 0, S(-20 * std::sin(angle))));
  SplineBead<S> scene(spline, S(0));
  for (int i = 0; i < 60; ++i) scene.sim->stepForward();
  const double expected = kG * std::sin(angle) * 1.0;  // m/s after 1 s
  const double speed = double(scene.joint->getCurrentSpeed(SplineJointT<S>::FIRST));
  const double along = double(scene.body->getVelocity().dot(spline->getUnitTangent(S(0))));
  MESSAGE("speed along the incline after 1 s: " << speed << " m/s (g sin 30° t = " << expected << ")");
  CHECK(std::abs(speed - expected) <= 0.005 * expected);
  CHECK(std::abs(along - expected) <= 0.005 * expected);
  CHECK((scene.body->getVelocity().template cast<double>() - along * spline->getUnitTangent(S(0)).template cast<double>()).norm() <=
        pick<S>(1e-6, 1e-3));
  CHECK(scene.offCurve() <= pick<S>(1e-6, 1e-4));
}

// A bead in a circular bowl of radius 1 m released at rest level with the
// bowl's center (φ = 90°) swings for 10 s at 60 Hz under gravity.
TEST_CASE_TEMPLATE("a bead in a curved spline bowl stays on the curve and keeps its energy", S, float, double) {
  const double from = -2.0 * kSplinePi / 3.0, to = 2.0 * kSplinePi / 3.0;
  for (bool post : {false, true}) {
    auto spline = splineBowl<S>(1.0, from, to, 49);
    const S start = S((kSplinePi / 2.0 - from) / (to - from) * 48.0);
    SplineBead<S> scene(spline, start, post);
    const double e0 = scene.energy();
    double worstOff = 0.0, worstEnergy = 0.0, lowest = 1.0;
    for (int i = 0; i < 600; ++i) {
      scene.sim->stepForward();
      worstOff = std::max(worstOff, scene.offCurve());
      worstEnergy = std::max(worstEnergy, std::abs(scene.energy() - e0));
      lowest = std::min(lowest, double(scene.body->getPosition().z()));
    }
    const double drop = kG * 1.0;  // m g R, J
    const double finalEnergy = std::abs(scene.energy() - e0);
    const std::string mode = post ? "with" : "without";
    MESSAGE(mode << " post-stabilization: largest distance from the curve " << worstOff << " m, largest energy error "
                 << worstEnergy / drop << " of m g R, after 10 s " << finalEnergy / drop);
    CHECK(lowest <= pick<S>(1e-3, 1e-2));  // it swung through the bottom
    // Without the rows' centripetal term the bead would ride (1 + 4τ/h)/4 ·
    // ½h²v²/R = 6 mm outside the curve at the bottom (4.4 m/s).
    CHECK(worstOff <= (post ? 1e-6 : 1.5e-3));  // measured 3.6e-7 and 8.0e-4, float and double
    // SPOOK's symplectic step: the energy error oscillates with the swing
    // (hω = 0.05) by a few percent (measured 3.1 % without, 2.7 % with
    // post-stabilization; 0.6 % and 1.9 % after 10 s).
    CHECK(worstEnergy <= 0.04 * drop);
    CHECK(finalEnergy <= 0.025 * drop);
  }
}

// The catalogue's check (test_joint_catalogue.cpp) for the spline joint: a
// perturbed bead, 10 s at 60 Hz, direct solver with post-stabilization,
// default compliance: the frame origin stays on the curve and its z axis
// along the tangent within 1e-6 from 1 s on (after SPOOK's transient).
TEST_CASE_TEMPLATE("a perturbed bead stays within 1e-6 of the curve and its tangent when post-stabilized", S, float,
                   double) {
  const double from = -2.0 * kSplinePi / 3.0, to = 2.0 * kSplinePi / 3.0;
  SplineBead<S> scene(splineBowl<S>(1.0, from, to, 49), S((kSplinePi / 3.0 - from) / (to - from) * 48.0), true);
  scene.body->setVelocity(S(0.2), S(-0.3), S(0.1));
  scene.body->setAngularVelocity(S(0.3), S(0.2), S(-0.4));
  // Measured on a double copy of the curve: float's nearest-point search
  // alone would misplace the tangent by ~1e-6.
  const auto curve = splineBowl<double>(1.0, from, to, 49);
  double worstOff = 0.0, worstTilt = 0.0;
  for (int i = 0; i < 600; ++i) {
    scene.sim->stepForward();
    if (i < 60) continue;
    const TransformT<S> X = scene.joint->getAttachmentFrame(0)->getMatrix();
    const Vec3T<double> p = X.translation().template cast<double>(), z = X.linear().col(2).template cast<double>();
    const double t = curve->findNearestParameter(p);
    worstOff = std::max(worstOff, (curve->getPosition(t) - p).norm());
    worstTilt = std::max(worstTilt, z.cross(curve->getUnitTangent(t)).norm());
  }
  MESSAGE("perturbed bead: worst distance from the curve " << worstOff << " m, tilt off the tangent " << worstTilt);
  CHECK(worstOff < 1e-6);
  // Float: the joint's curve parameter t ≈ 32 is quantized to 3.8e-6 (arc
  // 3.3e-7 m), and its tangent is evaluated from it in float: measured
  // 1.6e-6 rad (double 3.4e-10).
  CHECK(worstTilt < pick<S>(1e-6, 5e-6));
}

TEST_CASE_TEMPLATE("a motor on the spline's translation drives the bead at its speed along the arc", S, float, double) {
  // A horizontal quarter circle of radius 2 m; gravity loads the rows across the curve.
  ref_ptr<CubicSplineT<S>> spline = new CubicSplineT<S>();
  for (int i = 0; i <= 20; ++i) {
    const double phi = 0.5 * kSplinePi * i / 20.0;
    spline->add(Vec3T<S>(S(2 * std::cos(phi)), S(2 * std::sin(phi)), S(0)));
  }
  SplineBead<S> scene(spline, S(1));
  Motor1DT<S>* motor = scene.joint->getMotor1D(SplineJointT<S>::FIRST);
  motor->setEnable(true);
  motor->setSpeed(S(0.5));
  for (int i = 0; i < 30; ++i) scene.sim->stepForward();
  const double s0 = scene.arcLength();
  for (int i = 0; i < 120; ++i) scene.sim->stepForward();
  const double rate = (scene.arcLength() - s0) / 2.0;
  MESSAGE("arc-length rate under a 0.5 m/s motor: " << rate << " m/s");
  CHECK(rate == doctest::Approx(0.5).epsilon(pick<S>(1e-3, 2e-3)));
  CHECK(double(scene.joint->getCurrentSpeed(SplineJointT<S>::FIRST)) == doctest::Approx(0.5).epsilon(pick<S>(1e-3, 2e-3)));
  CHECK(double(scene.joint->getAngle(SplineJointT<S>::FIRST)) == doctest::Approx(scene.arcLength()).epsilon(1e-3));
  CHECK(scene.offCurve() <= pick<S>(1e-4, 1e-3));
}

TEST_CASE_TEMPLATE("a range on the spline's translation stops the bead at the arc-length limit", S, float, double) {
  const double from = -2.0 * kSplinePi / 3.0, to = 2.0 * kSplinePi / 3.0;
  auto spline = splineBowl<S>(1.0, from, to, 49);
  const S start = S((kSplinePi / 2.0 - from) / (to - from) * 48.0);
  const S stop = S((kSplinePi / 4.0 - from) / (to - from) * 48.0);  // φ = 45°, on the way down
  SplineBead<S> scene(spline, start);
  const S limit = spline->getLength(stop);
  Range1DT<S>* range = scene.joint->getRange1D(SplineJointT<S>::FIRST);
  range->setEnable(true);
  range->setRange(limit, S(100));
  double lowest = 1e9;
  for (int i = 0; i < 180; ++i) {
    scene.sim->stepForward();
    lowest = std::min(lowest, scene.arcLength());
  }
  MESSAGE("range limit " << limit << " m, lowest arc length " << lowest << " m, at rest at " << scene.arcLength() << " m");
  CHECK(scene.arcLength() == doctest::Approx(double(limit)).epsilon(pick<S>(1e-4, 1e-3)));
  CHECK(lowest >= double(limit) - 0.02);
  CHECK(std::abs(double(scene.joint->getCurrentSpeed(SplineJointT<S>::FIRST))) <= pick<S>(1e-3, 1e-2));
}

TEST_CASE_TEMPLATE("rotation about the spline's tangent is free and can be locked", S, float, double) {
  ref_ptr<CubicSplineT<S>> spline = new CubicSplineT<S>();
  spline->add(Vec3T<S>(-5, 0, 0));
  spline->add(Vec3T<S>(0, 0, S(0.5)));
  spline->add(Vec3T<S>(5, 0, 0));
  const S spin = S(3);  // rad/s about the tangent
  {
    SplineBead<S> scene(spline, S(0.5), false, S(0.1));
    scene.body->setAngularVelocity(spin * spline->getUnitTangent(S(0.5)));
    for (int i = 0; i < 60; ++i) scene.sim->stepForward();
    const S about = scene.body->getAngularVelocity().dot(spline->getUnitTangent(scene.joint->getParameter()));
    MESSAGE("spin about the tangent after 1 s on a curved spline: " << about << " rad/s; angle "
                                                                    << scene.joint->getAngle(SplineJointT<S>::SECOND));
    CHECK(double(about) == doctest::Approx(3.0).epsilon(pick<S>(1e-3, 2e-3)));
    CHECK(double(scene.joint->getAngle(SplineJointT<S>::SECOND)) == doctest::Approx(3.0).epsilon(0.01));
  }
  {
    SplineBead<S> scene(spline, S(0.5), false, S(0.1));
    scene.body->setAngularVelocity(spin * spline->getUnitTangent(S(0.5)));
    scene.joint->getLock1D(SplineJointT<S>::SECOND)->setEnable(true);
    for (int i = 0; i < 60; ++i) scene.sim->stepForward();
    const S about = scene.body->getAngularVelocity().dot(spline->getUnitTangent(scene.joint->getParameter()));
    MESSAGE("locked: spin " << about << " rad/s, angle " << scene.joint->getAngle(SplineJointT<S>::SECOND) << " rad");
    CHECK(std::abs(double(about)) <= 1e-3);
    CHECK(std::abs(double(scene.joint->getAngle(SplineJointT<S>::SECOND))) <= 1e-3);
  }
}

TEST_CASE("bad spline joint input throws spook::Error naming the joint and the value") {
  SimulationRef sim = new Simulation();
  RigidBodyRef body = makeBody<double>(*sim, "bead", 1.0, Vec3T<double>(0, 0, 0));
  CubicSplineRef spline = new CubicSpline();
  spline->add(Vec3T<double>(0, 0, 0));
  FrameRef frame = frameAt<double>(Vec3T<double>::Zero(), Vec3T<double>::UnitX());
  CHECK_THROWS_WITH_AS(SplineJointRef(new SplineJoint(body.get(), frame.get(), nullptr)),
                       doctest::Contains("SplineJoint"), spook::Error);
  CHECK_THROWS_WITH_AS(SplineJointRef(new SplineJoint(body.get(), frame.get(), spline.get())),
                       doctest::Contains("at least two points, got 1"), spook::Error);
  spline->add(Vec3T<double>(1, 0, 0));
  FrameRef backwards = frameAt<double>(Vec3T<double>::Zero(), -Vec3T<double>::UnitX());
  CHECK_THROWS_WITH_AS(SplineJointRef(new SplineJoint(body.get(), backwards.get(), spline.get())),
                       doctest::Contains("got -1"), spook::Error);
  CHECK_THROWS_WITH_AS(SplineJointRef(new SplineJoint(nullptr, frame.get(), spline.get())),
                       doctest::Contains("first body"), spook::Error);
  // The failed constructions left the frames unattached.
  CHECK(frame->getParent() == nullptr);
  CHECK(backwards->getParent() == nullptr);
  SplineJointRef joint = new SplineJoint(body.get(), frame.get(), spline.get());
  CHECK_THROWS_WITH_AS((void)joint->getMotor1D(2), doctest::Contains("FIRST (0) or SECOND (1)"), spook::Error);
  sim->add(joint);
  sim->stepForward();
  CHECK(joint->getAngle(SplineJoint::FIRST) == doctest::Approx(0.0).scale(1.0));
}
