#pragma once

namespace spook::detail {

/// The one place that reads and writes the private "which simulation am I
/// in" fields of bodies, listeners and collections.
struct SimulationMembership {
  template <class T>
  static auto& simulationOf(T& object) {
    return object.simulation_;
  }
  template <class T>
  static auto simulationOf(const T& object) {
    return object.simulation_;
  }
  template <class T>
  static auto& indexOf(T& object) {
    return object.simulationIndex_;
  }
};

}  // namespace spook::detail
