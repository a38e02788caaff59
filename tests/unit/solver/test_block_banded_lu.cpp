// The block-banded direct solver (src/solver/block_banded_lu.hpp) against a dense LU of
// the same matrix on random block-banded systems with global rows (bandwidth 1 and 2,
// sparse and dense off-diagonal blocks, pivoting inside the blocks), the structure it
// refuses, and a size-distribution run with it against the same run with KLU.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "src/core/error.hpp"
#include "src/core/units.hpp"
#include "src/model/simulation.hpp"
#include "src/run/restart.hpp"
#include "src/scene/config.hpp"
#include "src/solver/block_banded_lu.hpp"
#include "src/solver/cvode_integrator.hpp"
#include "src/solver/disk_model.hpp"
#include "tests/unit/support/config_error.hpp"
#include "tests/unit/support/jacobian_check.hpp"

namespace panoptic {
namespace {

//! A random system of n_blocks cells of b variables, coupled within bandwidth w, and
//! n_globals global rows that read some cells (never the other way round).
struct RandomSystem {
  SparsityPattern pattern;
  std::vector<double> values;
  Eigen::MatrixXd dense;
};

//! Off-diagonal blocks `sparse_offdiag`: the transport's shape, a bin to the same bin and
//! a column of the first variable (Sigma_g); else dense. Each pivot block is a permuted
//! scaled identity plus noise, so that its LU must pivot; the off-diagonal entries are
//! small enough for the block elimination without pivoting between blocks.
RandomSystem random_system(int n_blocks, int b, int w, int n_globals, bool sparse_offdiag,
                           unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const long n_cell_part = static_cast<long>(n_blocks) * b, n = n_cell_part + n_globals;
  PatternBuilder builder(n);
  for (int i = 0; i < n_blocks; ++i)
    for (int j = std::max(0, i - w); j <= std::min(n_blocks - 1, i + w); ++j)
      for (int r = 0; r < b; ++r)
        for (int c = 0; c < b; ++c)
          if (i == j || !sparse_offdiag || r == c || c == 0)
            builder.add(static_cast<long>(i) * b + r, static_cast<long>(j) * b + c);
  for (int g = 0; g < n_globals; ++g) {
    for (long c = g; c < n_cell_part; c += 3) builder.add(n_cell_part + g, c);
    for (int h = 0; h < n_globals; ++h) builder.add(n_cell_part + g, n_cell_part + h);
  }
  RandomSystem s{SparsityPattern(builder), {}, Eigen::MatrixXd::Zero(n, n)};
  std::vector<int> perm(static_cast<std::size_t>(b));
  for (int r = 0; r < b; ++r) perm[r] = (r * 7 + 1) % b;  // b not a multiple of 7
  const auto col_ptr = s.pattern.col_ptr();
  const auto rows = s.pattern.row_index();
  s.values.resize(static_cast<std::size_t>(s.pattern.nnz()));
  for (long c = 0; c < n; ++c)
    for (auto p = col_ptr[c]; p < col_ptr[c + 1]; ++p) {
      const long r = rows[p];
      double v = u(rng);
      const bool cell_block = r < n_cell_part && r / b == c / b;
      if (cell_block)
        v += r % b == perm[c % b] ? 8.0 * b : 0.0;
      else if (r < n_cell_part)
        v *= 0.3;
      if (r >= n_cell_part && r == c) v += 10.0;
      s.values[p] = v;
      s.dense(r, c) = v;
    }
  return s;
}

double relative_error(const Eigen::VectorXd& x, const Eigen::VectorXd& ref) {
  return (x - ref).cwiseAbs().maxCoeff() / ref.cwiseAbs().maxCoeff();
}

void expect_solves_like_dense(int w, bool sparse_offdiag, int n_globals) {
  const int n_blocks = 7, b = 8;
  for (unsigned seed : {1u, 2u}) {
    const RandomSystem s = random_system(n_blocks, b, w, n_globals, sparse_offdiag, seed);
    BlockBandedLU lu(s.pattern, n_blocks, b);
    EXPECT_EQ(lu.bandwidth(), w);
    EXPECT_EQ(lu.n_globals(), n_globals);
    ASSERT_TRUE(lu.factorize(s.values));
    const Eigen::PartialPivLU<Eigen::MatrixXd> dense_lu(s.dense);
    std::mt19937 rng(seed + 10);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int rhs = 0; rhs < 3; ++rhs) {
      Eigen::VectorXd bvec(s.dense.rows());
      for (auto& v : bvec) v = u(rng);
      const Eigen::VectorXd ref = dense_lu.solve(bvec);
      std::vector<double> x(bvec.begin(), bvec.end());
      ASSERT_TRUE(lu.solve(x));
      const double err =
          relative_error(Eigen::Map<Eigen::VectorXd>(x.data(), x.size()), ref);
      EXPECT_LT(err, 1e-12) << "w " << w << ", seed " << seed << ", rhs " << rhs;
      // and the residual of the dense matrix
      const Eigen::VectorXd res =
          s.dense * Eigen::Map<Eigen::VectorXd>(x.data(), x.size()) - bvec;
      EXPECT_LT(res.cwiseAbs().maxCoeff(), 1e-12 * bvec.cwiseAbs().maxCoeff());
    }
  }
}

TEST(BlockBandedLU, TridiagonalSparseCouplingsWithGlobalsMatchDenseSolve) {
  expect_solves_like_dense(1, true, 3);
}
TEST(BlockBandedLU, TridiagonalDenseCouplingsMatchDenseSolve) {
  expect_solves_like_dense(1, false, 0);
}
TEST(BlockBandedLU, BandwidthTwoWithGlobalsMatchesDenseSolve) {
  expect_solves_like_dense(2, true, 2);
  expect_solves_like_dense(2, false, 1);
}

// Bandwidth 0 (the GMRES preconditioner's cells): each pivot block is factorised in
// place, in the block's own storage, and gives the bits of Eigen's LU of a copy; a
// moved solver keeps its factors (they refer to the blocks' storage, which moves along).
TEST(BlockBandedLU, IndependentBlocksInPlaceGiveTheBitsOfEigensLuAndSurviveAMove) {
  const int n_blocks = 5, b = 9;
  const RandomSystem s = random_system(n_blocks, b, 0, 0, false, 5);
  BlockBandedLU lu(s.pattern, n_blocks, b);
  ASSERT_EQ(lu.bandwidth(), 0);
  ASSERT_TRUE(lu.factorize(s.values));
  BlockBandedLU moved(std::move(lu));
  const Eigen::VectorXd rhs = Eigen::VectorXd::LinSpaced(n_blocks * b, -1.0, 2.0);
  std::vector<double> x(rhs.begin(), rhs.end());
  ASSERT_TRUE(moved.solve(x));
  for (int k = 0; k < n_blocks; ++k) {
    const Eigen::MatrixXd block = s.dense.block(k * b, k * b, b, b);
    const Eigen::VectorXd ref = block.partialPivLu().solve(rhs.segment(k * b, b));
    for (int r = 0; r < b; ++r) EXPECT_EQ(x[k * b + r], ref(r)) << "cell " << k;
  }
}

// The Newton matrix I - c J formed while the values are gathered gives the bits of
// newton_matrix's matrix factorised; with the cells' blocks alone (the GMRES
// preconditioner's), every entry outside them is left out.
TEST(BlockBandedLU, NewtonMatrixFromTheJacobianGivesTheBitsOfNewtonMatrixFactorised) {
  const int n_blocks = 6, b = 7;
  const double c = 0.3;
  const RandomSystem s = random_system(n_blocks, b, 1, 2, true, 9);
  std::vector<double> m(s.values.size());
  newton_matrix(s.values, s.pattern.diagonal_positions(), c, m);
  BlockBandedLU from_j(s.pattern, n_blocks, b), from_m(s.pattern, n_blocks, b);
  ASSERT_TRUE(from_j.factorize_newton(s.values, c));
  ASSERT_TRUE(from_m.factorize(m));
  const Eigen::VectorXd rhs = Eigen::VectorXd::LinSpaced(s.dense.rows(), -1.0, 2.0);
  std::vector<double> x1(rhs.begin(), rhs.end()), x2 = x1;
  ASSERT_TRUE(from_j.solve(x1));
  ASSERT_TRUE(from_m.solve(x2));
  EXPECT_EQ(x1, x2);

  BlockBandedLU cells(s.pattern, n_blocks, b, BlockBandedLU::CellBlocksOnly{});
  EXPECT_EQ(cells.bandwidth(), 0);
  EXPECT_EQ(cells.n_globals(), 0);
  ASSERT_TRUE(cells.factorize_newton(s.values, c));
  std::vector<double> x(rhs.data(), rhs.data() + n_blocks * b);
  ASSERT_TRUE(cells.solve(x));
  for (int k = 0; k < n_blocks; ++k) {
    Eigen::MatrixXd block = (-c) * s.dense.block(k * b, k * b, b, b);
    for (int d = 0; d < b; ++d) block(d, d) = 1.0 + block(d, d);
    const Eigen::VectorXd ref = block.partialPivLu().solve(rhs.segment(k * b, b));
    for (int r = 0; r < b; ++r) EXPECT_EQ(x[k * b + r], ref(r)) << "cell " << k;
  }
  EXPECT_THROW(BlockBandedLU(s.pattern, n_blocks + 2, b, BlockBandedLU::CellBlocksOnly{}),
               std::invalid_argument);
}

// A second factorisation of other values in the same pattern starts from zero blocks:
// the fill of the first leaves nothing behind.
TEST(BlockBandedLU, RefactorisationOfNewValues) {
  const RandomSystem a = random_system(5, 6, 2, 2, true, 3);
  const RandomSystem b = random_system(5, 6, 2, 2, true, 4);
  BlockBandedLU lu(a.pattern, 5, 6);
  ASSERT_TRUE(lu.factorize(a.values));
  ASSERT_TRUE(lu.factorize(b.values));
  Eigen::VectorXd rhs = Eigen::VectorXd::LinSpaced(b.dense.rows(), -1.0, 2.0);
  std::vector<double> x(rhs.begin(), rhs.end());
  ASSERT_TRUE(lu.solve(x));
  EXPECT_LT(relative_error(Eigen::Map<Eigen::VectorXd>(x.data(), x.size()),
                           b.dense.partialPivLu().solve(rhs)),
            1e-12);
}

// A singular pivot block (a column of the first cell's block zero) and a
// non-finite entry are reported, not turned into a solution.
TEST(BlockBandedLU, SingularOrNonFinitePivotBlockFails) {
  RandomSystem s = random_system(4, 5, 1, 1, true, 5);
  BlockBandedLU lu(s.pattern, 4, 5);
  std::vector<double> values = s.values;
  const auto col_ptr = s.pattern.col_ptr();
  const auto rows = s.pattern.row_index();
  const long col = 1;  // cell 0 (the first pivot block is its own), variable 1
  for (auto p = col_ptr[col]; p < col_ptr[col + 1]; ++p)
    if (rows[p] / 5 == 0) values[p] = 0.0;
  EXPECT_FALSE(lu.factorize(values));
  values = s.values;
  values[static_cast<std::size_t>(col_ptr[7])] = std::nan("");
  EXPECT_FALSE(lu.factorize(values));
  EXPECT_TRUE(lu.factorize(s.values));
}

// A cell row that reads a global (no such module exists today) breaks the lower block
// triangular form: refused with the row and the global named.
TEST(BlockBandedLU, RefusesCellRowsThatReadGlobals) {
  PatternBuilder builder(3 * 2 + 1);
  for (long i = 0; i < 7; ++i) builder.add(i, i);
  builder.add(3, 6);  // cell 1, variable 1 reads global 0
  const SparsityPattern pattern(builder);
  const std::string why = BlockBandedLU::refusal(pattern, 3, 2);
  EXPECT_NE(why.find("variable 1 of cell 1 depends on global variable 0"),
            std::string::npos)
      << why;
  try {
    BlockBandedLU lu(pattern, 3, 2);
    ADD_FAILURE() << "expected a refusal";
  } catch (const BlockStructureRefused& e) {
    EXPECT_EQ(e.reason, why);
    EXPECT_EQ(std::string(e.what()), "BlockBandedLU: " + why);
  }
  EXPECT_THROW(BlockBandedLU(pattern, 3, 2), std::invalid_argument);
  EXPECT_EQ(BlockBandedLU::refusal(pattern, 7, 1), "");  // 7 cells of 1: no global
  EXPECT_NE(BlockBandedLU::refusal(pattern, 4, 2), "");  // 8 > 7 variables
}

//! A model of two cells and one global whose cell equations read the global.
class ReadsGlobal : public PhysicsModule {
 public:
  explicit ReadsGlobal(StateLayout& layout) : layout_(layout) {
    layout.add_cell_var({"y", "", "", 1.0, true});
    layout.add_global_var({"g", "", "", 1.0, true});
  }
  std::string_view name() const override { return "reads_global"; }
  void declare_pattern(PatternBuilder& p) const override {
    for (int c = 0; c < layout_.n_cells(); ++c)
      p.add(layout_.index(c, 0), layout_.global_index(0));
  }

