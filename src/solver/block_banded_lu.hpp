#pragma once
//! A direct solver for the Newton matrix M = I - gamma J of a state laid out as
//! StateLayout lays it out: n_blocks cells of block_size variables each (a cell's
//! variables contiguous), then the global variables. Read from the pattern, not assumed:
//! a cell row couples only to the cells within `bandwidth` of its own (the face stencil:
//! 1 for first-order upwind and centred diffusion, 2 with the van Leer limiter), and no
//! cell row depends on a global, so that
//!     M = [ A  0 ]     A: block-banded, dense b x b blocks (a cell's coagulation block),
//!         [ C  G ]     C: the globals' couplings to cells, G: the globals' own block.
//! A is factorised by block Gaussian elimination without pivoting between blocks
//! (Golub & Van Loan 2013, §4.5.3, block tridiagonal; here any bandwidth: fill stays in
//! the band), with partial pivoting inside each diagonal block (Eigen::PartialPivLU,
//! blocked, matrix-matrix kernels). That needs non-singular pivot blocks, as M has for
//! the steps CVODE takes (I - gamma J, block-diagonally dominant for small gamma); a
//! singular or non-finite one is reported, and CVODE retries with a smaller step.
//! Then x_c = A^-1 b_c and x_g = G^-1 (b_g - C x_c).
//!
//! The off-diagonal blocks of the transport couple a bin to the same bin of the
//! neighbour (and to its porosity moment and Sigma_g): sparse. Their products in the
//! elimination run as sparse times dense when a block holds few non-zeros, else as a
//! dense product (fill, bandwidth > 1).
#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "src/solver/sparsity.hpp"

namespace panoptic {

//! BlockBandedLU's refusal of a pattern without its structure: what() is
//! "BlockBandedLU: " + reason, `reason` BlockBandedLU::refusal()'s text (for the callers'
//! messages, which name the scene key that chose the solver).
struct BlockStructureRefused : std::invalid_argument {
  explicit BlockStructureRefused(const std::string& why);
  std::string reason;
};

class BlockBandedLU {
 public:
  //! Why `pattern` has not the structure above for cells of `block_size` variables and
  //! `n_blocks` cells (a cell row that depends on a global, or sizes that do not fit);
  //! empty when it has.
  static std::string refusal(const SparsityPattern& pattern, int n_blocks,
                             int block_size);

  //! Throws BlockStructureRefused with refusal() when the pattern lacks the structure.
  BlockBandedLU(const SparsityPattern& pattern, int n_blocks, int block_size);
  //! The cells' diagonal blocks of `pattern` alone (bandwidth 0, no globals): every
  //! other entry of a matrix in that pattern is left out (the GMRES preconditioner's
  //! matrix, src/solver/cell_block_preconditioner.hpp). Throws std::invalid_argument
  //! when the cells do not fit the pattern.
  struct CellBlocksOnly {};
  BlockBandedLU(const SparsityPattern& pattern, int n_blocks, int block_size,
                CellBlocksOnly);
  // The pivot blocks' LUs refer to the blocks' storage (in place): a copy would refer
  // to the original's; a move keeps the storage.
  BlockBandedLU(const BlockBandedLU&) = delete;
  BlockBandedLU& operator=(const BlockBandedLU&) = delete;
  BlockBandedLU(BlockBandedLU&&) = default;
  BlockBandedLU& operator=(BlockBandedLU&&) = default;

  int n_blocks() const { return n_; }
  int block_size() const { return b_; }
  int n_globals() const { return n_g_; }
  //! The largest distance between the cells of a row and of a column that couple.
  int bandwidth() const { return w_; }

  //! Factorises the matrix whose values, in the pattern's order, are `values`. false: a
  //! pivot block (or G) has a zero or non-finite pivot; the factors are then unusable
  //! until the next successful call.
  bool factorize(std::span<const double> values);
  //! Factorises the Newton matrix I - c J of the Jacobian whose values, in the pattern's
  //! order, are `jacobian`: entry by entry as newton_matrix (sparsity.hpp) forms it, the
  //! same bits, without a copy of the values in between.
  bool factorize_newton(std::span<const double> jacobian, double c);
  //! x <- M^-1 x, with the factors of the last successful factorize(). false: the
  //! solution is not finite.
  bool solve(std::span<double> x) const;

 private:
  using Matrix = Eigen::MatrixXd;
  using Sparse = Eigen::SparseMatrix<double>;
  //! Block (i, j) of A, |i - j| <= w.
  Matrix& block(int i, int j) { return blocks_[slot(i, j)]; }
  const Matrix& block(int i, int j) const { return blocks_[slot(i, j)]; }
  std::size_t slot(int i, int j) const {
    return static_cast<std::size_t>(i) * (2 * w_ + 1) + (j - i + w_);
  }
  //! The band blocks, G and C (sized), the LUs' slots and the scratch vectors.
  void allocate(long n_coupling);
  //! Adds pattern entry p, which goes to `to`, to the destinations: merged into the
  //! last run where it continues it.
  void add_destination(std::size_t p, double* to);
  //! The matrix from `values` in the pattern's order (with `newton_c`, the Newton
  //! matrix: times -c, and 1 + on the diagonal), then its factors.
  bool fill_and_factorize(std::span<const double> values, std::optional<double> newton_c);
  //! LU of the pivot block k, in place.
  void factorize_pivot(int k);
  //! y -= block (i, j) x, the block's sparse copy when it has one (lower blocks).
  void subtract_lower_product(int i, int j, const Eigen::Ref<const Eigen::VectorXd>& x,
                              Eigen::Ref<Eigen::VectorXd> y) const;

  int n_ = 0, b_ = 0, w_ = 0, n_g_ = 0;
  long n_cell_part_ = 0;
  std::vector<Matrix>
      blocks_;  //!< band blocks; after factorize: D^-1 U above the diagonal
  //! The lower blocks (i, j), i > j, as sparse matrices when few of their entries are
  //! non-zero (used in the elimination and the forward solve), indexed by slot().
  std::vector<Sparse> lower_sparse_;
  std::vector<char> lower_is_sparse_;
  //! LU of each pivot block, in place in the block (none before the first factorize)
  std::vector<std::optional<Eigen::PartialPivLU<Eigen::Ref<Matrix>>>> pivots_;
  //! Where the pattern's entries go: each run of consecutive entries [from, from +
  //! length) to consecutive storage at `to`, in a band block (column-major), in G, or
  //! in C; one run per column of a dense block instead of a pointer per entry.
  struct CopyRun {
    double* to = nullptr;
    std::size_t from = 0, length = 0;
  };
  std::vector<CopyRun> destination_;
  //! C as triplets: the global row (0-based among the globals), the cell column, value.
  std::vector<int> c_row_;
  std::vector<long> c_col_;
  std::vector<double> c_value_;
  Matrix g_;
  Matrix scratch_block_;
  Eigen::PartialPivLU<Matrix> g_lu_;
  mutable Eigen::VectorXd scratch_;
  //! bandwidth 0: one solve vector per worker thread (src/core/worker_threads.hpp)
  mutable std::vector<Eigen::VectorXd> worker_scratch_;
};

}  // namespace panoptic
