#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <spook/collide/detail/aabb_tree.hpp>
#include <spook/collide/detail/triangle.hpp>
#include <spook/collide/shapes/shape.hpp>
#include <spook/core/implementation.hpp>

namespace spook {

/// A terrain: a regular grid of resolutionX × resolutionY height samples
/// over the rectangle [−sizeX/2, sizeX/2] × [−sizeY/2, sizeY/2] of the shape
/// frame's xy plane, heights along +z (m), solid below the surface. Sample
/// (i, j) sits at x = −sizeX/2 + i·sizeX/(resolutionX − 1), likewise y, and
/// is stored at index i + resolutionX·j. Cell (i, j) is cut along its
/// diagonal from sample (i, j) to (i+1, j+1) into two triangles,
/// counter-clockwise seen from above; triangle k of the cell has index
/// 2·(i + (resolutionX − 1)·j) + k. Meant for static geometry: no volume.
template <Scalar S>
class HeightFieldT : public ShapeT<S> {
 public:
  static constexpr ShapeType kType = ShapeType::HEIGHTFIELD;
  using Vec3 = spook::Vec3T<S>;
  using Vec2 = Eigen::Matrix<S, 2, 1>;

  /// Throws spook::Error on fewer than 2 × 2 samples, more triangles than a
  /// contact's 32-bit face index can number, a heights vector not of
  /// resolutionX·resolutionY entries, a non-finite height, heights whose
  /// range (highest − lowest) overflows, a size that is not finite and
  /// > 0 m, or a cell so small that its spacing underflows.
  HeightFieldT(std::size_t resolutionX, std::size_t resolutionY, S sizeX, S sizeY, std::vector<S> heights);

  /// Number of samples along x.
  [[nodiscard]] std::size_t getResolutionX() const { return resolutionX_; }
  /// Number of samples along y.
  [[nodiscard]] std::size_t getResolutionY() const { return resolutionY_; }
  /// Extent along x (m).
  [[nodiscard]] S getSizeX() const { return sizeX_; }
  /// Extent along y (m).
  [[nodiscard]] S getSizeY() const { return sizeY_; }
  /// Cell size along x and y (m).
  [[nodiscard]] Vec2 getSpacing() const { return spacing_; }
  /// Number of triangles, two per cell.
  [[nodiscard]] std::size_t getNumTriangles() const { return 2 * (resolutionX_ - 1) * (resolutionY_ - 1); }
  /// Lowest sample height (m).
  [[nodiscard]] S getMinHeight() const { return minHeight_; }
  /// Highest sample height (m).
  [[nodiscard]] S getMaxHeight() const { return maxHeight_; }

  /// Height of sample (i, j) (m); throws when out of range.
  [[nodiscard]] S getHeight(std::size_t i, std::size_t j) const;
  /// Sets the height of sample (i, j) (m); throws, keeping the field, on an
  /// index out of range, a non-finite height or one whose distance to the
  /// others overflows.
  void setHeight(std::size_t i, std::size_t j, S h);

  /// Sample (i, j) as a point, shape frame (m).
  [[nodiscard]] Vec3 getVertex(std::size_t i, std::size_t j) const { return Vec3(gridX(i), gridY(j), height(i, j)); }
  /// Corners of triangle `index`, shape frame (m), counter-clockwise seen from above.
  [[nodiscard]] std::array<Vec3, 3> getTriangle(std::size_t index) const {
    const std::size_t cell = index / 2, i = cell % (resolutionX_ - 1), j = cell / (resolutionX_ - 1);
    if (index % 2 == 0) return {getVertex(i, j), getVertex(i + 1, j), getVertex(i + 1, j + 1)};
    return {getVertex(i, j), getVertex(i + 1, j + 1), getVertex(i, j + 1)};
  }
  /// Unit normal of triangle `index`, shape frame, pointing out of the solid (z > 0).
  [[nodiscard]] Vec3 getNormal(std::size_t index) const {
    const auto [a, b, c] = getTriangle(index);
    return (b - a).cross(c - a).normalized();
  }