  void add_rhs(double, std::span<const double>, std::span<double>) const override {}
  void add_jacobian(double, std::span<const double>, JacobianValues&) const override {}

 private:
  const StateLayout& layout_;
};

TEST(BlockBandedLU, IntegratorRefusesAPatternWithoutTheBlockStructure) {
  auto layout = std::make_shared<StateLayout>(2);
  std::vector<std::unique_ptr<PhysicsModule>> mods;
  mods.push_back(std::make_unique<ReadsGlobal>(*layout));
  layout->freeze();
  DiskModel model(layout, std::move(mods));
  IntegratorOptions opt;
  opt.atol = {1e-10, 1e-10, 1e-10};
  opt.linear = LinearSolverKind::block;
  const std::vector<double> y0{1.0, 1.0, 1.0};
  try {
    CvodeIntegrator cvode(model, 0.0, y0, opt);
    ADD_FAILURE() << "expected a refusal";
  } catch (const SolverError& e) {
    const std::string msg = e.what();
    for (const char* part : {"solver.linear = \"block\"", "depends on global variable 0",
                             "use solver.linear = \"klu\""})
      EXPECT_NE(msg.find(part), std::string::npos) << msg;
  }
  opt.linear = LinearSolverKind::klu;
  EXPECT_NO_THROW(CvodeIntegrator(model, 0.0, y0, opt));
}

//! Integrates the small distribution scene to t_yr with KLU and with the block solver
//! and compares the states in CVODE's weighted norm: |y_block - y_klu| / (rtol |y_klu| +
//! atol), the largest over the components. From the initial state, or (`filled`) from
//! one with every bin filled (testing::perturbed_state).
void expect_block_run_matches_klu(const std::vector<std::string>& sets, double t_yr,
                                  bool filled, int bandwidth, const char* label) {
  Simulation sim(load_scene(
      std::string(PANOPTIC_SOURCE_DIR) + "/params/tests/distribution_small.toml", sets));
  IntegratorOptions opt = sim.integrator_options();
  opt.linear = LinearSolverKind::klu;
  const double t_end = t_yr * units::kYr;
  const std::vector<double> y0 =
      filled ? testing::perturbed_state(sim, 1) : sim.initial_state();
  CvodeIntegrator klu(sim.model(), 0.0, y0, opt);
  klu.advance_to(t_end);
  opt.linear = LinearSolverKind::block;
  CvodeIntegrator block(sim.model(), 0.0, y0, opt);
  ASSERT_NE(block.block_solver(), nullptr);
  EXPECT_EQ(block.block_solver()->bandwidth(), bandwidth);
  EXPECT_EQ(block.block_solver()->block_size(), sim.model().layout().n_cell_vars());
  block.advance_to(t_end);
  double worst = 0.0;
  for (std::size_t i = 0; i < opt.atol.size(); ++i) {
    if (!sim.model().layout().info_of(static_cast<long>(i)).error_test) continue;
    const double d = std::abs(block.state()[i] - klu.state()[i]);
    worst = std::max(worst, d / (opt.rtol * std::abs(klu.state()[i]) + opt.atol[i]));
  }
  const SolverStats a = klu.stats(), b = block.stats();
  std::printf(
      "%s: largest weighted difference %.3g (rtol %.0e); steps %ld / %ld, RHS %ld / "
      "%ld, set-ups %ld / %ld, conv. fails %ld / %ld (KLU / block)\n",
      label, worst, opt.rtol, a.nst, b.nst, a.nfe, b.nfe, a.nsetups, b.nsetups, a.nncf,
      b.nncf);
  EXPECT_LT(worst, 1e-2) << label;
  EXPECT_LT(std::abs(static_cast<double>(b.nst - a.nst)),
            0.1 * static_cast<double>(a.nst))
      << label;
}

TEST(BlockBandedSolver, DistributionRunMatchesKlu) {
  expect_block_run_matches_klu({}, 3000.0, false, 1, "distribution, evolving gas");
}

TEST(BlockBandedSolver, DistributionRunMatchesKluVanLeer) {
  expect_block_run_matches_klu({"transport.advection=\"van_leer\"", "gas.evolve=false"},
                               300.0, true, 2, "distribution, van Leer, static gas");
}

// solver.linear: auto by default, an unknown solver refused naming the choices; a
// restart may change it (a numerical choice, as solver.rtol).
TEST(BlockBandedSolver, SolverLinearKey) {
  const std::string small =
      std::string(PANOPTIC_SOURCE_DIR) + "/params/tests/distribution_small.toml";
  EXPECT_EQ(load_scene(small, {}).str("solver.linear"), "auto");
  EXPECT_EQ(load_scene(small, std::vector<std::string>{"solver.linear=\"block\""})
                .str("solver.linear"),
            "block");
  const std::string m = config_error_message(
      [&] { load_scene(small, std::vector<std::string>{"solver.linear=\"lu\""}); },
      "solver.linear = lu");
  EXPECT_NE(m.find("solver.linear"), std::string::npos) << m;
  EXPECT_NE(m.find("klu, block"), std::string::npos) << m;
  EXPECT_TRUE(may_change_on_restart("solver.linear"));
}

// solver.linear = "auto": GMRES for a size distribution, porous or compact, KLU for the
// single size; a choice given by name is kept.
TEST(BlockBandedSolver, AutoPicksGmresForDistributionsKluForTheSingleSize) {
  const std::string dir = std::string(PANOPTIC_SOURCE_DIR) + "/params/";
  const auto solver = [&](const std::string& scene, std::vector<std::string> sets) {
    return Simulation(load_scene(dir + scene, sets)).linear_solver();
  };
  EXPECT_EQ(solver("tests/distribution_small.toml", {}), LinearSolverKind::gmres);
  EXPECT_EQ(solver("tests/distribution_small.toml", {"porosity.enabled=true"}),
            LinearSolverKind::gmres);
  EXPECT_EQ(solver("tests/distribution_small.toml",
                   {"porosity.enabled=true", "solver.linear=\"block\""}),
            LinearSolverKind::block);
  EXPECT_EQ(solver("fiducial.toml", {}), LinearSolverKind::klu);
  EXPECT_EQ(solver("tests/distribution_small.toml", {"solver.linear=\"klu\""}),
            LinearSolverKind::klu);
  EXPECT_EQ(solver("fiducial.toml", {"solver.linear=\"block\""}),
            LinearSolverKind::block);
  EXPECT_EQ(solver("tests/distribution_small.toml", {"solver.linear=\"gmres\""}),
            LinearSolverKind::gmres);
  EXPECT_STREQ(linear_solver_name(LinearSolverKind::block), "block");
  EXPECT_STREQ(linear_solver_name(LinearSolverKind::klu), "klu");
  EXPECT_STREQ(linear_solver_name(LinearSolverKind::gmres), "gmres");
}

}  // namespace
}  // namespace panoptic
