// The Jacobian's pattern (src/solver/sparsity.hpp): where its diagonal sits, and the
// Newton matrix I - c J that both integrators and the GMRES preconditioner factorise,
// against the same matrix written out by hand.
#include <gtest/gtest.h>

#include <cstddef>
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

}  // namespace
}  // namespace panoptic
