#pragma once
//! The preconditioner of solver.linear = "gmres": P = I - gamma J_cc, where J_cc keeps
//! of the Jacobian J only the dense diagonal block of each cell (its variables' couplings
//! among themselves: the coagulation of a cell's bins, its porosity moments and Sigma_g)
//! and, for the global variables (booked masses), their diagonal. Everything between
//! cells (transport) and between cells and globals is left to the Krylov iteration.
//! The cells' part is the block solver's matrix at bandwidth 0: a BlockBandedLU
//! (src/solver/block_banded_lu.hpp) of the cells' diagonal blocks of J's pattern, which
//! gathers each block from J, forms I - gamma J there and factorises it in place with
//! partial pivoting (Eigen::PartialPivLU); nothing is pivoted between cells, and none
//! need be: P's blocks are independent.
//! Storage: one b x b LU per cell (b variables per cell) and one pivot per global.
#include <span>
#include <vector>

#include "src/solver/block_banded_lu.hpp"
#include "src/solver/sparsity.hpp"

namespace panoptic {

class CellBlockPreconditioner {
 public:
  //! For `pattern` over n_cells cells of n_cell_vars variables each, then the globals
  //! (the layout of StateLayout). Throws std::invalid_argument when the cells do not fit.
  CellBlockPreconditioner(const SparsityPattern& pattern, int n_cells, int n_cell_vars);

  //! Forms and factorises P = I - gamma J_cc from the Jacobian `jacobian` (the
  //! pattern's order). false: a block has a zero or non-finite pivot (CVODE then retries
  //! with a fresh Jacobian or a smaller step).
  bool setup(std::span<const double> jacobian, double gamma);
  //! x <- P^-1 x with the factors of the last successful setup(). false: not finite.
  bool solve(std::span<double> x) const;

  //! Doubles held by the factors (the LU blocks): the preconditioner's memory.
  long stored_doubles() const;

 private:
  //! The cells' blocks of `pattern` as a BlockBandedLU; throws std::invalid_argument
  //! naming this class when they do not fit.
  static BlockBandedLU cells_of(const SparsityPattern& pattern, int n_cells,
                                int n_cell_vars);

  long n_cell_part_ = 0;
  BlockBandedLU cells_;                //!< its factors (bandwidth 0)
  std::vector<long> global_diagonal_;  //!< pattern position of each global's diagonal
  std::vector<double> global_pivot_;   //!< 1 - gamma J_gg of each global
};

}  // namespace panoptic
