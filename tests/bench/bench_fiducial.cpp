// Benchmark (not a test): params/fiducial.toml integrated as `panoptic run` does it
// (CVODE reinitialised at every snapshot time), without output, median wall time of R
// runs. Prints the solver statistics, the cost per cell per step, and where the time
// goes: the model's right-hand side and Jacobian, KLU's factorisation and solve (each
// call timed), and the rest (CVODE's own work: predictor, error test, history, vector
// operations). Usage: build/tests/bench_fiducial [--runs R] [--trace K] [--lts]
// [--scene FILE] [--set key=value ...]
//   --scene FILE: another scene than params/fiducial.toml (e.g. a size distribution with
//              solver.linear = "block": the set-up and solve rows are then the block
//              solver's).
//   --trace K: every K-th step, print t, h, order, the counts so far (convergence and
//              error-test failures, Jacobians, RHS) and the components with the largest
//              weighted local error (which variables limit the step), then the physical
//              state of the cell of the largest (after "||").
//   --lts:     also estimate from the coupled run what a scheme that stepped blocks of
//              B neighbouring cells each with its own step size (multirate, local time
//              stepping) would need at best (issues 3, 7; tests/bench/lts_estimate.hpp).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <iterator>
#include <span>
#include <string>
#include <vector>

#include "physics/modules/dust_transport.hpp"
#include "src/core/units.hpp"
#include "src/model/simulation.hpp"
#include "src/scene/config.hpp"
#include "src/solver/cvode_integrator.hpp"
#include "src/solver/state_layout.hpp"
#include "tests/bench/lts_estimate.hpp"

using namespace panoptic;

namespace {

struct Result {
  double wall = 0.0;
  double cpu = 0.0;  //!< the process's CPU time over the run (on a shared machine)
  SolverStats stats;
  CallbackTimes times;
};

Result run_once(const Config& cfg, long trace_every, bool lts) {
  Simulation sim(cfg);
  const auto times = sim.output_times();
  const auto y0 = sim.initial_state();
  Result res;
  const auto t0 = std::chrono::steady_clock::now();
  const std::clock_t cpu0 = std::clock();
  sim.refresh_local_gas(y0);  // as panoptic run (evolving gas)
  CvodeIntegrator cvode(sim.model(), times.front(), y0, sim.integrator_options());
  cvode.set_profile(&res.times);
  const bool reinit = cfg.flag("solver.reinit_at_snapshots");
  bench::LtsEstimate estimate(sim.model().layout());
  std::vector<double> sigma_d(static_cast<std::size_t>(sim.grid().n_cells()));
  for (std::size_t k = 1; k < times.size(); ++k) {
    cvode.advance_to(times[k], [&](double t, long nst) {
      if (lts) {
        const auto info = cvode.step_info(0, true);
        for (std::size_t c = 0; c < sigma_d.size(); ++c)
          sigma_d[c] = sim.transport().sigma_d(static_cast<int>(c), cvode.state());
        estimate.add(info.weighted_errors, info.h_last, info.order_last,
                     times[k] - times[k - 1], sigma_d);
      }
      if (trace_every <= 0 || nst % trace_every != 0) return;
      const auto info = cvode.step_info(3);
      const SolverStats so_far = cvode.stats();  // counts so far (failures, Jacobians)
      std::printf(
          "t = %.4e yr  step %ld  h = %.3e yr  q = %d  (ncf %ld netf %ld nje %ld nfe "
          "%ld)  limited by:",
          t / units::kYr, nst, info.h / units::kYr, info.order, so_far.nncf, so_far.netf,
          so_far.nje, so_far.nfe);
      for (const auto& [i, e] : info.largest_errors)
        std::printf("  %s (%.2f)", sim.model().layout().describe(i).c_str(), e);
      if (!info.largest_errors.empty())  // the physical state where the step is limited
        std::printf(
            "  || %s",
            sim.model().describe(info.largest_errors[0].first, cvode.state()).c_str());
      std::printf("\n");
    });
    if (reinit) {
      const std::vector<double> y(cvode.state().begin(), cvode.state().end());
      sim.refresh_local_gas(y);
      cvode.reinit(times[k], y);
    }
  }
  res.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  res.cpu = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
  res.stats = cvode.stats();
  if (lts) estimate.print(res.stats.nst);
  return res;
}

}  // namespace

