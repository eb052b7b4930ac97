#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include <spook/collide/contact_point.hpp>

namespace spook {

namespace detail {
/// Gap, relative to the smaller shape's size, within which two shapes, and
/// the corners of their manifold (FeatureClipping::contacts), count as
/// touching (contacts of depth 0); a mesh's triangle search grows the
/// shape's box by it. A body resting on a mesh settles about
/// 1e-6 m deep, and where its contacts pass from one triangle to the next
/// the solve lifts or tilts it by about as much: a contact lost at such a
/// gap lets the body fall freely for a step (2.7 mm at 60 Hz) and bump.
inline constexpr double kTouchingGap = 1e-5;
}  // namespace detail

/// Where a collider writes the contact points of one shape pair. It keeps
/// the "first toward second" normal convention when the pair was handed to
/// the collider in reverse order (flipped), and never lets a non-finite
/// point through: it drops it and counts it in getNumDropped().
///
/// A sink may carry a speculative margin (m): the shapes may come that much
/// closer within the coming step, and a collider that supports it also
/// reports the points where they are apart by up to the margin, as gap
/// points of negative depth (accepts()). The solver lets such a point close
/// its gap within the step and no more, so that a contact is not born
/// overlapping by up to the approach speed times the step.
template <Scalar S>
class ContactSinkT {
 public:
  explicit ContactSinkT(std::vector<ContactPointT<S>>& points, bool flipped = false, S margin = S(0))
      : ContactSinkT(points, flipped, std::make_shared<std::size_t>(0), margin) {}

  /// The speculative margin (m), >= 0.
  [[nodiscard]] S margin() const { return margin_; }
  /// True when a point of this depth is to be written: touching or
  /// overlapping, or apart by no more than the margin or `touching`
  /// (then with addSpeculative).
  [[nodiscard]] bool accepts(S depth, S touching = S(0)) const { return depth >= -std::max(margin_, touching); }

  /// Adds a touching point: world position (m), unit normal from the
  /// collider's first shape toward its second, penetration depth (m,
  /// clamped at 0).
  void add(const Vec3T<S>& point, const Vec3T<S>& normal, S depth) {
    addSpeculative(point, normal, std::max(depth, S(0)));
  }

  /// Adds a point that may be a gap point: as add(), but a point apart by
  /// more than `touching` (the collider's touching gap) keeps its negative
  /// depth when the sink has a margin.
  void addSpeculative(const Vec3T<S>& point, const Vec3T<S>& normal, S depth, S touching = S(0)) {
    if (!(point.allFinite() && normal.allFinite() && std::isfinite(depth))) {
      ++*dropped_;
      return;
    }
    ContactPointT<S> contact;
    contact.point = point;
    contact.normal = flipped_ ? Vec3T<S>(-normal) : normal;
    contact.depth = depth >= -touching || margin_ == S(0) ? std::max(depth, S(0)) : depth;
    contact.faceIndex1 = flipped_ ? faces_[1] : faces_[0];
    contact.faceIndex2 = flipped_ ? faces_[0] : faces_[1];
    points_->push_back(contact);
  }

  /// The triangles (of a Trimesh or HeightField) of the collider's first
  /// and second shape that the next points touch; 0 for other shapes.
  void setFaceIndices(std::size_t first, std::size_t second) {
    faces_ = {static_cast<std::uint32_t>(first), static_cast<std::uint32_t>(second)};
  }

  /// The same output with the shape order swapped (sharing the drop count).
  [[nodiscard]] ContactSinkT reversed() const { return ContactSinkT(*points_, !flipped_, dropped_, margin_); }

  /// A sink into `points`, unflipped, that shares this one's drop count and
  /// margin: where a collider adjusts its points before it add()s them here.
  [[nodiscard]] ContactSinkT staging(std::vector<ContactPointT<S>>& points) const {
    return ContactSinkT(points, false, dropped_, margin_);
  }

  /// Number of points written so far.
  [[nodiscard]] std::size_t size() const { return points_->size(); }
  /// Number of points refused so far because their position, normal or
  /// depth was not finite (this sink and its reversed() copies).
  [[nodiscard]] std::size_t getNumDropped() const { return *dropped_; }

 private:
  ContactSinkT(std::vector<ContactPointT<S>>& points, bool flipped, std::shared_ptr<std::size_t> dropped, S margin)
      : points_(&points), flipped_(flipped), dropped_(std::move(dropped)), margin_(margin > S(0) ? margin : S(0)) {}

  std::vector<ContactPointT<S>>* points_;
  bool flipped_;
  std::shared_ptr<std::size_t> dropped_;
  std::array<std::uint32_t, 2> faces_{};
  S margin_ = S(0);
};

}  // namespace spook
