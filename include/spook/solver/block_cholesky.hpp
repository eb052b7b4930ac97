#pragma once

#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCore>

#include <spook/solver/small_dense.hpp>

namespace spook::detail {

/// Sparse Cholesky factorization K = L Lᵀ of a symmetric positive definite
/// matrix of 6×6 blocks (one block row per body): the body-space matrix
/// M + GᵀΣ⁻¹G of a direct solve (body_space_solve.hpp). The elimination
/// runs over blocks, each operation a fixed-size 6×6 product, instead of
/// over the 6n scalar columns of a general sparse LDLᵀ (the approach of
/// supernodal factorizations, with the body as the supernode).
///
/// analyze() orders the blocks by approximate minimum degree on the body
/// graph (Amestoy, Davis & Duff 1996, Eigen's AMD) and computes the fill of
/// L (the elimination tree: Liu 1990, "The role of elimination trees in
/// sparse factorization"); factorize() then runs a right-looking block
/// elimination over that structure for any values of the same pattern.
class BlockCholesky {
 public:
  using Mat6 = Eigen::Matrix<double, 6, 6>;
  using Vec6 = Eigen::Matrix<double, 6, 1>;

  /// The pattern: n block rows and the blocks (row, column), row > column,
  /// of K's lower triangle; factorize() takes their values in this order.
  void analyze(int n, const std::vector<std::pair<int, int>>& lowerBlocks) {
    n_ = n;
    const auto size = static_cast<std::size_t>(n);
    // Fill-reducing order of the body graph: order_[k] is the block eliminated k-th.
    Eigen::SparseMatrix<double> graph(n, n);
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(size + 2 * lowerBlocks.size());
    for (int i = 0; i < n; ++i) entries.emplace_back(i, i, 1.0);
    for (const auto& [r, c] : lowerBlocks) {
      entries.emplace_back(r, c, 1.0);
      entries.emplace_back(c, r, 1.0);
    }
    graph.setFromTriplets(entries.begin(), entries.end());
    Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> permutation;
    Eigen::AMDOrdering<int>()(graph, permutation);
    order_.assign(permutation.indices().data(), permutation.indices().data() + n);
    position_.assign(size, 0);
    for (int k = 0; k < n; ++k) position_[static_cast<std::size_t>(order_[static_cast<std::size_t>(k)])] = k;

    // Each column's rows below the diagonal, in elimination order: K's own,
    // then the fill its children in the elimination tree pass up.
    std::vector<std::vector<int>> below(size), children(size);
    for (const auto& [r, c] : lowerBlocks) {
      const int a = position_[static_cast<std::size_t>(r)], b = position_[static_cast<std::size_t>(c)];
      below[static_cast<std::size_t>(std::min(a, b))].push_back(std::max(a, b));
    }
    std::vector<int> mark(size, -1);
    columnStart_.assign(size + 1, 0);
    rows_.clear();
    for (int j = 0; j < n; ++j) {
      std::vector<int>& column = below[static_cast<std::size_t>(j)];
      std::vector<int> rows;
      const auto add = [&](int i) {
        if (i == j || mark[static_cast<std::size_t>(i)] == j) return;
        mark[static_cast<std::size_t>(i)] = j;
        rows.push_back(i);
      };
      for (int i : column) add(i);
      for (int child : children[static_cast<std::size_t>(j)])
        for (int s = columnStart_[static_cast<std::size_t>(child)]; s < columnStart_[static_cast<std::size_t>(child) + 1]; ++s)
          add(rows_[static_cast<std::size_t>(s)]);
      std::sort(rows.begin(), rows.end());
      if (!rows.empty()) children[static_cast<std::size_t>(rows.front())].push_back(j);
      rows_.insert(rows_.end(), rows.begin(), rows.end());
      columnStart_[static_cast<std::size_t>(j) + 1] = static_cast<int>(rows_.size());
    }
    blocks_.assign(rows_.size(), Mat6::Zero());
    diagonal_.assign(size, Mat6::Zero());

    // Where each input block lands (a slot of L), and where each product of
    // a column's two blocks is subtracted (−1: the diagonal of the row).
    inputSlot_.resize(lowerBlocks.size());
    inputTransposed_.resize(lowerBlocks.size());
    for (std::size_t p = 0; p < lowerBlocks.size(); ++p) {
      const int a = position_[static_cast<std::size_t>(lowerBlocks[p].first)];
      const int b = position_[static_cast<std::size_t>(lowerBlocks[p].second)];
      inputSlot_[p] = slot(std::max(a, b), std::min(a, b));
      inputTransposed_[p] = a < b;  // the block (row, column) lands above the diagonal: store its transpose
    }
    updateSlot_.clear();
    for (int j = 0; j < n; ++j) {
      const int first = columnStart_[static_cast<std::size_t>(j)], last = columnStart_[static_cast<std::size_t>(j) + 1];
      for (int b = first; b < last; ++b)
        for (int a = first; a <= b; ++a)
          updateSlot_.push_back(a == b ? -1 : slot(rows_[static_cast<std::size_t>(b)], rows_[static_cast<std::size_t>(a)]));
    }
  }

