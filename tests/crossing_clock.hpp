#pragma once

#include <numbers>

namespace spook::test {

/// Period-mean angular frequency (rad/s) of the zero crossings of q(t),
/// each crossing placed by linear interpolation between samples.
struct CrossingClock {
  double lastValue = 0.0, lastTime = 0.0, firstCrossing = -1.0, lastCrossing = -1.0;
  int crossings = 0, samples = 0;
  void add(double t, double q) {
    if (samples++ > 0 && (q > 0.0) != (lastValue > 0.0)) {
      const double at = lastTime + (t - lastTime) * lastValue / (lastValue - q);
      if (firstCrossing < 0.0) firstCrossing = at;
      lastCrossing = at;
      ++crossings;
    }
    lastValue = q;
    lastTime = t;
  }
  [[nodiscard]] double omega() const {
    return crossings < 3 ? 0.0 : std::numbers::pi * (crossings - 1) / (lastCrossing - firstCrossing);
  }
};

}  // namespace spook::test
