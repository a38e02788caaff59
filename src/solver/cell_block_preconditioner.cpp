#include "src/solver/cell_block_preconditioner.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace panoptic {

CellBlockPreconditioner::CellBlockPreconditioner(const SparsityPattern& pattern,
                                                 int n_cells, int n_cell_vars)
    : n_cell_part_(static_cast<long>(n_cells) * n_cell_vars),
      cells_(cells_of(pattern, n_cells, n_cell_vars)) {
  for (long g = n_cell_part_; g < pattern.size(); ++g)
    global_diagonal_.push_back(pattern.position(g, g));  // the pattern holds it
  global_pivot_.assign(global_diagonal_.size(), 1.0);
}

BlockBandedLU CellBlockPreconditioner::cells_of(const SparsityPattern& pattern,
                                                int n_cells, int n_cell_vars) {
  try {
    return BlockBandedLU(pattern, n_cells, n_cell_vars, BlockBandedLU::CellBlocksOnly{});
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("CellBlockPreconditioner: ") + e.what());
  }
}

bool CellBlockPreconditioner::setup(std::span<const double> jacobian, double gamma) {
  if (!cells_.factorize_newton(jacobian, gamma)) return false;
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