  /// Factorizes K given its diagonal blocks (one per block row, in the
  /// input numbering) and its lower blocks in analyze()'s order. False when
  /// K is not positive definite (a pivot block failed its Cholesky).
  bool factorize(const std::vector<Mat6>& diagonal, const std::vector<Mat6>& lower) {
    for (int i = 0; i < n_; ++i)
      diagonal_[static_cast<std::size_t>(position_[static_cast<std::size_t>(i)])] = diagonal[static_cast<std::size_t>(i)];
    std::fill(blocks_.begin(), blocks_.end(), Mat6::Zero());
    for (std::size_t p = 0; p < lower.size(); ++p)
      blocks_[static_cast<std::size_t>(inputSlot_[p])] = inputTransposed_[p] ? Mat6(lower[p].transpose()) : lower[p];

    std::size_t update = 0;
    for (int j = 0; j < n_; ++j) {
      Mat6& pivot = diagonal_[static_cast<std::size_t>(j)];
      Mat6 factor;
      if (!choleskyLower<6>(pivot, factor)) return false;
      // L_jj⁻¹ (lower triangular) is kept: products with it are the fixed-size
      // kernels, where a triangular solve per block is not.
      invertLowerTriangular<6>(factor, pivot);
      const Mat6 inverseTransposed = pivot.transpose();
      const int first = columnStart_[static_cast<std::size_t>(j)], last = columnStart_[static_cast<std::size_t>(j) + 1];
      // L_ij = K_ij L_jj⁻ᵀ.
      for (int s = first; s < last; ++s) {
        Mat6& block = blocks_[static_cast<std::size_t>(s)];
        block = block * inverseTransposed;
      }
      // K_ab −= L_aj L_bjᵀ for the rows a ≥ b of the column.
      for (int b = first; b < last; ++b) {
        const Mat6& Lb = blocks_[static_cast<std::size_t>(b)];
        for (int a = first; a <= b; ++a) {
          const int target = updateSlot_[update++];
          const Mat6& La = blocks_[static_cast<std::size_t>(a)];
          if (target < 0) diagonal_[static_cast<std::size_t>(rows_[static_cast<std::size_t>(b)])].noalias() -= Lb * La.transpose();
          else blocks_[static_cast<std::size_t>(target)].noalias() -= Lb * La.transpose();
        }
      }
    }
    return true;
  }

  /// Solves K x = b in place (b: 6 entries per block row, input numbering).
  void solve(Eigen::VectorXd& b) const {
    std::vector<Vec6>& y = scratch_;
    y.resize(static_cast<std::size_t>(n_));
    for (int i = 0; i < n_; ++i) y[static_cast<std::size_t>(position_[static_cast<std::size_t>(i)])] = b.segment<6>(6 * i);
    for (int j = 0; j < n_; ++j) {
      Vec6& yj = y[static_cast<std::size_t>(j)];
      yj = diagonal_[static_cast<std::size_t>(j)] * yj;
      for (int s = columnStart_[static_cast<std::size_t>(j)]; s < columnStart_[static_cast<std::size_t>(j) + 1]; ++s)
        y[static_cast<std::size_t>(rows_[static_cast<std::size_t>(s)])].noalias() -= blocks_[static_cast<std::size_t>(s)] * yj;
    }
    for (int j = n_ - 1; j >= 0; --j) {
      Vec6& yj = y[static_cast<std::size_t>(j)];
      for (int s = columnStart_[static_cast<std::size_t>(j)]; s < columnStart_[static_cast<std::size_t>(j) + 1]; ++s)
        yj.noalias() -= blocks_[static_cast<std::size_t>(s)].transpose() * y[static_cast<std::size_t>(rows_[static_cast<std::size_t>(s)])];
      yj = diagonal_[static_cast<std::size_t>(j)].transpose() * yj;
    }
    for (int i = 0; i < n_; ++i) b.segment<6>(6 * i) = y[static_cast<std::size_t>(position_[static_cast<std::size_t>(i)])];
  }

  /// Blocks of L below the diagonal (the fill included).
  [[nodiscard]] std::size_t numFactorBlocks() const { return rows_.size(); }

  /// The multiply-adds of one factorize(), known from analyze(): 216 per
  /// 6×6 block product, a pivot's Cholesky and inverse counted as two.
  [[nodiscard]] double factorizationWork() const {
    const double blocks = static_cast<double>(rows_.size());
    return 216.0 * (static_cast<double>(updateSlot_.size()) + blocks + 2.0 * n_);
  }

  /// About how many solve() calls one factorize() costs (a solve: 36
  /// multiply-adds per block-vector product, two per block).
  [[nodiscard]] double solvesPerFactorization() const {
    const double blocks = static_cast<double>(rows_.size());
    return factorizationWork() / (36.0 * 2.0 * (blocks + n_) + 1.0);
  }

 private:
  // The slot of L's block (row, column), row > column, both in elimination order.
  int slot(int row, int column) const {
    const auto first = rows_.begin() + columnStart_[static_cast<std::size_t>(column)];
    const auto last = rows_.begin() + columnStart_[static_cast<std::size_t>(column) + 1];
    return static_cast<int>(std::lower_bound(first, last, row) - rows_.begin());
  }

  int n_ = 0;
  std::vector<int> order_, position_;       ///< elimination order and its inverse
  std::vector<int> columnStart_, rows_;     ///< L's blocks below the diagonal, column by column
  std::vector<int> inputSlot_, updateSlot_;
  std::vector<char> inputTransposed_;
  std::vector<Mat6> diagonal_, blocks_;     ///< L_jj⁻¹ (lower triangular) and L's blocks below the diagonal
  mutable std::vector<Vec6> scratch_;
};

}  // namespace spook::detail
