#include "src/solver/sparsity.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace panoptic {

SparsityPattern::SparsityPattern(const PatternBuilder& builder) : n_(builder.size()) {
  std::set<std::pair<long, long>> entries = builder.entries_;
  for (long i = 0; i < n_; ++i) entries.emplace(i, i);  // full diagonal
  col_ptr_.assign(n_ + 1, 0);
  row_index_.reserve(entries.size());
  for (const auto& [col, row] : entries) {
    if (row < 0 || row >= n_ || col < 0 || col >= n_)
      throw std::logic_error("SparsityPattern: entry outside the matrix");
    ++col_ptr_[col + 1];
    row_index_.push_back(row);
  }
  for (long c = 0; c < n_; ++c) col_ptr_[c + 1] += col_ptr_[c];
}

long SparsityPattern::position(long row, long col) const {
  if (col < 0 || col >= n_) return -1;
  const auto first = row_index_.begin() + col_ptr_[col];
  const auto last = row_index_.begin() + col_ptr_[col + 1];
  const auto it = std::lower_bound(first, last, row);
  return (it != last && *it == row) ? static_cast<long>(it - row_index_.begin()) : -1;
}

void SparsityPattern::copy_structure_to(sunindextype* colptrs,
                                        sunindextype* rowvals) const {
  std::copy(col_ptr_.begin(), col_ptr_.end(), colptrs);
  std::copy(row_index_.begin(), row_index_.end(), rowvals);
}

void SparsityPattern::multiply(std::span<const double> values, std::span<const double> x,
                               std::span<double> y) const {
  std::fill(y.begin(), y.end(), 0.0);
  for (long c = 0; c < n_; ++c) {
    const double xc = x[static_cast<std::size_t>(c)];
    for (auto p = col_ptr_[c]; p < col_ptr_[c + 1]; ++p)
      y[static_cast<std::size_t>(row_index_[p])] +=
          values[static_cast<std::size_t>(p)] * xc;
  }
}

PatternMiss::PatternMiss(long r, long c)
    : std::logic_error("Jacobian entry (" + std::to_string(r) + ", " + std::to_string(c) +
                       ") is outside the declared pattern"),
      row(r),
      col(c) {}

void JacobianValues::add(long row, long col, double v) {
  const long p = pattern_.position(row, col);
  if (p < 0) throw PatternMiss(row, col);
  values_[p] += v;
}

}  // namespace panoptic