  /// Which edges of triangle `index` may give a contact a normal of its own
  /// (detail::edgeActivity): bit k for the edge from corner k to corner
  /// k + 1, bits 0-2 seen from above, 3-5 from below. An edge between two
  /// triangles is active where the surface folds away by more than 5° from
  /// the side looking at it; the rim of the grid is active.
  [[nodiscard]] std::uint8_t getActiveEdges(std::size_t index) const {
    const std::size_t cell = index / 2, i = cell % (resolutionX_ - 1), j = cell / (resolutionX_ - 1);
    const std::size_t cellsX = resolutionX_ - 1, cellsY = resolutionY_ - 1;
    // Neighbours across edges 0, 1, 2 (cell offset, triangle of that cell); see getTriangle.
    const auto across = [&](long di, long dj, std::size_t k) -> std::optional<std::size_t> {
      const long ni = static_cast<long>(i) + di, nj = static_cast<long>(j) + dj;
      if (ni < 0 || nj < 0 || ni >= static_cast<long>(cellsX) || nj >= static_cast<long>(cellsY)) return std::nullopt;
      return 2 * (static_cast<std::size_t>(ni) + cellsX * static_cast<std::size_t>(nj)) + k;
    };
    const std::array<std::optional<std::size_t>, 3> neighbour =
        index % 2 == 0 ? std::array{across(0, -1, 1), across(1, 0, 1), across(0, 0, 1)}
                       : std::array{across(0, 0, 0), across(0, 1, 0), across(-1, 0, 0)};
    std::array<Vec3, 3> normals;
    std::array<const Vec3*, 3> neighbours{};
    for (std::size_t k = 0; k < 3; ++k)
      if (neighbour[k]) {
        normals[k] = getNormal(*neighbour[k]);
        neighbours[k] = &normals[k];
      }
    return detail::activeEdges<S>(getTriangle(index), getNormal(index), neighbours);
  }

  /// Height of the surface above (x, y) (shape frame, m), interpolated on
  /// its triangle; points outside the grid are first clamped onto it.
  /// Throws on a NaN coordinate.
  [[nodiscard]] S heightAt(S x, S y) const {
    if (std::isnan(x) || std::isnan(y))
      throw detail::makeError("HeightField", "", "heightAt needs x and y that are not NaN (m)", Vec2(x, y));
    const S u = std::clamp((x + S(0.5) * sizeX_) / spacing_.x(), S(0), S(resolutionX_ - 1));
    const S v = std::clamp((y + S(0.5) * sizeY_) / spacing_.y(), S(0), S(resolutionY_ - 1));
    const std::size_t i = std::min(static_cast<std::size_t>(u), resolutionX_ - 2);
    const std::size_t j = std::min(static_cast<std::size_t>(v), resolutionY_ - 2);
    const S fu = u - S(i), fv = v - S(j);
    const S h00 = height(i, j), h11 = height(i + 1, j + 1);
    if (fu >= fv) return h00 + fu * (height(i + 1, j) - h00) + fv * (h11 - height(i + 1, j));
    return h00 + fv * (height(i, j + 1) - h00) + fu * (h11 - height(i, j + 1));
  }

  [[nodiscard]] ShapeType getType() const override { return kType; }
  bool collideWithLowerRank(const TransformT<S>& X_WA, const ShapeT<S>& other, const TransformT<S>& X_WB,
                            ContactSinkT<S>& sink) const override {
    return detail::collideWithLowerRank(*this, X_WA, other, X_WB, sink);
  }

  /// 0: a solid below the surface has no finite volume.
  [[nodiscard]] S getVolume() const override { return S(0); }

  /// Always throws: a HeightField has no volume, so no inertia.
  [[nodiscard]] SPDMat3T<S> calculateInertia(S mass) const override;

  /// The grid's x and y extents, z from the lowest to the highest sample (shape frame, m).
  [[nodiscard]] BoundingBoxT<S> getBoundingBox() const override;