int main(int argc, char** argv) {
  int runs = 3;
  long trace = 0;
  bool lts = false;
  std::vector<std::string> sets;
  std::string scene = std::string(PANOPTIC_SOURCE_DIR) + "/params/fiducial.toml";
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--runs") && i + 1 < argc) {
      runs = std::atoi(argv[++i]);
    } else if (!std::strcmp(argv[i], "--trace") && i + 1 < argc) {
      trace = std::atol(argv[++i]);
    } else if (!std::strcmp(argv[i], "--lts")) {
      lts = true;
    } else if (!std::strcmp(argv[i], "--set") && i + 1 < argc) {
      sets.emplace_back(argv[++i]);
    } else if (!std::strcmp(argv[i], "--scene") && i + 1 < argc) {
      scene = argv[++i];
    } else {
      std::fprintf(stderr,
                   "usage: bench_fiducial [--runs R] [--trace K] [--lts] [--scene FILE] "
                   "[--set key=value ...]\n");
      return 2;
    }
  }
  const Config cfg = load_scene(scene, sets);
  std::vector<Result> results;
  for (int r = 0; r < std::max(runs, 1); ++r)
    results.push_back(run_once(cfg, trace, lts));
  std::sort(results.begin(), results.end(),
            [](const Result& a, const Result& b) { return a.wall < b.wall; });
  const Result& m = results[results.size() / 2];
  const SolverStats& s = m.stats;
  const int n = static_cast<int>(cfg.integer("grid.n_cells"));
  const double other =
      m.wall - m.times.rhs_s - m.times.jac_s - m.times.lsetup_s - m.times.lsolve_s;
  const auto pct = [&](double x) { return 100.0 * x / m.wall; };
  const auto us = [&](double x, long calls) {
    return calls > 0 ? 1e6 * x / (double(n) * double(calls)) : 0.0;
  };
  std::printf("%s to %g yr, %d cells", scene.c_str(), cfg.real("output.t_end_yr"), n);
  for (const auto& set : sets) std::printf(", %s", set.c_str());
  std::printf("; median of %zu runs (walls:", results.size());
  for (const auto& r : results) std::printf(" %.3f", r.wall);
  std::printf(" s; CPU of the median run %.3f s)\n", m.cpu);
  std::printf(
      "| wall [s] | steps | RHS | Jac | KLU set-ups | Newton its | err-test fails | "
      "conv fails | us per cell per step |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|\n");
  std::printf("| %.3f | %ld | %ld | %ld | %ld | %ld | %ld | %ld | %.3f |\n", m.wall,
              s.nst, s.nfe, s.nje, s.nsetups, s.nni, s.netf, s.nncf,
              1e6 * m.wall / (double(n) * double(s.nst)));
  std::printf("\n| part | wall [s] | share | calls | us per cell per call |\n");
  std::printf("|---|---|---|---|---|\n");
  std::printf("| right-hand side | %.3f | %.0f %% | %ld | %.3f |\n", m.times.rhs_s,
              pct(m.times.rhs_s), m.times.n_rhs, us(m.times.rhs_s, m.times.n_rhs));
  std::printf("| Jacobian | %.3f | %.0f %% | %ld | %.3f |\n", m.times.jac_s,
              pct(m.times.jac_s), m.times.n_jac, us(m.times.jac_s, m.times.n_jac));
  // with GMRES the set-up is the preconditioner's, which evaluates the Jacobian: the
  // Jacobian row is then also inside the set-up row
  const std::string linear = cfg.str("solver.linear");
  const std::string ls = linear == "klu" ? "KLU"
                         : linear == "block"
                             ? "block solver"
                             : "GMRES (set-up: Jacobian and preconditioner)";
  std::printf("| %s factorisation | %.3f | %.0f %% | %ld | %.3f |\n", ls.c_str(),
              m.times.lsetup_s, pct(m.times.lsetup_s), m.times.n_lsetup,
              us(m.times.lsetup_s, m.times.n_lsetup));
  std::printf("| %s solve | %.3f | %.0f %% | %ld | %.3f |\n", ls.c_str(),
              m.times.lsolve_s, pct(m.times.lsolve_s), m.times.n_lsolve,
              us(m.times.lsolve_s, m.times.n_lsolve));
  std::printf("| CVODE overhead (the rest) | %.3f | %.0f %% | %ld steps | %.3f |\n",
              other, pct(other), s.nst, us(other, s.nst));
  return 0;
}
