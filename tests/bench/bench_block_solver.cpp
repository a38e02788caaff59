// The two solvers of CVODE's Newton systems (solver.linear; not a test) on one Newton
// matrix M = I - gamma J of a scene: KLU (SUNDIALS' KLU, as CVODE calls it: the first
// set-up analyses, later ones refactor) and the block-banded LU
// (src/solver/block_banded_lu.hpp). The state is the scene's at --t-yr, integrated with
// the scene's own solver settings; gamma = --gamma-yr (BDF1's h). Prints the CPU time of
// each set-up and solve (medians of --reps), the residual |M x - b|_inf / |b|_inf of
// each solution of a random right-hand side and their difference; and the CPU time of
// the product J b (GMRES's) by runs of rows against entry by entry.
// Usage: build/tests/bench_block_solver SCENE [--t-yr T] [--gamma-yr G] [--reps R]
//        [--set key=value ...]
// Results: tests/bench/results/block_solver.md (the product: porous_cost.md, "GMRES's
// product J v over runs of rows").
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "src/core/units.hpp"
#include "src/model/simulation.hpp"
#include "src/scene/config.hpp"
#include "src/solver/block_banded_lu.hpp"
#include "src/solver/cvode_integrator.hpp"

using namespace panoptic;

namespace {

double cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

//! The median CPU time of `reps` calls of f.
double median_time(int reps, const std::function<void()>& f) {
  std::vector<double> t;
  for (int r = 0; r < reps; ++r) {
    const double t0 = cpu_seconds();
    f();
    t.push_back(cpu_seconds() - t0);
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

//! r = M x for M in CSC form, entry by entry through the row indices.
void product_by_entries(const SparsityPattern& p, const std::vector<double>& m,
                        const std::vector<double>& x, std::vector<double>& r) {
  std::fill(r.begin(), r.end(), 0.0);
  const auto col_ptr = p.col_ptr();
  const auto rows = p.row_index();
  for (long c = 0; c < p.size(); ++c)
    for (auto k = col_ptr[c]; k < col_ptr[c + 1]; ++k) r[rows[k]] += m[k] * x[c];
}

//! |M x - b|_inf / |b|_inf for M in CSC form.
double residual(const SparsityPattern& p, const std::vector<double>& m,
                const std::vector<double>& x, const std::vector<double>& b) {
  std::vector<double> r(b.size());
  product_by_entries(p, m, x, r);
  double num = 0.0, den = 0.0;
  for (std::size_t i = 0; i < b.size(); ++i) {
    num = std::max(num, std::abs(r[i] - b[i]));
    den = std::max(den, std::abs(b[i]));
  }
  return num / den;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr,
                 "usage: %s SCENE [--t-yr T] [--gamma-yr G] [--reps R] [--set k=v]\n",
                 argv[0]);
    return 2;
  }
  std::string scene = argv[1];
  double t_yr = 0.0, gamma_yr = 0.01;
  int reps = 5;
  std::vector<std::string> sets;
  for (int i = 2; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--t-yr")
      t_yr = std::stod(argv[i + 1]);
    else if (a == "--gamma-yr")
      gamma_yr = std::stod(argv[i + 1]);
    else if (a == "--reps")
      reps = std::stoi(argv[i + 1]);
    else if (a == "--set")
      sets.emplace_back(argv[i + 1]);
  }
  Simulation sim(load_scene(scene, sets));
  std::vector<double> y = sim.initial_state();
  if (t_yr > 0.0) {
    CvodeIntegrator cvode(sim.model(), 0.0, y, sim.integrator_options());
    cvode.advance_to(t_yr * units::kYr);
    y.assign(cvode.state().begin(), cvode.state().end());
  }
  const SparsityPattern& pattern = sim.model().pattern();
  const StateLayout& layout = sim.model().layout();
  const long n = pattern.size();
  std::vector<double> jac(static_cast<std::size_t>(pattern.nnz()));
  sim.model().jacobian(t_yr * units::kYr, y, jac);
  const double gamma = gamma_yr * units::kYr;
  std::vector<double> m(jac.size());
  const auto col_ptr = pattern.col_ptr();
  const auto rows = pattern.row_index();
  for (long c = 0; c < n; ++c)
    for (auto k = col_ptr[c]; k < col_ptr[c + 1]; ++k)
      m[k] = (rows[k] == c ? 1.0 : 0.0) - gamma * jac[k];
  std::vector<double> b(static_cast<std::size_t>(n));
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (double& v : b) v = u(rng);

  // KLU through SUNDIALS, as CVODE uses it
  SUNContext ctx = nullptr;
  SUNContext_Create(nullptr, &ctx);
  N_Vector xv = N_VNew_Serial(n, ctx), bv = N_VNew_Serial(n, ctx);
  SUNMatrix a = SUNSparseMatrix(n, n, pattern.nnz(), CSC_MAT, ctx);
  pattern.copy_structure_to(SUNSparseMatrix_IndexPointers(a),
                            SUNSparseMatrix_IndexValues(a));
  std::copy(m.begin(), m.end(), SUNSparseMatrix_Data(a));
  SUNLinearSolver klu = SUNLinSol_KLU(xv, a, ctx);
  SUNLinSolInitialize(klu);
  double t0 = cpu_seconds();
  SUNLinSolSetup(klu, a);
  const double klu_first = cpu_seconds() - t0;
  const double klu_setup = median_time(reps, [&] { SUNLinSolSetup(klu, a); });
  std::copy(b.begin(), b.end(), N_VGetArrayPointer(bv));
  const double klu_solve =
      median_time(reps, [&] { SUNLinSolSolve(klu, a, xv, bv, 0.0); });
  const std::vector<double> x_klu(N_VGetArrayPointer(xv), N_VGetArrayPointer(xv) + n);

  t0 = cpu_seconds();
  BlockBandedLU lu(pattern, layout.n_cells(), layout.n_cell_vars());
  const double block_build = cpu_seconds() - t0;
  bool ok = true;
  const double block_setup = median_time(reps, [&] { ok = lu.factorize(m) && ok; });
  std::vector<double> x_block(b);
  const double block_solve = median_time(reps, [&] {
    x_block = b;
    ok = lu.solve(x_block) && ok;
  });
  double diff = 0.0, scale = 0.0;
  for (long i = 0; i < n; ++i) {
    diff = std::max(diff, std::abs(x_block[i] - x_klu[i]));
    scale = std::max(scale, std::abs(x_klu[i]));
  }
  std::printf(
      "%s at %g yr, gamma %g yr: %d cells x %d variables + %d globals, %ld "
      "non-zeros, block bandwidth %d\n",
      scene.c_str(), t_yr, gamma_yr, layout.n_cells(), layout.n_cell_vars(),
      layout.n_global_vars(), pattern.nnz(), lu.bandwidth());
  std::printf("| solver | first set-up [s] | set-up [s] | solve [s] | residual |\n");
  std::printf("|---|---|---|---|---|\n");
  std::printf("| KLU | %.4g | %.4g | %.4g | %.2e |\n", klu_first, klu_setup, klu_solve,
              residual(pattern, m, x_klu, b));
  std::printf("| block | %.4g (map) | %.4g | %.4g | %.2e |\n", block_build, block_setup,
              block_solve, residual(pattern, m, x_block, b));
  std::printf("block %s; |x_block - x_klu|_inf / |x_klu|_inf = %.2e\n",
              ok ? "succeeded" : "FAILED", diff / scale);
  // GMRES's product J v (SparsityPattern::multiply, over runs of rows) against the same
  // sums entry by entry: the same bits, and the CPU time of each (medians of 10 reps)
  std::vector<double> jb(b.size()), jb_entries(b.size());
  const double product_runs =
      median_time(10 * reps, [&] { pattern.multiply(jac, b, jb); });
  const double product_entries =
      median_time(10 * reps, [&] { product_by_entries(pattern, jac, b, jb_entries); });
  const bool same = jb == jb_entries;
  std::printf("product J b: %.4g s by runs of rows, %.4g s entry by entry (%s)\n",
              product_runs, product_entries, same ? "identical" : "DIFFERENT");
  ok = ok && same;
  SUNLinSolFree(klu);
  SUNMatDestroy(a);
  N_VDestroy(xv);
  N_VDestroy(bv);
  SUNContext_Free(&ctx);
  return ok ? 0 : 1;
}