  /// Calls visit(index, a, b, c) with the corners (shape frame, m) of each
  /// triangle whose box overlaps `localBox` (shape frame, touching counts);
  /// only the cells under the box's x, y range are looked at.
  template <class F>
  void forEachTriangle(const BoundingBoxT<S>& localBox, F&& visit) const {
    if (!detail::overlaps(localBox, getBoundingBox())) return;
    // One cell of slack on each side absorbs round-off at the cell borders;
    // each triangle's own box then decides.
    const auto [i0, i1] = cellRange(localBox.min.x(), localBox.max.x(), sizeX_, spacing_.x(), resolutionX_);
    const auto [j0, j1] = cellRange(localBox.min.y(), localBox.max.y(), sizeY_, spacing_.y(), resolutionY_);
    for (std::size_t j = j0; j <= j1; ++j)
      for (std::size_t i = i0; i <= i1; ++i)
        for (std::size_t k = 0; k < 2; ++k) {
          const std::size_t index = 2 * (i + (resolutionX_ - 1) * j) + k;
          const auto [a, b, c] = getTriangle(index);
          if (detail::overlaps(localBox, {a.cwiseMin(b).cwiseMin(c), a.cwiseMax(b).cwiseMax(c)})) visit(index, a, b, c);
        }
  }

 protected:
  ~HeightFieldT() override = default;

 private:
  [[nodiscard]] S height(std::size_t i, std::size_t j) const { return heights_[i + resolutionX_ * j]; }
  // Sample coordinates, computed one way everywhere so that boxes and corners agree to the bit.
  [[nodiscard]] S gridX(std::size_t i) const { return S(-0.5) * sizeX_ + S(i) * spacing_.x(); }
  [[nodiscard]] S gridY(std::size_t j) const { return S(-0.5) * sizeY_ + S(j) * spacing_.y(); }

  void requireSample(std::size_t i, std::size_t j) const;

  static void requireFiniteRange(S lowest, S highest);
  void updateHeightRange();

  // Cells [first, last] along one axis that may meet [lo, hi], given that
  // the box meets the grid's extent on that axis.
  [[nodiscard]] static std::pair<std::size_t, std::size_t> cellRange(S lo, S hi, S size, S spacing,
                                                                     std::size_t resolution);

  // Contact points number the triangles with 32 bits.
  static constexpr std::size_t kMaxTriangles = std::numeric_limits<std::uint32_t>::max();

