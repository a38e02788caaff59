// The Jacobian's pattern (src/solver/sparsity.hpp): built from repeated, unordered
// entries; where its diagonal sits; its product with a vector; dense blocks added as
// entry by entry; and the Newton matrix I - c J that both integrators and the GMRES
// preconditioner factorise, against the same matrix written out by hand.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <random>
#include <set>
#include <stdexcept>
#include <utility>
#include <vector>

#include "src/solver/sparsity.hpp"

namespace panoptic {
namespace {

// A 4 x 4 pattern of 9 entries, column-major (col, row):
//   col 0: (0, 0) (2, 0)   col 1: (0, 1) (1, 1)   col 2: (2, 2) (3, 2)
//   col 3: (0, 3) (1, 3) (3, 3)
SparsityPattern four_by_four() {
  PatternBuilder builder(4);
  builder.add(2, 0);
  builder.add(0, 1);
  builder.add(3, 2);
  builder.add(0, 3);
  builder.add(1, 3);
  return SparsityPattern(builder);  // adds the diagonal
}

TEST(Sparsity, DiagonalPositionsAreWhereEachColumnHoldsItsDiagonal) {
  const SparsityPattern pattern = four_by_four();
  ASSERT_EQ(pattern.nnz(), 9);
  const std::vector<std::size_t> diagonal = pattern.diagonal_positions();
  EXPECT_EQ(diagonal, (std::vector<std::size_t>{0, 3, 4, 8}));
  for (long j = 0; j < 4; ++j)
    EXPECT_EQ(static_cast<long>(diagonal[static_cast<std::size_t>(j)]),
              pattern.position(j, j));
  EXPECT_TRUE(SparsityPattern().diagonal_positions().empty());
}

TEST(Sparsity, NewtonMatrixIsIdentityMinusCTimesJ) {
  const SparsityPattern pattern = four_by_four();
  const std::vector<double> jacobian{-2.0, 0.5, 0.25, -3.0, -1.5, 7.0, 0.125, 1.0, -0.75};
  const double c = 0.3;
  // by hand, in the pattern's order: 1 - c J on the diagonal, -c J elsewhere
  const std::vector<double> expected{1.0 - c * -2.0, -c * 0.5,       -c * 0.25,
                                     1.0 - c * -3.0, 1.0 - c * -1.5, -c * 7.0,
                                     -c * 0.125,     -c * 1.0,       1.0 - c * -0.75};
  std::vector<double> m(jacobian.size(), 99.0);
  newton_matrix(jacobian, pattern.diagonal_positions(), c, m);
  for (std::size_t k = 0; k < m.size(); ++k) EXPECT_EQ(m[k], expected[k]) << k;

  // in place: out may be the Jacobian's own values
  std::vector<double> in_place = jacobian;
  newton_matrix(in_place, pattern.diagonal_positions(), c, in_place);
  EXPECT_EQ(in_place, m);

  // the matrix acts as I - c J: M x = x - c J x
  const std::vector<double> x{1.0, -2.0, 0.5, 4.0};
  std::vector<double> mx(4), jx(4);
  pattern.multiply(m, x, mx);
  pattern.multiply(jacobian, x, jx);
  for (std::size_t i = 0; i < 4; ++i) EXPECT_DOUBLE_EQ(mx[i], x[i] - c * jx[i]) << i;
}

TEST(Sparsity, RepeatedAndUnorderedEntriesGiveTheSortedUniquePattern) {
  // enough repeats to compact the builder's list many times over
  const long n = 60;
  std::mt19937 rng(7);
  std::uniform_int_distribution<long> index(0, n - 1);
  PatternBuilder builder(n);
  std::set<std::pair<long, long>> reference;  // (col, row)
  for (int k = 0; k < 20000; ++k) {
    const long row = index(rng), col = index(rng) / 4;  // columns 0-14 only: repeats
    builder.add(row, col);
    reference.emplace(col, row);
  }
  for (long i = 0; i < n; ++i) reference.emplace(i, i);
  EXPECT_THROW(builder.add(n, 0), std::logic_error);
  EXPECT_THROW(builder.add(0, -1), std::logic_error);
  const SparsityPattern pattern(builder);
  ASSERT_EQ(pattern.nnz(), static_cast<long>(reference.size()));
  std::vector<long> col_count(n + 1, 0);
  long p = 0;
  for (const auto& [col, row] : reference) {
    EXPECT_EQ(pattern.row_index()[static_cast<std::size_t>(p)], row) << p;
    EXPECT_EQ(pattern.position(row, col), p);
    ++col_count[static_cast<std::size_t>(col) + 1];
    ++p;
  }
  for (long c = 0; c < n; ++c) {
    col_count[static_cast<std::size_t>(c) + 1] += col_count[static_cast<std::size_t>(c)];
    EXPECT_EQ(pattern.col_ptr()[static_cast<std::size_t>(c) + 1],
              col_count[static_cast<std::size_t>(c) + 1]);
  }
}

TEST(Sparsity, ProductByRunsOfRowsIsTheEntryByEntrySumToTheBit) {
  // dense 5 x 5 cell blocks (one run of rows per column), transport-like couplings to
  // the neighbouring cells' same rows, and random entries that break runs anywhere
  const long cell = 5, n_cells = 6, n = cell * n_cells;
  std::mt19937 rng(11);
  std::uniform_int_distribution<long> index(0, n - 1);
  PatternBuilder builder(n);
  for (long b = 0; b < n_cells; ++b)
    for (long r = 0; r < cell; ++r)
      for (long c = 0; c < cell; ++c) {
        builder.add(b * cell + r, b * cell + c);
        if (b > 0) builder.add((b - 1) * cell + r, b * cell + r);
      }
  for (int k = 0; k < 80; ++k) builder.add(index(rng), index(rng));
  const SparsityPattern pattern(builder);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::vector<double> values(static_cast<std::size_t>(pattern.nnz()));
  for (double& v : values) v = value(rng) * std::exp(30.0 * value(rng));
  std::vector<double> x(static_cast<std::size_t>(n));
  for (double& v : x) v = value(rng) * std::exp(30.0 * value(rng));
  // entry by entry: column after column, each column's rows in order
  std::vector<double> expected(static_cast<std::size_t>(n), 0.0);
  for (long c = 0; c < n; ++c)
    for (auto p = pattern.col_ptr()[static_cast<std::size_t>(c)];
         p < pattern.col_ptr()[static_cast<std::size_t>(c) + 1]; ++p)
      expected[static_cast<std::size_t>(
          pattern.row_index()[static_cast<std::size_t>(p)])] +=
          values[static_cast<std::size_t>(p)] * x[static_cast<std::size_t>(c)];
  std::vector<double> y(static_cast<std::size_t>(n), 99.0);
  pattern.multiply(values, x, y);
  for (std::size_t i = 0; i < y.size(); ++i) EXPECT_EQ(y[i], expected[i]) << i;
}

TEST(Sparsity, DenseBlockAddsWhatAddGivesEntryByEntry) {
  // two 3 x 3 blocks on the diagonal of a 7 x 7 matrix: the first whole, the second
  // without (5, 4); an off-block entry (6, 1) in the first block's column
  PatternBuilder builder(7);
  for (long r = 0; r < 3; ++r)
    for (long c = 0; c < 3; ++c) builder.add(r, c);
  for (long r = 3; r < 6; ++r)
    for (long c = 3; c < 6; ++c)
      if (!(r == 5 && c == 4)) builder.add(r, c);
  builder.add(6, 1);
  const SparsityPattern pattern(builder);
  const std::vector<double> block{1.5, 0.0, -2.0, 4.0, 0.25, 8.0, -1.0, 3.0, 0.5};
  std::vector<double> by_entry(static_cast<std::size_t>(pattern.nnz()), 1.0);
  std::vector<double> by_block = by_entry;
  JacobianValues entry(pattern, by_entry), whole(pattern, by_block);
  for (long r = 0; r < 3; ++r)
    for (long c = 0; c < 3; ++c)
      if (block[static_cast<std::size_t>(r * 3 + c)] != 0.0)
        entry.add(r, c, block[static_cast<std::size_t>(r * 3 + c)]);
  whole.add_dense_block(0, 3, block);
  EXPECT_EQ(by_block, by_entry);

  // the second block: its hole is skipped when the block holds 0 there, a miss otherwise
  std::vector<double> holed = block;
  holed[2 * 3 + 1] = 0.0;  // (5, 4)
  for (long r = 0; r < 3; ++r)
    for (long c = 0; c < 3; ++c)
      if (holed[static_cast<std::size_t>(r * 3 + c)] != 0.0)
        entry.add(3 + r, 3 + c, holed[static_cast<std::size_t>(r * 3 + c)]);
  whole.add_dense_block(3, 3, holed);
  EXPECT_EQ(by_block, by_entry);
  EXPECT_THROW(whole.add_dense_block(3, 3, block), PatternMiss);
}

TEST(Sparsity, DenseBlockDoesNotReadTheNextColumnsRowsAsItsOwn) {
  // column 1 lacks (2, 1), and column 2 holds only its diagonal (2, 2): the position
  // n - 1 entries after (0, 1) is column 2's row 2, the row the block's last would have
  PatternBuilder builder(3);
  builder.add(1, 0);
  builder.add(2, 0);
  builder.add(0, 1);
  const SparsityPattern pattern(builder);
  ASSERT_EQ(pattern.nnz(), 6);
  std::vector<double> values(6, 0.0);
  JacobianValues jac(pattern, values);
  const std::vector<double> block{1.0, 2.0, 0.0, 3.0, 4.0,
                                  0.0, 5.0, 7.0, 6.0};  // (2,1)=7
  EXPECT_THROW(jac.add_dense_block(0, 3, block), PatternMiss);
  // without (2, 1): column 1 gets (0, 1) and (1, 1), column 2 only its diagonal
  std::vector<double> fitting = block;
  fitting[2 * 3 + 1] = 0.0;
  std::fill(values.begin(), values.end(), 0.0);
  jac.add_dense_block(0, 3, fitting);
  EXPECT_EQ(values, (std::vector<double>{1.0, 3.0, 5.0, 2.0, 4.0, 6.0}));
}

}  // namespace
}  // namespace panoptic
