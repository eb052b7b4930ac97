#pragma once

#include <array>
#include <cstddef>

#include <spook/core/math.hpp>

namespace spook {

/// The part of a convex shape that is extreme along a direction, as contact
/// manifolds need it (the reference and incident faces of Box2D's and
/// Jolt's manifolds): a face (its corners, counter-clockwise or not), an
/// edge (its two ends) or one point, in the shape's frame (m). A face or an
/// edge is supporting when it is within the angle kSupportingFeatureSin of
/// perpendicular to the direction; the colliders clip the two features and
/// keep only the points that penetrate, so a feature tilted within that
/// angle yields the contacts of its low side alone.
template <Scalar S>
struct SupportingFeatureT {
  static constexpr std::size_t kCapacity = 16;
  std::array<Vec3T<S>, kCapacity> points;
  std::size_t count = 0;
  /// A round face (a cylinder's cap) has radius > 0: the disc about
  /// `center` with unit normal `axis`, whose rim the points sample.
  S radius = S(0);
  Vec3T<S> center = Vec3T<S>::Zero();
  Vec3T<S> axis = Vec3T<S>::UnitZ();

  void add(const Vec3T<S>& p) {
    if (count < kCapacity) points[count++] = p;
  }
};

/// Sine of the angle (~3°) within which a face or an edge counts as
/// supporting: wide enough for a resting body rocking under its contacts'
/// compliance, narrow enough that two crossing edges stay edges.
inline constexpr double kSupportingFeatureSin = 0.05;
/// Its cosine, sqrt(1 − 0.05²).
inline constexpr double kSupportingFeatureCos = 0.99874921777190895;

/// A flush face axis (two faces lying against each other within round-off)
/// marks a seam beside the least axis only when it runs across that axis,
/// at more than ~45° to it: |cos| below this. Its near twin on the other
/// shape (a face turned by round-off) is no seam.
inline constexpr double kFlushAcrossCos = 0.7;

/// Corners of a cylinder's or a cone's cap a cap feature has (a regular
/// polygon inscribed in the rim).
inline constexpr int kCapCorners = 8;

}  // namespace spook