  std::size_t resolutionX_;
  std::size_t resolutionY_;
  S sizeX_ = S(0);
  S sizeY_ = S(0);
  Vec2 spacing_ = Vec2::Zero();
  std::vector<S> heights_;
  S minHeight_ = S(0);
  S maxHeight_ = S(0);
};

template <Scalar S>
HeightFieldT<S>::HeightFieldT(std::size_t resolutionX, std::size_t resolutionY, S sizeX, S sizeY,
                              std::vector<S> heights)
    : resolutionX_(resolutionX), resolutionY_(resolutionY), heights_(std::move(heights)) {
  const std::array<std::size_t, 2> resolution{resolutionX, resolutionY};
  if (resolutionX < 2 || resolutionY < 2)
    throw detail::makeError("HeightField", "", "needs at least 2 x 2 height samples (resolutionX, resolutionY)",
                            resolution);
  // Checked before any product of the resolutions is formed, so that none wraps around.
  if ((resolutionX - 1) > kMaxTriangles / 2 / (resolutionY - 1))
    throw detail::makeError(
        "HeightField", "",
        "2 (resolutionX - 1)(resolutionY - 1) triangles must not exceed " + std::to_string(kMaxTriangles), resolution);
  sizeX_ = this->requireLength("HeightField", "sizeX", sizeX);
  sizeY_ = this->requireLength("HeightField", "sizeY", sizeY);
  if (heights_.size() != resolutionX * resolutionY)
    throw detail::makeError(
        "HeightField", "",
        "needs resolutionX * resolutionY = " + std::to_string(resolutionX * resolutionY) + " heights", heights_.size());
  for (std::size_t k = 0; k < heights_.size(); ++k)
    if (!std::isfinite(heights_[k]))
      throw detail::makeError("HeightField", "", "height " + std::to_string(k) + " must be finite (m)", heights_[k]);
  spacing_ = Vec2(sizeX_ / S(resolutionX - 1), sizeY_ / S(resolutionY - 1));
  if (!(spacing_.minCoeff() >= std::numeric_limits<S>::min()))
    throw detail::makeError("HeightField", "", "cell spacing size / (resolution - 1) must not underflow (m)", spacing_);
  updateHeightRange();
  requireFiniteRange(minHeight_, maxHeight_);
}

template <Scalar S>
S HeightFieldT<S>::getHeight(std::size_t i, std::size_t j) const {
  requireSample(i, j);
  return height(i, j);
}

template <Scalar S>
void HeightFieldT<S>::setHeight(std::size_t i, std::size_t j, S h) {
  requireSample(i, j);
  if (!std::isfinite(h)) throw detail::makeError("HeightField", "", "height must be finite (m)", h);
  S& sample = heights_[i + resolutionX_ * j];
  const S old = sample, oldMin = minHeight_, oldMax = maxHeight_;
  const auto apply = [&] {
    sample = h;
    if (old == oldMin || old == oldMax) return updateHeightRange();
    minHeight_ = std::min(oldMin, h);
    maxHeight_ = std::max(oldMax, h);
  };
  const auto undo = [&] { sample = old, minHeight_ = oldMin, maxHeight_ = oldMax; };
  apply();
  const Vec2 range(minHeight_, maxHeight_);
  undo();
  requireFiniteRange(range.x(), range.y());
  this->change(apply, undo);
}

template <Scalar S>
auto HeightFieldT<S>::calculateInertia(S mass) const -> SPDMat3T<S> {
  throw detail::makeError("HeightField", "", "a HeightField has no volume, hence no inertia; mass (kg)", mass);
}

template <Scalar S>
auto HeightFieldT<S>::getBoundingBox() const -> BoundingBoxT<S> {
  return {Vec3(gridX(0), gridY(0), minHeight_), Vec3(gridX(resolutionX_ - 1), gridY(resolutionY_ - 1), maxHeight_)};
}

template <Scalar S>
void HeightFieldT<S>::requireSample(std::size_t i, std::size_t j) const {
  if (i >= resolutionX_ || j >= resolutionY_)
    throw detail::makeError("HeightField", "",
                            "sample (i, j) must lie in [0, " + std::to_string(resolutionX_) + ") x [0, " +
                                std::to_string(resolutionY_) + ")",
                            std::array<std::size_t, 2>{i, j});
}

template <Scalar S>
void HeightFieldT<S>::requireFiniteRange(S lowest, S highest) {
  if (!std::isfinite(highest - lowest))
    throw detail::makeError("HeightField", "", "heights must span a finite range, highest - lowest (m)",
                            Vec2(lowest, highest));
}

template <Scalar S>
void HeightFieldT<S>::updateHeightRange() {
  const auto [lo, hi] = std::minmax_element(heights_.begin(), heights_.end());
  minHeight_ = *lo;
  maxHeight_ = *hi;
}

template <Scalar S>
auto HeightFieldT<S>::cellRange(S lo, S hi, S size, S spacing, std::size_t resolution)
    -> std::pair<std::size_t, std::size_t> {
  const S cells = S(resolution - 1);
  const S first = std::clamp(std::floor((lo + S(0.5) * size) / spacing) - S(1), S(0), cells - S(1));
  const S last = std::clamp(std::floor((hi + S(0.5) * size) / spacing) + S(1), S(0), cells - S(1));
  return {static_cast<std::size_t>(first), static_cast<std::size_t>(last)};
}

SPOOK_COMPILED_WITH_COLLIDERS(class, HeightFieldT)

using HeightField = HeightFieldT<double>;
using HeightFieldRef = ref_ptr<HeightField>;
namespace f32 {
using HeightField = HeightFieldT<float>;
using HeightFieldRef = ref_ptr<HeightField>;
}  // namespace f32

}  // namespace spook
