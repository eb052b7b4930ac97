#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numeric>
#include <utility>
#include <vector>

#include <spook/collide/bounding_box.hpp>
#include <spook/core/math.hpp>

namespace spook::detail {

/// True when two closed boxes share at least one point (touching counts).
template <Scalar S>
[[nodiscard]] bool overlaps(const BoundingBoxT<S>& a, const BoundingBoxT<S>& b) {
  return (a.min.array() <= b.max.array()).all() && (b.min.array() <= a.max.array()).all();
}

/// The axis-aligned box, in the target frame, around `box` moved by the
/// rigid transform X (source → target): center X c, half extents |R| h.
template <Scalar S>
[[nodiscard]] BoundingBoxT<S> transformBox(const BoundingBoxT<S>& box, const TransformT<S>& X) {
  const Vec3T<S> center = X.linear() * box.center() + X.translation();
  const Vec3T<S> reach = X.linear().cwiseAbs() * box.halfExtents();
  return {center - reach, center + reach};
}

/// A static bounding-volume hierarchy over N primitives given by their
/// boxes, in the frame the boxes are given in. Built once, top down: each
/// node's primitives are split at the median of their box centers along the
/// longest axis of those centers' bounds, so the depth is about log2(N/4)
/// whatever the input. Nodes sit in one vector in depth-first order (a left
/// child follows its parent); a leaf holds at most kMaxLeafSize primitives.
template <Scalar S>
class AabbTree {
 public:
  using Box = BoundingBoxT<S>;
  using Vec3 = spook::Vec3T<S>;
  static constexpr std::size_t kMaxLeafSize = 4;

  /// An empty tree; every query visits nothing.
  AabbTree() = default;

  /// Builds the tree over `boxes`; primitive i is boxes[i] (fewer than 2³² primitives).
  explicit AabbTree(const std::vector<Box>& boxes) { build(boxes); }

  /// Number of primitives.
  [[nodiscard]] std::size_t size() const { return primitives_.size(); }
  /// True when the tree holds no primitive.
  [[nodiscard]] bool empty() const { return primitives_.empty(); }
  /// Number of nodes, leaves included.
  [[nodiscard]] std::size_t getNodeCount() const { return nodes_.size(); }
  /// Number of levels; 1 for a single leaf, 0 for an empty tree.
  [[nodiscard]] std::size_t getDepth() const { return depth_; }
  /// Box around all primitives, tree frame (m); a zero box when empty.
  [[nodiscard]] Box getBoundingBox() const { return nodes_.empty() ? Box{} : nodes_.front().box; }

  /// Calls visit(primitiveIndex) once for each primitive whose box overlaps
  /// `box` (tree frame, touching counts).
  template <class F>
  void query(const Box& box, F&& visit) const {
    if (nodes_.empty()) return;
    std::array<std::uint32_t, kMaxStack> stack{};
    std::size_t top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const std::uint32_t id = stack[--top];
      const Node& node = nodes_[id];
      if (!overlaps(node.box, box)) continue;
      if (node.count == 0) {
        stack[top++] = node.index;
        stack[top++] = id + 1;
        continue;
      }
      for (std::uint32_t k = node.index; k < node.index + node.count; ++k)
        if (overlaps(boxes_[k], box)) visit(static_cast<std::size_t>(primitives_[k]));
    }
  }

  /// Calls visit(i, j) once for each primitive i of this tree and j of
  /// `other` whose boxes overlap, with `other` placed in this tree's frame
  /// by X_thisOther (other → this). Primitive j is tested with
  /// transformBox(its box, X_thisOther).
  template <class F>
  void queryPairs(const AabbTree& other, const TransformT<S>& X_thisOther, F&& visit) const {
    if (nodes_.empty() || other.nodes_.empty()) return;
    const Mat3T<S> R = X_thisOther.linear();
    const Mat3T<S> absR = R.cwiseAbs();
    const Vec3 t = X_thisOther.translation();
    // Node boxes of `other` grow by a few ulps of their coordinates, so that
    // round-off in the transform never culls a pair its leaves would report.
    const auto movedNode = [&](const Box& b) {
      Box moved = transformBox(b, X_thisOther);
      const Vec3 scale = absR * b.min.cwiseAbs().cwiseMax(b.max.cwiseAbs()) + t.cwiseAbs();
      const Vec3 margin = S(16) * std::numeric_limits<S>::epsilon() * scale;
      return Box{moved.min - margin, moved.max + margin};
    };
    std::array<std::array<std::uint32_t, 2>, 2 * kMaxStack> stack{};
    std::size_t top = 0;
    stack[top++] = {0, 0};
    while (top > 0) {
      const auto [ia, ib] = stack[--top];
      const Node& a = nodes_[ia];
      const Node& b = other.nodes_[ib];
      if (!overlaps(a.box, movedNode(b.box))) continue;
      if (a.count > 0 && b.count > 0) {
        for (std::uint32_t kb = b.index; kb < b.index + b.count; ++kb) {
          const Box moved = transformBox(other.boxes_[kb], X_thisOther);
          for (std::uint32_t ka = a.index; ka < a.index + a.count; ++ka)
            if (overlaps(boxes_[ka], moved))
              visit(static_cast<std::size_t>(primitives_[ka]), static_cast<std::size_t>(other.primitives_[kb]));
        }
      } else if (b.count > 0 || (a.count == 0 && a.box.halfExtents().sum() >= b.box.halfExtents().sum())) {
        stack[top++] = {a.index, ib};
        stack[top++] = {ia + 1, ib};
      } else {
        stack[top++] = {ia, b.index};
        stack[top++] = {ia, ib + 1};
      }
    }
  }

