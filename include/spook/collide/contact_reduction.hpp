#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include <spook/collide/contact_point.hpp>
#include <spook/core/error.hpp>

namespace spook {

/// How contact points are reduced (AGX's ContactMaterial modes).
enum class ContactReductionMode {
  REDUCE_NONE,      ///< keep every point
  REDUCE_GEOMETRY,  ///< reduce per geometry pair (default)
  REDUCE_ALL        ///< reduce per body pair, over all their geometry pairs
};

namespace detail {

/// Disables redundant contact points. Each point is binned in the six
/// dimensional space of the unit wrench it can carry, [n, n × r/|r|max]
/// with r its arm from the points' centroid (the binning of the AGX manual,
/// ch. 13), each coordinate cut into `resolution` bins over [−1, 1]; in each
/// bin the point farthest from the centroid survives (so the survivors span
/// the largest area, as the seeds put it), ties going to the deeper one.
/// Where a gap point (negative depth) meets a deeper point in its bin by
/// more than 1e-3 of the patch's radius, the deeper one survives: the
/// smallest gap is the one the body reaches first (a curved hull over a
/// fine mesh has gap points on many triangles, the farthest of them the
/// highest; kept, a 40-point ellipsoid fell 47-133 mm into the mesh at
/// h = 0.1 s). The deepest point survives too where it is deeper than every
/// survivor by more than that: the farthest of a tilted or curved shape's
/// points (gap points of a hull nearing the ground) may be its highest, and
/// without the lowest one it falls past the ground for a step.
/// Resolution 2 keeps at most one point per quadrant of a flat contact
/// patch, 3 keeps more. Disabled points stay in the list. A point whose
/// position, normal or depth is not finite is disabled and left out of the
/// binning (the Space's sinks never let one through); the others are scaled
/// by a power of two first, so that points near the largest finite
/// coordinate cannot overflow the centroid or the arms.
template <Scalar S>
void reduceContacts(std::vector<ContactPointT<S>*>& points, int resolution) {
  if (resolution < 1 || resolution > 3) throw detail::makeError("ContactReduction", "", "bin resolution must be 1, 2 or 3", resolution);
  std::erase_if(points, [](ContactPointT<S>* p) {
    const bool finite = p->point.allFinite() && p->normal.allFinite() && std::isfinite(p->depth);
    if (!finite) p->enabled = false;
    return !finite;
  });
  if (points.size() <= 4) return;
  // Positions in units of 2^e, e the largest coordinate's exponent: an exact
  // scaling that leaves every coordinate below 2 in magnitude.
  S largest = S(0);
  for (const auto* p : points) largest = std::max(largest, p->point.cwiseAbs().maxCoeff());
  const S unit = largest > S(0) ? std::ldexp(S(1), std::ilogb(largest)) : S(1);
  const auto scaled = [&](const ContactPointT<S>* p) { return Vec3T<S>(p->point / unit); };
  Vec3T<S> centroid = Vec3T<S>::Zero();
  for (const auto* p : points) centroid += scaled(p);
  centroid /= S(points.size());
  S reach = S(0);
  for (const auto* p : points) reach = std::max(reach, (scaled(p) - centroid).norm());
  const S scale = reach > S(0) ? S(1) / reach : S(0);
  // The small shift keeps round-off from splitting a bin whose edge sits at
  // 0 (resolution 2): a component of ±1e-17 lands on the + side either way.
  const auto binOf = [&](S x) {
    const int b = static_cast<int>((x + S(1)) * S(0.5) * S(resolution) + S(1e-5));
    return std::clamp(b, 0, resolution - 1);
  };
  const S tolerance = S(1e-3) * reach * unit;
  struct Bin {
    std::array<int, 6> key;
    ContactPointT<S>* best;
  };
  std::vector<Bin> bins;
  for (auto* p : points) {
    const Vec3T<S> arm = (scaled(p) - centroid) * scale;
    const Vec3T<S> moment = p->normal.cross(arm);
    const std::array<int, 6> key = {binOf(p->normal.x()), binOf(p->normal.y()), binOf(p->normal.z()),
                                    binOf(moment.x()),    binOf(moment.y()),    binOf(moment.z())};
    auto it = std::find_if(bins.begin(), bins.end(), [&](const Bin& b) { return b.key == key; });
    if (it == bins.end()) {
      bins.push_back({key, p});
      continue;
    }
    const S current = (scaled(it->best) - centroid).squaredNorm(), candidate = (scaled(p) - centroid).squaredNorm();
    const S deeperBy = p->depth - it->best->depth;
    const bool gapPoint = std::min(p->depth, it->best->depth) < S(0);
    const bool better =
        gapPoint && std::abs(deeperBy) > tolerance
            ? deeperBy > S(0)
            : candidate > current * (S(1) + S(1e-6)) || (candidate >= current * (S(1) - S(1e-6)) && deeperBy > S(0));
    (better ? it->best : p)->enabled = false;
    if (better) it->best = p;
  }
  ContactPointT<S>* deepest = nullptr;
  S deepestSurvivor = -std::numeric_limits<S>::infinity();
  for (auto* p : points) {
    if (!deepest || p->depth > deepest->depth) deepest = p;
    if (p->enabled) deepestSurvivor = std::max(deepestSurvivor, p->depth);
  }
  if (deepest->depth - deepestSurvivor > tolerance) deepest->enabled = true;
}

}  // namespace detail
}  // namespace spook
