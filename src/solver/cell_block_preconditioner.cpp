#include "src/solver/cell_block_preconditioner.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "src/core/worker_threads.hpp"

namespace panoptic {
namespace {

// The pattern of the diagonal blocks of n_cells cells of b variables in `pattern`, and
// every diagonal entry of the cells' part; throws when the cells do not fit.
SparsityPattern cell_block_pattern(const SparsityPattern& pattern, int n_cells, int b) {
  const long n_cell_part = static_cast<long>(n_cells) * b;
  if (n_cells < 1 || b < 1 || n_cell_part > pattern.size())
    throw std::invalid_argument("CellBlockPreconditioner: " + std::to_string(n_cells) +
                                " cells of " + std::to_string(b) +
                                " variables do not fit a matrix of size " +
                                std::to_string(pattern.size()));
  // a filter of pattern's columns, which hold their diagonal (SparsityPattern's
  // constructor): no builder's list of entries
  const auto col_ptr = pattern.col_ptr();
  const auto rows = pattern.row_index();
  std::vector<sunindextype> block_col_ptr(static_cast<std::size_t>(n_cell_part) + 1, 0);
  for (long col = 0; col < n_cell_part; ++col) {
    const long first = col / b * b;
    sunindextype count = 0;
    for (auto p = col_ptr[col]; p < col_ptr[col + 1]; ++p)
      count += rows[p] >= first && rows[p] < first + b;
    block_col_ptr[static_cast<std::size_t>(col) + 1] =
        block_col_ptr[static_cast<std::size_t>(col)] + count;
  }
  std::vector<sunindextype> block_rows;
  block_rows.reserve(static_cast<std::size_t>(block_col_ptr.back()));
  for (long col = 0; col < n_cell_part; ++col) {
    const long first = col / b * b;
    for (auto p = col_ptr[col]; p < col_ptr[col + 1]; ++p)
      if (rows[p] >= first && rows[p] < first + b) block_rows.push_back(rows[p]);
  }
  return SparsityPattern(n_cell_part, std::move(block_col_ptr), std::move(block_rows));
}

}  // namespace

CellBlockPreconditioner::CellBlockPreconditioner(const SparsityPattern& pattern,
                                                 int n_cells, int n_cell_vars)
    : CellBlockPreconditioner(pattern, cell_block_pattern(pattern, n_cells, n_cell_vars),
                              n_cells, n_cell_vars) {}

CellBlockPreconditioner::CellBlockPreconditioner(const SparsityPattern& pattern,
                                                 const SparsityPattern& block_pattern,
                                                 int n_cells, int n_cell_vars)
    : n_cell_part_(static_cast<long>(n_cells) * n_cell_vars),
      cells_(block_pattern, n_cells, n_cell_vars) {
  const auto col_ptr = block_pattern.col_ptr();
  const auto rows = block_pattern.row_index();
  // every entry is one of pattern's: its cells' blocks and the diagonal it holds whole
  for (long col = 0; col < n_cell_part_; ++col)
    for (auto p = col_ptr[col]; p < col_ptr[col + 1]; ++p) {
      const auto from = static_cast<std::size_t>(pattern.position(rows[p], col));
      const auto to = static_cast<std::size_t>(p);
      if (!source_.empty()) {
        CopyRun& last = source_.back();
        if (last.from + last.length == from && last.to + last.length == to) {
          ++last.length;
          continue;
        }
      }
      source_.push_back({from, to, 1});
    }
  source_.shrink_to_fit();
  block_diagonal_ = block_pattern.diagonal_positions();
  block_values_.assign(static_cast<std::size_t>(block_pattern.nnz()), 0.0);
  for (long g = n_cell_part_; g < pattern.size(); ++g)
    global_diagonal_.push_back(pattern.position(g, g));  // the pattern holds it
  global_pivot_.assign(global_diagonal_.size(), 1.0);
}

bool CellBlockPreconditioner::setup(std::span<const double> jacobian, double gamma) {
  parallel_bands(source_.size(), [&](std::size_t lo, std::size_t hi) {
    for (std::size_t q = lo; q < hi; ++q)
      std::copy_n(jacobian.data() + source_[q].from, source_[q].length,
                  block_values_.data() + source_[q].to);
  });
  newton_matrix(block_values_, block_diagonal_, gamma, block_values_);
  if (!cells_.factorize(block_values_)) return false;
  for (std::size_t g = 0; g < global_diagonal_.size(); ++g) {
    global_pivot_[g] =
        1.0 - gamma * jacobian[static_cast<std::size_t>(global_diagonal_[g])];
    if (!std::isfinite(global_pivot_[g]) || global_pivot_[g] == 0.0) return false;
  }
  return true;
}

bool CellBlockPreconditioner::solve(std::span<double> x) const {
  const bool cells_finite = cells_.solve(x.first(static_cast<std::size_t>(n_cell_part_)));
  bool globals_finite = true;
  for (std::size_t g = 0; g < global_pivot_.size(); ++g) {
    double& xg = x[static_cast<std::size_t>(n_cell_part_) + g];
    xg /= global_pivot_[g];
    globals_finite = globals_finite && std::isfinite(xg);
  }
  return cells_finite && globals_finite;
}

long CellBlockPreconditioner::stored_doubles() const {
  return n_cell_part_ * cells_.block_size() + static_cast<long>(global_pivot_.size());
}

}  // namespace panoptic