 private:
  struct Node {
    Box box;
    std::uint32_t index = 0;  ///< inner node: right child (the left one is the next node); leaf: first slot
    std::uint32_t count = 0;  ///< primitives in a leaf, 0 for an inner node
  };
  // A median split halves the primitives at every level, so fewer than 2³²
  // primitives give at most 31 levels: a depth-first stack never holds more
  // than depth + 1 nodes, a pair stack more than depthA + depthB + 1 pairs.
  static constexpr std::size_t kMaxStack = 64;

  void build(const std::vector<Box>& boxes) {
    const std::size_t n = boxes.size();
    if (n == 0) return;
    std::vector<Vec3> centers(n);
    for (std::size_t i = 0; i < n; ++i) centers[i] = boxes[i].min + boxes[i].max;  // twice the center
    std::vector<std::uint32_t> order(n);
    std::iota(order.begin(), order.end(), std::uint32_t(0));
    nodes_.reserve(2 * (n / kMaxLeafSize + 1));

    struct Task {
      std::size_t begin, end, level;
      std::size_t parent;  ///< node whose right child this is, or npos for a left child or the root
    };
    constexpr std::size_t npos = std::numeric_limits<std::size_t>::max();
    std::vector<Task> tasks{{0, n, 1, npos}};
    while (!tasks.empty()) {
      const Task task = tasks.back();
      tasks.pop_back();
      const auto id = static_cast<std::uint32_t>(nodes_.size());
      if (task.parent != npos) nodes_[task.parent].index = id;
      depth_ = std::max(depth_, task.level);

      Node node;
      node.box = boxes[order[task.begin]];
      Box centerBounds{centers[order[task.begin]], centers[order[task.begin]]};
      for (std::size_t k = task.begin + 1; k < task.end; ++k) {
        const Box& b = boxes[order[k]];
        node.box = {node.box.min.cwiseMin(b.min), node.box.max.cwiseMax(b.max)};
        centerBounds = {centerBounds.min.cwiseMin(centers[order[k]]), centerBounds.max.cwiseMax(centers[order[k]])};
      }
      const std::size_t count = task.end - task.begin;
      if (count <= kMaxLeafSize) {
        node.index = static_cast<std::uint32_t>(task.begin);
        node.count = static_cast<std::uint32_t>(count);
        nodes_.push_back(node);
        continue;
      }
      nodes_.push_back(node);
      int axis = 0;
      (centerBounds.max - centerBounds.min).maxCoeff(&axis);
      const std::size_t mid = task.begin + count / 2;
      const auto first = order.begin() + static_cast<std::ptrdiff_t>(task.begin);
      std::nth_element(first, order.begin() + static_cast<std::ptrdiff_t>(mid),
                       order.begin() + static_cast<std::ptrdiff_t>(task.end), [&](std::uint32_t p, std::uint32_t q) {
                         const S cp = centers[p][axis], cq = centers[q][axis];
                         return cp < cq || (cp == cq && p < q);
                       });
      // The left child is popped next, so it lands right after its parent.
      tasks.push_back({mid, task.end, task.level + 1, id});
      tasks.push_back({task.begin, mid, task.level + 1, npos});
    }
    primitives_ = std::move(order);
    boxes_.resize(n);
    for (std::size_t k = 0; k < n; ++k) boxes_[k] = boxes[primitives_[k]];
  }

  std::vector<Node> nodes_;
  std::vector<std::uint32_t> primitives_;  ///< primitive indices, leaf after leaf
  std::vector<Box> boxes_;                 ///< their boxes, in the same order
  std::size_t depth_ = 0;
};

}  // namespace spook::detail
