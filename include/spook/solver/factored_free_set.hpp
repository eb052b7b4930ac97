#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>

namespace spook::detail {

/// What a direct solve's updates of a factor share (free_set_update.hpp in
/// row space, BodySpaceSolve in body space): the rows free when the factor
/// was made, the rows whose state differs now, and per changed row a column
/// solved with the factor, kept while the factor stands.
class FactoredFreeSet {
 public:
  /// Rows changed against the factorized free set, at most, for an update.
  static constexpr int kMaxChangedRows = 32;
  /// Kept columns per factor, at most.
  static constexpr int kMaxColumns = 2 * kMaxChangedRows;

  /// A new factor, made with the rows freeIndex[k] ≥ 0 free.
  void reset(const std::vector<int>& freeIndex) {
    wasFree_.resize(freeIndex.size());
    for (std::size_t k = 0; k < freeIndex.size(); ++k) wasFree_[k] = freeIndex[k] >= 0 ? 1 : 0;
    columnOf_.assign(freeIndex.size(), -1);
    columns_.clear();
  }

  /// No factor.
  void clear() {
    wasFree_.clear();
    columnOf_.clear();
    columns_.clear();
  }

  /// Whether the rows freeIndex[k] ≥ 0 are those free in the factor.
  [[nodiscard]] bool isFactorized(const std::vector<int>& freeIndex) const {
    if (wasFree_.size() != freeIndex.size()) return false;
    for (std::size_t k = 0; k < freeIndex.size(); ++k)
      if ((freeIndex[k] >= 0) != (wasFree_[k] != 0)) return false;
    return true;
  }

  /// Collects the rows whose state in `freeIndex` differs from the
  /// factorized one, and makes the column `makeColumn(k)` of each not seen
  /// changed before. False where there is no factor for these rows or the
  /// change passes kMaxChangedRows or kMaxColumns.
  template <class MakeColumn>
  bool collect(const std::vector<int>& freeIndex, MakeColumn&& makeColumn) {
    if (wasFree_.size() != freeIndex.size()) return false;
    changed_.clear();
    for (std::size_t k = 0; k < freeIndex.size(); ++k)
      if ((freeIndex[k] >= 0) != (wasFree_[k] != 0)) {
        if (static_cast<int>(changed_.size()) == kMaxChangedRows) return false;
        changed_.push_back(static_cast<int>(k));
      }
    for (int k : changed_)
      if (columnOf_[static_cast<std::size_t>(k)] < 0) {
        if (static_cast<int>(columns_.size()) == kMaxColumns) return false;
        columnOf_[static_cast<std::size_t>(k)] = static_cast<int>(columns_.size());
        columns_.push_back(makeColumn(k));
      }
    return true;
  }

  /// Whether row k was free in the factorized matrix.
  [[nodiscard]] bool wasFree(int k) const { return wasFree_[static_cast<std::size_t>(k)] != 0; }
  /// The rows of the last collect().
  [[nodiscard]] const std::vector<int>& changed() const { return changed_; }
  /// The column of a changed row.
  [[nodiscard]] const Eigen::VectorXd& column(int k) const {
    return columns_[static_cast<std::size_t>(columnOf_[static_cast<std::size_t>(k)])];
  }

 private:
  std::vector<char> wasFree_;
  std::vector<int> columnOf_;  ///< per row: its kept column, or −1
  std::vector<Eigen::VectorXd> columns_;
  std::vector<int> changed_;
};

}  // namespace spook::detail
