// A wire's high resolution range (agxWire's HighResolutionRange): a stretch
// of the wire, measured from one of its ends, kept at a finer resolution,
// which stays at a winch there as the wire pays out; bad input.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <spook/spook.hpp>

#include "error_message.hpp"

using namespace spook;

namespace {

/// A light limp line (radius 5 mm, 1000 kg/m³, 1 node per meter) hanging
/// 10 m from a winch on the world, a free end below, stepped at 500 Hz so
/// that its tension (under 10 N) lets nodes 10 cm apart resolve.
template <Scalar S>
struct HangingLine {
  using Vec3 = Vec3T<S>;
  ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
  ref_ptr<WireWinchControllerT<S>> winch =
      new WireWinchControllerT<S>(nullptr, Vec3(S(0), S(0), S(10)), Vec3(S(0), S(0), S(-1)));
  ref_ptr<WireT<S>> line = new WireT<S>(S(0.005), S(1));

  HangingLine() {
    sim->setTimeStep(S(1.0 / 500.0));
    line->getMaterial()->getBulkMaterial()->setDensity(S(1000));
    line->getMaterial()->getWireMaterial()->setYoungsModulusBend(S(0));
    line->add(winch, S(10));
    line->add(new FreeNodeT<S>(Vec3(S(0), S(0), S(0))));
    sim->add(line);
  }
  void run(double seconds) {
    const int steps = int(std::lround(seconds / double(sim->getTimeStep())));
    for (int s = 0; s < steps; ++s) sim->stepForward();
  }
  /// Segment lengths (m) as (distance from the winch of the segment's
  /// middle, length), along the line from its begin.
  [[nodiscard]] std::vector<std::pair<double, double>> segments() const {
    const std::vector<Vec3> points = line->getPoints();
    std::vector<std::pair<double, double>> result;
    double along = 0.0;
    for (std::size_t k = 0; k + 1 < points.size(); ++k) {
      const double length = double((points[k + 1] - points[k]).norm());
      result.emplace_back(along + length / 2.0, length);
      along += length;
    }
    return result;
  }
  /// The longest and shortest segment whose middle lies within [from, to] m.
  [[nodiscard]] std::pair<double, double> extremes(double from, double to) const {
    double longest = 0.0, shortest = 1e9;
    for (const auto& [middle, length] : segments())
      if (middle >= from && middle <= to) {
        longest = std::max(longest, length);
        shortest = std::min(shortest, length);
      }
    return {longest, shortest};
  }
};

}  // namespace

TEST_CASE_TEMPLATE("a high resolution range keeps its stretch fine and stays at the winch as the wire pays out", S,
                   double, float) {
  HangingLine<S> rig;
  rig.run(0.2);
  const auto coarse = rig.extremes(0.0, 10.0);
  MESSAGE("without a range: segments " << coarse.second << " to " << coarse.first << " m, "
                                        << rig.line->getNumMassNodes() << " nodes");
  CHECK(coarse.second > 0.5);
  // 10 nodes per meter over the first 3 m from the winch: segments split
  // until they are shorter than twice its spacing (0.2 m); beyond, the
  // wire's 1 m.
  rig.line->setHighResolutionRange(true, S(0), S(3), S(10));
  rig.run(0.5);
  const auto inside = rig.extremes(0.0, 2.9), outside = rig.extremes(3.6, 10.0);
  MESSAGE("range 0-3 m at 10/m: " << inside.second << " to " << inside.first << " m within it, " << outside.second
                                  << " to " << outside.first << " m beyond, " << rig.line->getNumMassNodes()
                                  << " nodes");
  CHECK(inside.first < 0.2);
  CHECK(outside.second > 0.5);
  // Paying out 2 m at 1 m/s: the range stays at the winch, the wire it
  // left behind merges up to a quarter of the wire's spacing.
  rig.winch->setSpeed(S(1));
  rig.winch->setForceRange(S(-1e3), S(1e3));
  rig.run(2.0);
  rig.winch->setSpeed(S(0));
  rig.run(0.2);
  const double length = double(rig.line->getRestLength());
  const auto atWinch = rig.extremes(0.0, 2.9), below = rig.extremes(3.6, length);
  MESSAGE("after paying out to " << length << " m: " << atWinch.second << " to " << atWinch.first
                                 << " m within 3 m of the winch, " << below.second << " to " << below.first
                                 << " m beyond, " << rig.line->getNumMassNodes() << " nodes");
  CHECK(length == doctest::Approx(12.0).epsilon(0.01));
  CHECK(atWinch.first < 0.2);
  CHECK(below.second > 0.24);
  // Cleared, the wire's own resolution: no segment under a quarter of its spacing.
  rig.line->clearHighResolutionRange(true);
  rig.run(0.2);
  const auto cleared = rig.extremes(0.0, length);
  MESSAGE("cleared: segments " << cleared.second << " to " << cleared.first << " m, "
                               << rig.line->getNumMassNodes() << " nodes");
  CHECK(cleared.second > 0.24);
}

TEST_CASE("a high resolution range from the end follows reverse, cut and merge with its end") {
  HangingLine<double> rig;
  rig.line->setHighResolutionRange(false, 1.0, 2.0, 8.0);
  rig.line->reverse();
  CHECK(rig.line->getHighResolutionRange(true).resolution == 8.0);
  CHECK(rig.line->getHighResolutionRange(false).resolution == 0.0);
  rig.line->reverse();
  rig.run(0.1);
  ref_ptr<Wire> tail = rig.line->cut(5.0);
  CHECK(tail->getHighResolutionRange(false).start == 1.0);
  CHECK(tail->getHighResolutionRange(false).end == 2.0);
  CHECK(rig.line->getHighResolutionRange(false).resolution == 0.0);
  rig.sim->add(tail);
  rig.line->merge(tail.get());
  rig.sim->remove(tail.get());
  CHECK(rig.line->getHighResolutionRange(false).resolution == 8.0);
  rig.run(0.3);
  // The last 1-2 m of the 10 m line (from the winch: 8-9 m) are fine.
  const auto fine = rig.extremes(8.1, 8.9);
  MESSAGE("range 1-2 m from the end: segments " << fine.second << " to " << fine.first << " m there");
  CHECK(fine.first < 0.25);
}

TEST_CASE("a high resolution range refuses bad input by name and keeps the one it had") {
  const auto message = [](auto&& make) { return spook::test::errorMessage(make); };
  ref_ptr<Wire> wire = new Wire(0.01, 2.0);
  wire->setName("line");
  wire->setHighResolutionRange(true, 0.0, 5.0, 6.0);
  CHECK(message([&] { wire->setHighResolutionRange(true, -1.0, 5.0, 6.0); }).find("'line'") != std::string::npos);
  CHECK(message([&] { wire->setHighResolutionRange(true, 5.0, 5.0, 6.0); }).find("start < end") != std::string::npos);
  CHECK(message([&] { wire->setHighResolutionRange(true, 0.0, std::nan(""), 6.0); }).find("line") !=
        std::string::npos);
  CHECK(message([&] { wire->setHighResolutionRange(true, 0.0, 5.0, 0.0); }).find("resolution must be finite and > 0") !=
        std::string::npos);
  CHECK(message([&] { wire->setHighResolutionRange(false, 0.0, 1e9, 1e3); }).find("1e6") != std::string::npos);
  CHECK(wire->getHighResolutionRange(true).end == 5.0);
  CHECK(wire->getHighResolutionRange(true).resolution == 6.0);
  CHECK(wire->getHighResolutionRange(false).resolution == 0.0);
}
