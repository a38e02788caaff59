// Micro-benchmarks (Google Benchmark; not a test) of the three kernels of a CVODE step
// on the fiducial scene (params/fiducial.toml): the right-hand side, the Jacobian
// evaluation and the KLU factorisation + solve of the Newton matrix I - gamma J, at
// N = 100, 250 (the default) and 1000 cells. The state is the fiducial run's at
// t = 300 yr (grown and compacting particles inside ~3 au, monomers further out), so
// every branch of the rates is visited. The counter `per_cell` is the CPU time per call
// divided by N (CPU rather than wall time: the machine is shared).
// Usage: build/tests/bench_kernels [--benchmark_filter=Rhs] [--benchmark_repetitions=5]
#include <benchmark/benchmark.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <algorithm>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "src/core/units.hpp"
#include "src/model/simulation.hpp"
#include "src/scene/config.hpp"
#include "src/solver/cvode_integrator.hpp"

using namespace panoptic;

namespace {

constexpr double kStateAgeYr = 300.0;

//! The fiducial scene at N cells and its state at kStateAgeYr (integrated once per N).
struct Fixture {
  std::unique_ptr<Simulation> sim;
  std::vector<double> y;
};

Fixture& fixture(int n) {
  static std::map<int, Fixture> cache;
  auto it = cache.find(n);
  if (it != cache.end()) return it->second;
  const std::string scene = std::string(PANOPTIC_SOURCE_DIR) + "/params/fiducial.toml";
  Fixture fx;
  const std::vector<std::string> sets{"grid.n_cells=" + std::to_string(n)};
  fx.sim = std::make_unique<Simulation>(load_scene(scene, sets));
  const auto y0 = fx.sim->initial_state();
  CvodeIntegrator cvode(fx.sim->model(), 0.0, y0, fx.sim->integrator_options());
  cvode.advance_to(kStateAgeYr * units::kYr);
  fx.y.assign(cvode.state().begin(), cvode.state().end());
  return cache.emplace(n, std::move(fx)).first->second;
}

//! Two states a relative 1e-9 apart, alternated so that no per-cell cache (St, rates)
//! is hit: every call does the full work, as in CVODE's Newton iterations.
std::vector<double> nudged(const std::vector<double>& y) {
  std::vector<double> z(y);
  for (auto& v : z) v *= 1.0 + 1e-9;
  return z;
}

void set_per_cell(benchmark::State& state, int n) {
  state.counters["per_cell"] = benchmark::Counter(
      n, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

//! The model's right-hand side (or, with `jacobian`, its Jacobian) at the fixture's
//! state and a nudged copy, alternately, so that no memo of the last state is hit.
void time_model(benchmark::State& state, bool jacobian) {
  const int n = static_cast<int>(state.range(0));
  auto& fx = fixture(n);
  const auto y2 = nudged(fx.y);
  const DiskModel& model = fx.sim->model();
  std::vector<double> out(jacobian ? model.pattern().nnz() : fx.y.size());
  bool flip = false;
  for (auto _ : state) {
    const std::vector<double>& y = flip ? y2 : fx.y;
    if (jacobian)
      model.jacobian(kStateAgeYr * units::kYr, y, out);
    else
      model.rhs(kStateAgeYr * units::kYr, y, out);
    flip = !flip;
    benchmark::DoNotOptimize(out.data());
  }
  set_per_cell(state, n);
}

void BM_Rhs(benchmark::State& state) { time_model(state, false); }

void BM_Jacobian(benchmark::State& state) { time_model(state, true); }

//! The Newton matrix M = I - gamma J of the fixture's state at a step typical of that
//! time (0.1 yr, BDF2), in a KLU solver that has analysed and factorised it once (not
//! timed), with a right-hand side b = 1.
class NewtonSystem {
 public:
  explicit NewtonSystem(const Fixture& fx) {
    const auto& model = fx.sim->model();
    const auto& pattern = model.pattern();
    const auto size = static_cast<sunindextype>(fx.y.size());
    std::vector<double> jac(pattern.nnz());
    model.jacobian(kStateAgeYr * units::kYr, fx.y, jac);
    const double gamma = 0.1 * units::kYr * 2.0 / 3.0;
    SUNContext_Create(nullptr, &ctx_);
    A_ = SUNSparseMatrix(size, size, pattern.nnz(), CSC_MAT, ctx_);
    x_ = N_VNew_Serial(size, ctx_);
    b_ = N_VNew_Serial(size, ctx_);
    pattern.copy_structure_to(SUNSparseMatrix_IndexPointers(A_),
                              SUNSparseMatrix_IndexValues(A_));
    double* a = SUNSparseMatrix_Data(A_);
    const auto cols = pattern.col_ptr();
    const auto rows = pattern.row_index();
    for (sunindextype j = 0; j < size; ++j)
      for (sunindextype k = cols[j]; k < cols[j + 1]; ++k)
        a[k] = (rows[k] == j ? 1.0 : 0.0) - gamma * jac[k];
    ls_ = SUNLinSol_KLU(x_, A_, ctx_);
    SUNLinSolInitialize(ls_);
    SUNLinSolSetup(ls_, A_);  // analysis + first factorisation
    N_VConst(1.0, b_);
  }
  ~NewtonSystem() {
    SUNLinSolFree(ls_);
    N_VDestroy(x_);
    N_VDestroy(b_);
    SUNMatDestroy(A_);
    SUNContext_Free(&ctx_);
  }
  NewtonSystem(const NewtonSystem&) = delete;
  NewtonSystem& operator=(const NewtonSystem&) = delete;

  //! A later set-up: refactorisation with the same pivot order.
  void refactor() { SUNLinSolSetup(ls_, A_); }
  void solve() {
    SUNLinSolSolve(ls_, A_, x_, b_, 0.0);
    benchmark::DoNotOptimize(N_VGetArrayPointer(x_));
  }

 private:
  SUNContext ctx_ = nullptr;
  SUNMatrix A_ = nullptr;
  N_Vector x_ = nullptr, b_ = nullptr;
  SUNLinearSolver ls_ = nullptr;
};

//! KLU as CVODE uses it: the first set-up analyses and factorises; later set-ups
//! refactorise with the same pivot order (timed here), then one solve per Newton
//! iteration (one per set-up timed here; the fiducial run averages ~10 solves per
//! set-up, see bench_fiducial).
void BM_KluFactorSolve(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  NewtonSystem newton(fixture(n));
  for (auto _ : state) {
    newton.refactor();
    newton.solve();
  }
  set_per_cell(state, n);
}

//! One solve with the factors of the last set-up (a Newton iteration).
void BM_KluSolve(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  NewtonSystem newton(fixture(n));
  for (auto _ : state) newton.solve();
  set_per_cell(state, n);
}

}  // namespace

BENCHMARK(BM_Rhs)->Arg(100)->Arg(250)->Arg(1000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Jacobian)->Arg(100)->Arg(250)->Arg(1000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_KluFactorSolve)
    ->Arg(100)
    ->Arg(250)
    ->Arg(1000)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_KluSolve)->Arg(100)->Arg(250)->Arg(1000)->Unit(benchmark::kMicrosecond);
BENCHMARK_MAIN();
