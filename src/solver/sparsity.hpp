#pragma once
//! Sparsity pattern of the Jacobian: the union of the entries every module declares, plus
//! the full diagonal (CVODE forms I - gamma J in place and must not insert entries).
//! Built once in compressed-sparse-column form, with sunindextype indices for
//! SUNSparseMatrix.
#include <sundials/sundials_types.h>

#include <span>
#include <stdexcept>
#include <utility>
#include <vector>

namespace panoptic {

//! Collects the declared entries. A flat list, sorted and deduplicated once the
//! duplicates could outgrow what is kept, and at the end: a tree (std::set) of the 5.9
//! million entries of the porous DustPy disk took 70 % of its set-up's CPU and 430 MB of
//! its 1 GB peak memory (tests/bench/results/porous_cost.md, set-up section).
class PatternBuilder {
 public:
  explicit PatternBuilder(long n) : n_(n) {}
  //! Throws std::logic_error for an entry outside the n x n matrix (a programming error
  //! of the module that declares it).
  void add(long row, long col) {
    if (row < 0 || row >= n_ || col < 0 || col >= n_) throw_outside(row, col);
    entries_.emplace_back(col, row);
    if (entries_.size() >= 2 * unique_ + 1024) compact();
  }
  long size() const { return n_; }

 private:
  friend class SparsityPattern;
  //! Sorts column-major ((col, row) pairs) and drops repeated entries: a counting sort
  //! by column, then each column's rows (O(entries); a comparison sort of the whole list
  //! took most of the set-up left).
  void compact();
  [[noreturn]] void throw_outside(long row, long col) const;
  long n_;
  std::vector<std::pair<long, long>> entries_;  // (col, row)
  std::size_t unique_ = 0;  // entries_'s size after the last compact()
};

class SparsityPattern {
 public:
  SparsityPattern() = default;
  explicit SparsityPattern(PatternBuilder&& builder);
  explicit SparsityPattern(const PatternBuilder& builder)
      : SparsityPattern(PatternBuilder(builder)) {}

  long size() const { return n_; }
  long nnz() const { return static_cast<long>(row_index_.size()); }
  //! Position of (row, col) in the value array, or -1 when it is not in the pattern.
  long position(long row, long col) const;
  bool contains(long row, long col) const { return position(row, col) >= 0; }
  //! Writes the CSC index arrays (what CVODE zeroes in the matrix before each call).
  void copy_structure_to(sunindextype* colptrs, sunindextype* rowvals) const;
  std::span<const sunindextype> col_ptr() const { return col_ptr_; }
  std::span<const sunindextype> row_index() const { return row_index_; }
  //! y = A x for the matrix A whose values, in the pattern's order, are `values`. Column
  //! by column, each column's rows in order (the same sums as entry by entry), over runs
  //! of consecutive rows: a porous cell's 240 x 240 block is one run per column, so the
  //! product reads no row index per entry. GMRES forms two products per Newton iteration
  //! and they stream the whole Jacobian (95 MB of values and indices on the porous
  //! DustPy disk): the indices were half of that traffic. With worker threads
  //! (src/core/worker_threads.hpp) each takes a band of rows, with the same sums.
  void multiply(std::span<const double> values, std::span<const double> x,
                std::span<double> y) const;
  //! Where each column's diagonal entry sits in the value array, column by column (the
  //! identity of newton_matrix). Throws std::logic_error naming the first column whose
  //! diagonal is missing (the constructor inserts the whole diagonal: a miss is a
  //! programming error).
  std::vector<std::size_t> diagonal_positions() const;

 private:
  //! One run of consecutive rows in a column: its first row and its length.
  struct RowRun {
    sunindextype first_row, length;
  };
  long n_ = 0;
  std::vector<sunindextype> col_ptr_, row_index_;
  //! Column c's runs are runs_[run_ptr_[c]] .. runs_[run_ptr_[c + 1] - 1].
  std::vector<std::size_t> run_ptr_;
  std::vector<RowRun> runs_;
};

//! The Newton matrix M = I - c J of an implicit step (c = gamma = h beta_0 of CVODE's
//! BDF, dt of implicit Euler) from J's values in a pattern's order and the pattern's
//! diagonal_positions(): M_ij = (-c) J_ij, then M_jj = 1 + (-c) J_jj. `out` may be
//! `jacobian` itself.
void newton_matrix(std::span<const double> jacobian,
                   std::span<const std::size_t> diagonal, double c,
                   std::span<double> out);

//! The value array of a Jacobian in the pattern: modules add their dF/dy into it.
//! A Jacobian entry written outside the declared pattern (a programming error of the
//! module that wrote it; DiskModel names the module and the variables).
struct PatternMiss : std::logic_error {
  PatternMiss(long r, long c);
  long row, col;
};

class JacobianValues {
 public:
  JacobianValues(const SparsityPattern& pattern, std::span<double> values)
      : pattern_(pattern), values_(values) {}
  //! J(row, col) += v. The entry must have been declared; a miss is a programming error.
  void add(long row, long col, double v);
  //! J(first + r, first + c) += block[r n + c] for each non-zero entry of the dense,
  //! row-major n x n `block`: add() entry by entry, with one search per column instead of
  //! one per entry where the pattern holds the column's n rows (a coagulation cell's
  //! 240 x 240 block is 57 600 searches otherwise).
  void add_dense_block(long first, int n, std::span<const double> block);
  const SparsityPattern& pattern() const { return pattern_; }

 private:
  const SparsityPattern& pattern_;
  std::span<double> values_;
};

}  // namespace panoptic
