#pragma once

namespace spook::detail {

/// The simulation's settings of the contact rows (sim/contact_rows.hpp).
struct ContactSettings {
  /// Approach speed (m/s) above which restitution acts; slower contacts rest.
  double restitutionThreshold = 0.2;
  /// Cap on the speed (m/s) at which the stabilization of the normal rows
  /// pushes overlapping shapes apart.
  double maxDepenetrationSpeed = 1.0;
  /// A point of this step continues a point of the last step (same geometry
  /// pair) when they lie within this distance (m) in the first geometry's
  /// frame: its rows start from that point's force.
  double persistenceDistance = 0.01;
  /// Contacts found ahead of the step (SpaceT::update's reach): points
  /// apart by a gap the shapes may close within the step become rows that
  /// let them close it and no more.
  bool speculative = true;
};

}  // namespace spook::detail
