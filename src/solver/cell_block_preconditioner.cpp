#include "src/solver/cell_block_preconditioner.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace panoptic {

CellBlockPreconditioner::CellBlockPreconditioner(const SparsityPattern& pattern,
                                                 int n_cells, int n_cell_vars)
    : n_(n_cells), b_(n_cell_vars) {
  n_cell_part_ = static_cast<long>(n_) * b_;
  if (n_ < 1 || b_ < 1 || n_cell_part_ > pattern.size())
    throw std::invalid_argument("CellBlockPreconditioner: " + std::to_string(n_) +
                                " cells of " + std::to_string(b_) +
                                " variables do not fit a matrix of size " +
                                std::to_string(pattern.size()));
  const auto col_ptr = pattern.col_ptr();
  const auto rows = pattern.row_index();
  cell_begin_.push_back(0);
  for (int c = 0; c < n_; ++c) {
    const long first = static_cast<long>(c) * b_;
    for (long col = first; col < first + b_; ++col)
      for (auto p = col_ptr[col]; p < col_ptr[col + 1]; ++p)
        if (rows[p] >= first && rows[p] < first + b_) {
          source_.push_back(p);
          target_.push_back((col - first) * b_ + (rows[p] - first));
        }
    cell_begin_.push_back(static_cast<long>(source_.size()));
  }
  for (long g = n_cell_part_; g < pattern.size(); ++g)
    global_diagonal_.push_back(pattern.position(g, g));  // the pattern holds it
  lu_.resize(static_cast<std::size_t>(n_));
  global_pivot_.assign(global_diagonal_.size(), 1.0);
  block_.resize(b_, b_);
  scratch_.resize(b_);
}

bool CellBlockPreconditioner::setup(std::span<const double> jacobian, double gamma) {
  for (int c = 0; c < n_; ++c) {
    block_.setZero();
    double* m = block_.data();
    for (long k = cell_begin_[c]; k < cell_begin_[c + 1]; ++k)
      m[target_[k]] = -gamma * jacobian[static_cast<std::size_t>(source_[k])];
    block_.diagonal().array() += 1.0;
    lu_[c].compute(block_);
    const auto pivots = lu_[c].matrixLU().diagonal().cwiseAbs();
    if (!pivots.allFinite() || pivots.minCoeff() == 0.0) return false;
  }
  for (std::size_t g = 0; g < global_diagonal_.size(); ++g) {
    global_pivot_[g] =
        1.0 - gamma * jacobian[static_cast<std::size_t>(global_diagonal_[g])];
    if (!std::isfinite(global_pivot_[g]) || global_pivot_[g] == 0.0) return false;
  }
  return true;
}

bool CellBlockPreconditioner::solve(std::span<double> x) const {
  Eigen::Map<Eigen::VectorXd> v(x.data(), static_cast<Eigen::Index>(x.size()));
  for (int c = 0; c < n_; ++c) {
    auto xc = v.segment(static_cast<Eigen::Index>(c) * b_, b_);
    scratch_ = lu_[c].solve(xc);
    xc = scratch_;
  }
  for (std::size_t g = 0; g < global_pivot_.size(); ++g)
    x[static_cast<std::size_t>(n_cell_part_) + g] /= global_pivot_[g];
  return v.allFinite();
}

long CellBlockPreconditioner::stored_doubles() const {
  return static_cast<long>(n_) * b_ * b_ + static_cast<long>(global_pivot_.size());
}

}  // namespace panoptic
