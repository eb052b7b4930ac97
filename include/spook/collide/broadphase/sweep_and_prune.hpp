#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include <spook/collide/bounding_box.hpp>

namespace spook::detail {

/// Sweep and prune along one axis: boxes sorted by their lower bound on the
/// axis of largest spread of the box centers, then swept, each box tested
/// against the boxes whose interval it overlaps. Boxes unbounded along the
/// axis (planes) are kept aside and tested against every box.
/// The sweep rebuilds from scratch each pass in O(n log n), with no
/// persistent structure to refit when everything moves every step.
template <Scalar S>
class SweepAndPrune {
 public:
  /// Calls visit(i, j), i < j, for every pair of overlapping boxes.
  template <class F>
  void findPairs(const std::vector<BoundingBoxT<S>>& boxes, F&& visit) {
    const int axis = sweepAxis(boxes);
    bounded_.clear();
    unbounded_.clear();
    for (std::size_t i = 0; i < boxes.size(); ++i) {
      if (std::isfinite(boxes[i].min[axis]) && std::isfinite(boxes[i].max[axis]))
        bounded_.push_back(i);
      else
        unbounded_.push_back(i);
    }
    std::sort(bounded_.begin(), bounded_.end(),
              [&](std::size_t a, std::size_t b) { return boxes[a].min[axis] < boxes[b].min[axis]; });
    for (std::size_t k = 0; k < bounded_.size(); ++k) {
      const BoundingBoxT<S>& a = boxes[bounded_[k]];
      for (std::size_t m = k + 1; m < bounded_.size(); ++m) {
        const BoundingBoxT<S>& b = boxes[bounded_[m]];
        if (b.min[axis] > a.max[axis]) break;
        if (overlap(a, b)) emit(bounded_[k], bounded_[m], visit);
      }
    }
    for (std::size_t k = 0; k < unbounded_.size(); ++k)
      for (std::size_t i = 0; i < boxes.size(); ++i)
        if (i != unbounded_[k] && overlap(boxes[unbounded_[k]], boxes[i]) &&
            !(isUnbounded(i) && i < unbounded_[k]))
          emit(unbounded_[k], i, visit);
  }

  [[nodiscard]] static bool overlap(const BoundingBoxT<S>& a, const BoundingBoxT<S>& b) {
    return (a.min.array() <= b.max.array()).all() && (b.min.array() <= a.max.array()).all();
  }

 private:
  template <class F>
  static void emit(std::size_t i, std::size_t j, F& visit) {
    if (i < j)
      visit(i, j);
    else
      visit(j, i);
  }
  [[nodiscard]] bool isUnbounded(std::size_t i) const {
    return std::find(unbounded_.begin(), unbounded_.end(), i) != unbounded_.end();
  }
  // The axis along which the finite box centers spread the most.
  static int sweepAxis(const std::vector<BoundingBoxT<S>>& boxes) {
    Vec3<S> sum = Vec3<S>::Zero(), sumSq = Vec3<S>::Zero();
    std::size_t n = 0;
    for (const auto& b : boxes) {
      if (!(b.min.allFinite() && b.max.allFinite())) continue;
      const Vec3<S> c = b.center();
      sum += c;
      sumSq += c.cwiseAbs2();
      ++n;
    }
    if (n == 0) return 0;
    const Vec3<S> variance = sumSq / S(n) - (sum / S(n)).cwiseAbs2();
    int axis = 0;
    variance.maxCoeff(&axis);
    return axis;
  }

  std::vector<std::size_t> bounded_;
  std::vector<std::size_t> unbounded_;
};

}  // namespace spook::detail
