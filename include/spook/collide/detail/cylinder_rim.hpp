#pragma once

#include <array>

#include <spook/collide/contact_sink.hpp>
#include <spook/core/math.hpp>
#include <spook/core/scalar.hpp>

namespace spook::detail {

/// The contact candidates of a cylinder (radius r, half height, axis u
/// through its center, world) against a plane of unit normal n: on each cap
/// rim four points 90° apart, starting from the rim point farthest along
/// −n, v = −(n − (n·u) u)/|…| (x, a vector ⟂ u, where the axis is along n
/// and every rim point is as far). The deepest point of the cylinder is
/// always among them; a cylinder lying on its side has one per cap at its
/// side line, one standing on a cap four spread around its rim.
template <Scalar S>
std::array<Vec3T<S>, 8> cylinderRimCandidates(const Vec3T<S>& center, const Vec3T<S>& u, const Vec3T<S>& x, S r,
                                              S halfHeight, const Vec3T<S>& n) {
  // Projected off u once more: for a cylinder standing nearly upright
  // (n ≈ ±u) the first difference is round-off that need not be ⟂ u (in
  // float it made rim points below the cap).
  Vec3T<S> across = (n.dot(u)) * u - n;
  across -= across.dot(u) * u;
  const S acrossLength = across.norm();
  const Vec3T<S> v = acrossLength > ScalarTraits<S>::epsilon() ? Vec3T<S>(across / acrossLength) : x;
  const Vec3T<S> w = u.cross(v);
  const std::array<Vec3T<S>, 4> rim = {v, w, Vec3T<S>(-v), Vec3T<S>(-w)};
  std::array<Vec3T<S>, 8> out;
  std::size_t k = 0;
  for (const S side : {S(-1), S(1)})
    for (const Vec3T<S>& direction : rim) out[k++] = center + side * halfHeight * u + r * direction;
  return out;
}

/// A cylinder resting on a face as on a plane (the face of a box, a hull or
/// a triangle): its rim `candidates` over the face (`over(p)`) that the
/// sink accepts are its contacts, touching or gap points, each midway
/// between the rim and the face, normal `up` (the face's unit normal toward
/// the cylinder) times `normalSign` (+1 where the face's shape is the
/// pair's first). `onFace` is a point of the face's plane. Where a
/// candidate within `touching` of the face lies where `restsAcross(p)`
/// (beside the face across an edge) the cylinder rests across that edge:
/// nothing is written and false is returned, for the caller to leave the
/// pair to the shapes' features.
template <Scalar S, Scalar T, class Over, class RestsAcross>
bool addRimPointsOverFace(const std::array<Vec3T<T>, 8>& candidates, const Vec3T<T>& up, const Vec3T<T>& onFace,
                          T touching, T normalSign, Over over, RestsAcross restsAcross, ContactSinkT<S>& sink) {
  for (const Vec3T<T>& p : candidates)
    if (up.dot(p - onFace) <= touching && restsAcross(p)) return false;
  const Vec3T<S> normal = (normalSign * up).template cast<S>();
  for (const Vec3T<T>& p : candidates) {
    const T height = up.dot(p - onFace);
    if (sink.accepts(S(-height), S(touching)) && over(p))
      sink.addSpeculative(Vec3T<T>(p - T(0.5) * height * up).template cast<S>(), normal, S(-height), S(touching));
  }
  return true;
}

}  // namespace spook::detail
