// GMRES with the per-cell block preconditioner (solver.linear = "gmres";
// src/solver/cell_block_preconditioner.hpp): the preconditioner against a dense inverse
// of the same blocks; a Newton system (I - gamma J) x = b of the small size-distribution
// scene solved by SPGMR (products with the assembled J, right preconditioning, as the
// integrator sets it up) against KLU's solution of the same matrix, and by SPGMR's
// iteration as the integrator runs it (src/solver/conservative_gmres.hpp) against
// SPGMR's; the key.
#include <gtest/gtest.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunlinsol/sunlinsol_spgmr.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <cfloat>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "src/core/units.hpp"
#include "src/model/simulation.hpp"
#include "src/scene/config.hpp"
#include "src/solver/cell_block_preconditioner.hpp"
#include "src/solver/conservative_gmres.hpp"
#include "src/solver/cvode_integrator.hpp"
#include "tests/unit/support/config_error.hpp"
#include "tests/unit/support/jacobian_check.hpp"

namespace panoptic {
namespace {

std::string small_scene() {
  return std::string(PANOPTIC_SOURCE_DIR) + "/params/tests/distribution_small.toml";
}

// P^-1 x against the inverse of the dense matrix I - gamma J restricted to the cells'
// diagonal blocks and the globals' diagonal: 3 cells of 4 variables, 2 globals, every
// entry of the matrix in the pattern (the couplings between cells must be dropped).
TEST(CellBlockPreconditioner, InvertsTheCellBlocksOnly) {
  const int n_cells = 3, b = 4, n_g = 2, n = n_cells * b + n_g;
  PatternBuilder builder(n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) builder.add(i, j);
  const SparsityPattern pattern(builder);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> jac(static_cast<std::size_t>(pattern.nnz()));
  for (double& v : jac) v = u(rng);
  const double gamma = 2.0;
  Eigen::MatrixXd p = Eigen::MatrixXd::Identity(n, n);
  const auto col_ptr = pattern.col_ptr();
  const auto rows = pattern.row_index();
  for (long c = 0; c < n; ++c)
    for (auto k = col_ptr[c]; k < col_ptr[c + 1]; ++k) {
      const long r = rows[k];
      const bool same_cell = r < n_cells * b && c < n_cells * b && r / b == c / b;
      if (same_cell || r == c) p(r, c) -= gamma * jac[static_cast<std::size_t>(k)];
    }
  CellBlockPreconditioner pre(pattern, n_cells, b);
  ASSERT_TRUE(pre.setup(jac, gamma));
  std::vector<double> x(static_cast<std::size_t>(n));
  for (double& v : x) v = u(rng);
  const Eigen::VectorXd expected =
      p.partialPivLu().solve(Eigen::Map<Eigen::VectorXd>(x.data(), n));
  ASSERT_TRUE(pre.solve(x));
  for (int i = 0; i < n; ++i) EXPECT_NEAR(x[i], expected(i), 1e-12) << i;
  EXPECT_EQ(pre.stored_doubles(), n_cells * b * b + n_g);
  // a singular block is reported: gamma J = I on the first cell's block
  std::vector<double> singular(jac.size(), 0.0);
  for (int i = 0; i < b; ++i)
    singular[static_cast<std::size_t>(pattern.position(i, i))] = 1.0 / gamma;
  EXPECT_FALSE(pre.setup(singular, gamma));
}

//! The Newton matrix A = I - gamma J of the products and the preconditioner of SPGMR.
struct NewtonSystem {
  const SparsityPattern* pattern;
  std::vector<double> jac;
  double gamma;
  CellBlockPreconditioner* pre;
  int n_psolve = 0, n_times = 0;  //!< calls of the preconditioner's solve and of A v
};

extern "C" int newton_times(void* data, N_Vector v, N_Vector z) {
  auto* s = static_cast<NewtonSystem*>(data);
  ++s->n_times;
  const std::size_t n = static_cast<std::size_t>(N_VGetLength(v));
  const std::span<const double> vs(N_VGetArrayPointer(v), n);
  const std::span<double> zs(N_VGetArrayPointer(z), n);
  s->pattern->multiply(s->jac, vs, zs);
  for (std::size_t i = 0; i < n; ++i) zs[i] = vs[i] - s->gamma * zs[i];
  return 0;
}
extern "C" int newton_psetup(void* data) {
  const auto* s = static_cast<NewtonSystem*>(data);
  return s->pre->setup(s->jac, s->gamma) ? 0 : 1;
}
extern "C" int newton_psolve(void* data, N_Vector r, N_Vector z, sunrealtype, int) {
  N_VScale(1.0, r, z);
  auto* s = static_cast<NewtonSystem*>(data);
  ++s->n_psolve;
  return s->pre->solve({N_VGetArrayPointer(z), static_cast<std::size_t>(N_VGetLength(z))})
             ? 0
             : 1;
}

// The weighted RMS norm of CVODE's tests.
double wrms(const std::vector<double>& x, const std::vector<double>& w) {
  double s = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) s += (x[i] * w[i]) * (x[i] * w[i]);
  return std::sqrt(s / static_cast<double>(x.size()));
}

// A Newton system of the small distribution scene (porous bins: the widest cells), every
// bin filled, gamma of a 1000 yr step (the transport couples the cells: the block
// preconditioner alone is not the inverse), right-hand side of unit weighted size in
// CVODE's error weights w.
class PorousNewtonSystem : public ::testing::Test {
 protected:
  Simulation sim{
      load_scene(small_scene(), std::vector<std::string>{"porosity.enabled=true"})};
  const SparsityPattern& pattern = sim.model().pattern();
  const long n = sim.model().layout().size();
  const std::size_t nz = static_cast<std::size_t>(n);
  CellBlockPreconditioner pre{pattern, sim.model().layout().n_cells(),
                              sim.model().layout().n_cell_vars()};
  NewtonSystem sys{&pattern, std::vector<double>(static_cast<std::size_t>(pattern.nnz())),
                   1000.0 * units::kYr, &pre};
  std::vector<double> w = std::vector<double>(nz), b = std::vector<double>(nz);
  void SetUp() override {
    const std::vector<double> y = testing::perturbed_state(sim, 3);
    sim.model().jacobian(0.0, y, sys.jac);
    const IntegratorOptions opt = sim.integrator_options();
    std::mt19937 rng(11);
    std::normal_distribution<double> normal(0.0, 1.0);
    for (std::size_t i = 0; i < nz; ++i) {
      w[i] = 1.0 / (opt.rtol * std::abs(y[i]) + opt.atol[i]);
      b[i] = normal(rng) / w[i];
    }
    ASSERT_EQ(SUNContext_Create(nullptr, &ctx), 0);
    bv = N_VMake_Serial(n, b.data(), ctx);
    wv = N_VMake_Serial(n, w.data(), ctx);
  }
  void TearDown() override {
    if (bv != nullptr) N_VDestroy(bv);
    if (wv != nullptr) N_VDestroy(wv);
    if (ctx != nullptr) SUNContext_Free(&ctx);
  }
  //! b and w as N_Vectors (on their storage) in a SUNDIALS context of their own
  SUNContext ctx = nullptr;
  N_Vector bv = nullptr, wv = nullptr;
};

// SPGMR on PorousNewtonSystem against KLU. SPGMR
// stops at ||W (b - A x)||_2 < delta = delta_rms sqrt(N), CVODE's form of its Krylov
// tolerance in the weighted RMS norm (there eplifac 0.05 times the error-test constant;
// here 1e-6, to see the iteration converge to KLU's solution).
TEST_F(PorousNewtonSystem, SpgmrMatchesKlu) {
  // KLU on A
  SUNMatrix a = SUNSparseMatrix(n, n, pattern.nnz(), CSC_MAT, ctx);
  pattern.copy_structure_to(SUNSparseMatrix_IndexPointers(a),
                            SUNSparseMatrix_IndexValues(a));
  double* av = SUNSparseMatrix_Data(a);
  for (std::size_t k = 0; k < sys.jac.size(); ++k) av[k] = -sys.gamma * sys.jac[k];
  for (long i = 0; i < n; ++i) av[pattern.position(i, i)] += 1.0;
  N_Vector x_klu = N_VClone(bv);
  SUNLinearSolver klu = SUNLinSol_KLU(bv, a, ctx);
  ASSERT_EQ(SUNLinSolInitialize(klu), 0);
  ASSERT_EQ(SUNLinSolSetup(klu, a), 0);
  ASSERT_EQ(SUNLinSolSolve(klu, a, x_klu, bv, 0.0), 0);
  // SPGMR, right-preconditioned, and without the preconditioner
  const double delta_rms = 1e-6;
  const auto gmres = [&](int prec, std::vector<double>& x, long& iterations) {
    N_Vector xv = N_VMake_Serial(n, x.data(), ctx);
    N_VConst(0.0, xv);
    SUNLinearSolver s = SUNLinSol_SPGMR(bv, prec, 20, ctx);
    SUNLinSolSetATimes(s, &sys, newton_times);
    SUNLinSolSetPreconditioner(s, &sys, newton_psetup, newton_psolve);
    SUNLinSolSetScalingVectors(s, wv, wv);
    SUNLinSolInitialize(s);
    EXPECT_EQ(SUNLinSolSetup(s, nullptr), 0);
    const int flag =
        SUNLinSolSolve(s, nullptr, xv, bv, delta_rms * std::sqrt(static_cast<double>(n)));
    iterations = SUNLinSolNumIters(s);
    SUNLinSolFree(s);
    N_VDestroy(xv);
    return flag;
  };
  std::vector<double> x(nz), x_plain(nz);
  long iterations = 0, plain_iterations = 0;
  EXPECT_EQ(gmres(SUN_PREC_RIGHT, x, iterations), SUNLS_SUCCESS);
  const int plain = gmres(SUN_PREC_NONE, x_plain, plain_iterations);
  std::vector<double> diff(nz), residual(nz);
  const double* xk = N_VGetArrayPointer(x_klu);
  for (std::size_t i = 0; i < nz; ++i) diff[i] = x[i] - xk[i];
  pattern.multiply(sys.jac, x, residual);
  for (std::size_t i = 0; i < nz; ++i)
    residual[i] = b[i] - (x[i] - sys.gamma * residual[i]);
  std::printf(
      "N = %ld: GMRES %ld iterations, weighted RMS residual %.3g, |x - x_klu| %.3g "
      "(KLU's solution %.3g); without the preconditioner: flag %d after %ld\n",
      n, iterations, wrms(residual, w), wrms(diff, w),
      wrms(std::vector<double>(xk, xk + nz), w), plain, plain_iterations);
  EXPECT_LT(wrms(residual, w), delta_rms);
  // the residual bounds the error through A^-1 (in the weighted norm: a few here)
  EXPECT_LT(wrms(diff, w), 10.0 * delta_rms);
  EXPECT_GT(iterations, 1);         // the cells' coupling is not in P
  EXPECT_NE(plain, SUNLS_SUCCESS);  // nor is I - gamma J close to I
  SUNLinSolFree(klu);
  SUNMatDestroy(a);
  N_VDestroy(x_klu);
}

// preconditioned_gmres (src/solver/conservative_gmres.hpp) is SPGMR's solve as CVODE
// calls it, less SPGMR's last preconditioner solve: on PorousNewtonSystem, for a
// Krylov dimension of 20 and of 2 and tolerances that take several iterations, one, or
// none (above |b|), it returns SPGMR's flag, iterations and residual norm, its solution
// to round-off with one preconditioner solve fewer and as many products, and the
// residual b - A x of that solution.
TEST_F(PorousNewtonSystem, PreconditionedGmresIsSpgmrWithoutItsLastSolve) {
  double beta = 0.0;
  for (std::size_t i = 0; i < nz; ++i) beta += (w[i] * b[i]) * (w[i] * b[i]);
  beta = std::sqrt(beta);
  const auto spgmr = [&](int maxl) {
    SUNLinearSolver s = SUNLinSol_SPGMR(bv, SUN_PREC_RIGHT, maxl, ctx);
    SUNLinSolSetATimes(s, &sys, newton_times);
    SUNLinSolSetPreconditioner(s, &sys, newton_psetup, newton_psolve);
    SUNLinSolSetScalingVectors(s, wv, wv);
    SUNLinSolInitialize(s);
    EXPECT_EQ(SUNLinSolSetup(s, nullptr), 0);
    return s;
  };
  const double tight = 1e-6 * std::sqrt(static_cast<double>(n));
  // SPGMR's residual after one iteration, to set a tolerance that one iteration meets
  double rho1 = 0.0;
  {
    SUNLinearSolver s = spgmr(1);
    std::vector<double> x(nz);
    N_Vector xv = N_VMake_Serial(n, x.data(), ctx);
    EXPECT_EQ(SUNLinSolSolve(s, nullptr, xv, bv, 0.0), SUNLS_RES_REDUCED);
    rho1 = SUNLinSolResNorm(s);
    N_VDestroy(xv);
    SUNLinSolFree(s);
  }
  ASSERT_LT(rho1, beta);  // one iteration reduces the residual
  struct Case {
    int maxl;
    double tol;
    int flag;
  };
  for (const Case c :
       {Case{20, tight, SUNLS_SUCCESS}, Case{2, tight, SUNLS_RES_REDUCED},
        Case{20, 1.01 * rho1, SUNLS_SUCCESS}, Case{20, 1.01 * beta, SUNLS_SUCCESS}}) {
    SUNLinearSolver ref = spgmr(c.maxl), ours = spgmr(c.maxl);
    std::vector<double> x_ref(nz), x(nz), r, ax(nz), diff(nz), r_check(nz);
    N_Vector xr = N_VMake_Serial(n, x_ref.data(), ctx),
             xv = N_VMake_Serial(n, x.data(), ctx);
    N_Vector axv = N_VMake_Serial(n, ax.data(), ctx);
    sys.n_psolve = sys.n_times = 0;
    SUNLinSolSetZeroGuess(ref, SUNTRUE);
    EXPECT_EQ(SUNLinSolSolve(ref, nullptr, xr, bv, c.tol), c.flag)
        << c.maxl << " " << c.tol;
    const int ref_psolve = sys.n_psolve, ref_times = sys.n_times;
    const int iterations = SUNLinSolNumIters(ref);
    sys.n_psolve = sys.n_times = 0;
    GmresDirections directions;
    EXPECT_EQ(preconditioned_gmres(ours, xv, bv, c.tol, directions, r), c.flag);
    EXPECT_EQ(SUNLinSolNumIters(ours), iterations);
    EXPECT_EQ(SUNLinSolLastFlag(ours), c.flag);
    EXPECT_NEAR(SUNLinSolResNorm(ours), SUNLinSolResNorm(ref),
                1e-12 * SUNLinSolResNorm(ref));
    EXPECT_EQ(sys.n_times, ref_times);
    EXPECT_EQ(sys.n_psolve, iterations > 0 ? ref_psolve - 1 : 0);
    for (std::size_t i = 0; i < nz; ++i) diff[i] = x[i] - x_ref[i];
    EXPECT_LE(wrms(diff, w), 1e-12 * wrms(x_ref, w));
    newton_times(&sys, xv, axv);
    for (std::size_t i = 0; i < nz; ++i) r_check[i] = r[i] - (b[i] - ax[i]);
    // to the round-off of the products A z_l and A x, whose terms x_j - gamma J_ij x_j
    // are far larger than their sums (they cancel): sum_j |A_ij| |x_j| sets its scale
    std::vector<double> abs_jac(sys.jac.size()), abs_x(nz), terms(nz);
    for (std::size_t k = 0; k < abs_jac.size(); ++k) abs_jac[k] = std::abs(sys.jac[k]);
    for (std::size_t i = 0; i < nz; ++i) abs_x[i] = std::abs(x[i]);
    pattern.multiply(abs_jac, abs_x, terms);
    for (std::size_t i = 0; i < nz; ++i) terms[i] = abs_x[i] + sys.gamma * terms[i];
    EXPECT_LT(wrms(r_check, w), 16.0 * DBL_EPSILON * (wrms(terms, w) + wrms(b, w)));
    std::printf(
        "Krylov dimension %d, tolerance %.3g: %d iterations, residual %.3g; x - x_spgmr "
        "%.2g, r - (b - A x) %.2g (|A| |x| %.3g)\n",
        c.maxl, c.tol, iterations, SUNLinSolResNorm(ours), wrms(diff, w),
        wrms(r_check, w), wrms(terms, w));
    for (N_Vector v : {xr, xv, axv}) N_VDestroy(v);
    SUNLinSolFree(ref);
    SUNLinSolFree(ours);
  }
}

// The budget's weights c (Simulation::budget_weights, the invariant GMRES's solutions
// are corrected to keep): c . y is the sum of the budget terms, and c . f(y) = 0 (the
// model conserves the booked dust mass) up to round-off, on perturbed states of a porous
// size distribution and of the single-size scene with planetesimals.
TEST(KrylovSolver, BudgetWeightsSumTheBudgetAndTheModelConservesThem) {
  const std::string fiducial = std::string(PANOPTIC_SOURCE_DIR) + "/params/fiducial.toml";
  for (const auto& [scene, sets] :
       {std::pair{small_scene(), std::vector<std::string>{"porosity.enabled=true"}},
        std::pair{fiducial, std::vector<std::string>{}}}) {
    Simulation sim(load_scene(scene, sets));
    const std::vector<double> c = sim.budget_weights();
    for (unsigned seed : {1u, 2u}) {
      const std::vector<double> y = testing::perturbed_state(sim, seed);
      double total = 0.0, cy = 0.0, cf = 0.0, cf_abs = 0.0;
      for (const double m : sim.budget_masses(y)) total += m;
      std::vector<double> f(y.size());
      sim.model().rhs(0.0, y, f);
      for (std::size_t j = 0; j < y.size(); ++j) {
        cy += c[j] * y[j];
        cf += c[j] * f[j];
        cf_abs += std::abs(c[j] * f[j]);
      }
      EXPECT_NEAR(cy, total, 1e-13 * total) << scene;
      EXPECT_GT(cf_abs, 0.0) << scene;
      EXPECT_LT(std::abs(cf), 1e-12 * cf_abs) << scene;
    }
  }
}

// A GMRES run keeps the dust budget to round-off, as a direct solver does: the small
// distribution scene to 300 yr, with every Krylov solution corrected to keep the
// budget's invariant (conservative_spgmr_solve), and, to show what that mends, without
// the correction, where the budget closes only to the Krylov residual.
TEST(KrylovSolver, CorrectedSolutionsCloseTheBudgetToRoundOff) {
  Simulation sim(load_scene(
      small_scene(),
      std::vector<std::string>{"solver.linear=\"gmres\"", "output.t_end_yr=300"}));
  const IntegratorOptions corrected = sim.integrator_options();
  ASSERT_EQ(corrected.invariant.size(), sim.initial_state().size());
  IntegratorOptions uncorrected = corrected;
  uncorrected.invariant.clear();
  double error[2];
  for (int k = 0; k < 2; ++k) {
    CvodeIntegrator cvode(sim.model(), 0.0, sim.initial_state(),
                          k == 0 ? uncorrected : corrected);
    cvode.advance_to(300.0 * units::kYr);
    error[k] = sim.budget_error(cvode.state());
  }
  std::printf("budget error to 300 yr: %.2e uncorrected, %.2e corrected\n", error[0],
              error[1]);
  EXPECT_GT(error[0], 1e-13);
  EXPECT_LT(error[1], 1e-14);
}

// solver.linear = "gmres": accepted, listed in the refusal of an unknown solver, and
// what the integrator builds (the preconditioner over the layout's cells).
TEST(KrylovSolver, SolverLinearKey) {
  const Config cfg =
      load_scene(small_scene(), std::vector<std::string>{"solver.linear=\"gmres\""});
  EXPECT_EQ(cfg.str("solver.linear"), "gmres");
  Simulation sim(cfg);
  const IntegratorOptions opt = sim.integrator_options();
  EXPECT_EQ(opt.linear, LinearSolverKind::gmres);
  CvodeIntegrator cvode(sim.model(), 0.0, sim.initial_state(), opt);
  ASSERT_NE(cvode.preconditioner(), nullptr);
  const int b = sim.model().layout().n_cell_vars();
  EXPECT_EQ(cvode.preconditioner()->stored_doubles(),
            static_cast<long>(sim.model().layout().n_cells()) * b * b +
                sim.model().layout().n_global_vars());
  EXPECT_EQ(cvode.block_solver(), nullptr);
  const std::string m = config_error_message(
      [&] {
        load_scene(small_scene(), std::vector<std::string>{"solver.linear=\"krylov\""});
      },
      "solver.linear = krylov");
  EXPECT_NE(m.find("klu, block, gmres"), std::string::npos) << m;
}

}  // namespace
}  // namespace panoptic
