#include "src/solver/sparsity.hpp"

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <string>

#include "src/core/worker_threads.hpp"

namespace panoptic {

void PatternBuilder::compact() {
  const auto n = static_cast<std::size_t>(n_);
  std::vector<std::size_t> start(n + 1, 0);
  for (const auto& e : entries_) ++start[static_cast<std::size_t>(e.first) + 1];
  for (std::size_t c = 0; c < n; ++c) start[c + 1] += start[c];
  std::vector<long> rows(entries_.size());
  {
    std::vector<std::size_t> next(start.begin(), start.end() - 1);
    for (const auto& [col, row] : entries_)
      rows[next[static_cast<std::size_t>(col)]++] = row;
  }
  entries_.clear();
  for (std::size_t c = 0; c < n; ++c) {
    const auto first = rows.begin() + static_cast<std::ptrdiff_t>(start[c]);
    const auto last = rows.begin() + static_cast<std::ptrdiff_t>(start[c + 1]);
    std::sort(first, last);
    const auto end = std::unique(first, last);
    for (auto it = first; it != end; ++it)
      entries_.emplace_back(static_cast<long>(c), *it);
  }
  unique_ = entries_.size();
}

void PatternBuilder::throw_outside(long row, long col) const {
  throw std::logic_error("PatternBuilder: entry (" + std::to_string(row) + ", " +
                         std::to_string(col) + ") is outside the " + std::to_string(n_) +
                         " x " + std::to_string(n_) + " matrix");
}

SparsityPattern::SparsityPattern(PatternBuilder&& builder) : n_(builder.size()) {
  for (long i = 0; i < n_; ++i) builder.entries_.emplace_back(i, i);  // full diagonal
  builder.compact();
  col_ptr_.assign(n_ + 1, 0);
  row_index_.reserve(builder.entries_.size());
  for (const auto& [col, row] : builder.entries_) {  // in the matrix: add() checked
    ++col_ptr_[col + 1];
    row_index_.push_back(row);
  }
  for (long c = 0; c < n_; ++c) col_ptr_[c + 1] += col_ptr_[c];
  run_ptr_.assign(static_cast<std::size_t>(n_) + 1, 0);
  for (long c = 0; c < n_; ++c) {
    for (auto p = col_ptr_[c]; p < col_ptr_[c + 1]; ++p) {
      const auto row = row_index_[static_cast<std::size_t>(p)];
      if (p > col_ptr_[c] && row == row_index_[static_cast<std::size_t>(p) - 1] + 1)
        ++runs_.back().length;
      else
        runs_.push_back({row, 1});
    }
    run_ptr_[static_cast<std::size_t>(c) + 1] = runs_.size();
  }
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
  // Worker threads (src/core/worker_threads.hpp) take bands of rows: each goes through
  // every column in order and adds the part of its runs that falls in its band, so that
  // each y_r is summed over the same columns in the same order as on one thread.
  parallel_bands(static_cast<std::size_t>(n_), [&](std::size_t band_lo,
                                                   std::size_t band_hi) {
    const auto lo = static_cast<sunindextype>(band_lo),
               hi = static_cast<sunindextype>(band_hi);
    std::fill(y.begin() + lo, y.begin() + hi, 0.0);
    for (std::size_t c = 0; c < static_cast<std::size_t>(n_); ++c) {
      const double xc = x[c];
      const double* v = values.data() + col_ptr_[c];
      for (std::size_t r = run_ptr_[c]; r < run_ptr_[c + 1]; ++r) {
        const sunindextype first = runs_[r].first_row, length = runs_[r].length;
        const sunindextype from = std::max(first, lo), to = std::min(first + length, hi);
        for (sunindextype k = from; k < to; ++k) y[k] += v[k - first] * xc;
        v += length;
      }
    }
  });
}

std::vector<std::size_t> SparsityPattern::diagonal_positions() const {
  std::vector<std::size_t> diagonal(static_cast<std::size_t>(n_));
  for (long j = 0; j < n_; ++j) {
    const long k = position(j, j);
    if (k < 0)
      throw std::logic_error("SparsityPattern: the diagonal entry (" + std::to_string(j) +
                             ", " + std::to_string(j) +
                             ") is missing; the Newton matrix I - c J needs every one");
    diagonal[static_cast<std::size_t>(j)] = static_cast<std::size_t>(k);
  }
  return diagonal;
}

void newton_matrix(std::span<const double> jacobian,
                   std::span<const std::size_t> diagonal, double c,
                   std::span<double> out) {
  const double minus_c = -c;
  // element by element, in bands on the worker threads (src/core/worker_threads.hpp)
  parallel_bands(jacobian.size(), [&](std::size_t lo, std::size_t hi) {
    for (std::size_t k = lo; k < hi; ++k) out[k] = minus_c * jacobian[k];
  });
  // 1 + (-c J_jj) from the product just rounded into out: the same bits as from J, and
  // `out` may alias `jacobian`
  for (const std::size_t k : diagonal) out[k] = 1.0 + out[k];
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

void JacobianValues::add_dense_block(long first, int n, std::span<const double> block) {
  const auto rows = pattern_.row_index();
  const auto col_ptr = pattern_.col_ptr();
  const auto un = static_cast<std::size_t>(n);
  for (int c = 0; c < n; ++c) {
    const long col = first + c;
    const long p0 = pattern_.position(first, col);
    // rows are sorted and unique in a column: its n rows are there when the last is, in
    // the same column
    const long last = p0 + n - 1;
    const bool whole = p0 >= 0 && last < col_ptr[static_cast<std::size_t>(col) + 1] &&
                       rows[static_cast<std::size_t>(last)] == first + n - 1;
    for (int r = 0; r < n; ++r) {
      const double v =
          block[static_cast<std::size_t>(r) * un + static_cast<std::size_t>(c)];
      if (v == 0.0) continue;
      if (whole)
        values_[static_cast<std::size_t>(p0 + r)] += v;
      else
        add(first + r, col, v);
    }
  }
}

}  // namespace panoptic
