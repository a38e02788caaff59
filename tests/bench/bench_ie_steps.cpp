// What sets the steps of DustPy's step rule (solver.method = "implicit_euler") on a
// size-distribution scene, and what DustPy does differently that could take more of them
// (not a test; tests/bench/results/implicit_euler.md, "Why DustPy takes more steps").
// Integrates the scene as `panoptic run` does (gas of the particle laws refreshed at
// every snapshot) and prints the steps to every snapshot, the components that set the
// steps after --window-yr (variable and cell, with their count), and with --log FILE
// every step from --log-from-yr on (t, dt, the limiting component, its value over its
// floor). Variants, each an emulation of something DustPy does (file and function names
// in the results file):
//   --no-gas       Sigma_g out of the rule (the dust's time step alone)
//   --edge N       the N innermost and outermost cells out of the rule (DustPy leaves its
//                  two boundary cells out of both time steps)
//   --floor-reset  after every step every bin at or below its floor 0.1 m_k/A_i is set to
//                  a tenth of it (dustpy/std/dust.py enforce_floor_value; adds mass)
//   --picard       DustPy's coagulation matrix in place of the coagulation Jacobian:
//                  each pair's rate attributed to the column of its larger partner, with
//                  the smaller partner's number density held (dust.f90
//                  jacobian_coagulation_generator), so that J_P sigma = S_coag; built
//                  from the engine's right-hand side on the state cut above each bin;
//                  --picard-cells K: in the K innermost cells only (a cheaper proxy)
// The last two (and --own, for a check: the same steps) take the steps here (the
// integrator's arithmetic: M = I - dt J, M Delta = dt f); the others run
// ImplicitEulerIntegrator itself.
// Usage: build/tests/bench_ie_steps SCENE [--set key=value ...] [--no-gas] [--edge N]
//        [--floor-reset] [--picard] [--picard-cells K] [--own] [--window-yr T] [--log
//        FILE] [--log-from-yr T]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "physics/modules/size_distribution.hpp"
#include "src/core/units.hpp"
#include "src/model/simulation.hpp"
#include "src/scene/config.hpp"
#include "src/solver/block_banded_lu.hpp"
#include "src/solver/implicit_euler_integrator.hpp"

using namespace panoptic;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct Args {
  std::string scene, log;
  std::vector<std::string> sets;
  bool no_gas = false, floor_reset = false, picard = false, own = false;
  int edge = 0, picard_cells = -1;
  double window_yr = 1e4, log_from_yr = 1e4;
};

Args parse(int argc, char** argv) {
  Args a;
  a.scene = argv[1];
  a.sets.emplace_back("solver.method=\"implicit_euler\"");
  for (int i = 2; i < argc; ++i) {
    const std::string s = argv[i];
    const bool has_value = i + 1 < argc;
    if (s == "--no-gas")
      a.no_gas = true;
    else if (s == "--floor-reset")
      a.floor_reset = true;
    else if (s == "--picard")
      a.picard = true;
    else if (s == "--own")
      a.own = true;
    else if (s == "--set" && has_value)
      a.sets.emplace_back(argv[++i]);
    else if (s == "--edge" && has_value)
      a.edge = std::stoi(argv[++i]);
    else if (s == "--picard-cells" && has_value)
      a.picard_cells = std::stoi(argv[++i]);
    else if (s == "--window-yr" && has_value)
      a.window_yr = std::stod(argv[++i]);
    else if (s == "--log" && has_value)
      a.log = argv[++i];
    else if (s == "--log-from-yr" && has_value)
      a.log_from_yr = std::stod(argv[++i]);
    else
      throw std::invalid_argument("bench_ie_steps: unknown or incomplete option " + s);
  }
  return a;
}

//! DustPy's coagulation matrix (see the header) on the intra-cell bin blocks of J:
//! J's dense coagulation block of each cell (the engine's derivative) is replaced by
//! J_P. Column i of J_P is S^(i) / sigma_i, S^(i) the rates of the pairs whose larger
//! partner is bin i: S(bins <= i) - S(bins < i). Entries below the round-off of that
//! difference (1e-13 of the larger term) are dropped.
class PicardMatrix {
 public:
  //! J_P in the cells below `n_cells` (all if negative), the derivative elsewhere.
  PicardMatrix(const Simulation& sim, int n_cells)
      : sim_(sim), dist_(*sim.distribution()), n_cells_(n_cells) {
    const StateLayout& L = sim.model().layout();
    const int nb = dist_.n_bins();
    pos_.resize(static_cast<std::size_t>(L.n_cells()) * nb * nb);
    for (int c = 0; c < L.n_cells(); ++c)
      for (int k = 0; k < nb; ++k)
        for (int i = 0; i < nb; ++i)
          pos_[(static_cast<std::size_t>(c) * nb + k) * nb + i] =
              sim.model().pattern().position(L.index(c, dist_.bin_slot(k)),
                                             L.index(c, dist_.bin_slot(i)));
  }

  //! J (the model's Jacobian at y, pattern order) with the coagulation blocks swapped.
  void apply(std::span<const double> y, std::vector<double>& jac) const {
    const StateLayout& L = sim_.model().layout();
    const auto& engine = dist_.engine();
    const int nb = dist_.n_bins();
    std::vector<double> sigma(nb), cut(nb), below(nb), upto(nb), dense(nb * nb);
    before_.resize(static_cast<std::size_t>(nb) * nb);
    const int cells = n_cells_ < 0 ? L.n_cells() : std::min(n_cells_, L.n_cells());
    for (int c = 0; c < cells; ++c) {
      const auto coef = dist_.coefficients(c, y);
      for (int k = 0; k < nb; ++k) sigma[k] = y[L.index(c, dist_.bin_slot(k))];
      engine.jacobian(coef, sigma, {}, dense);
      std::fill(cut.begin(), cut.end(), 0.0);
      std::fill(below.begin(), below.end(), 0.0);
      const auto at = [&](int k, int i) -> double& {
        return jac[static_cast<std::size_t>(
            pos_[(static_cast<std::size_t>(c) * nb + k) * nb + i])];
      };
      for (int i = 0; i < nb; ++i) {
        cut[i] = sigma[i];
        engine.rhs(coef, cut, {}, upto, {});
        for (int k = 0; k < nb; ++k) {
          const double s_i = upto[k] - below[k];
          const bool noise =
              std::abs(s_i) <= 1e-13 * std::max(std::abs(upto[k]), std::abs(below[k]));
          const double jp = (sigma[i] != 0.0 && !noise) ? s_i / sigma[i] : 0.0;
          at(k, i) += jp - dense[static_cast<std::size_t>(k) * nb + i];
          if (!checked_) before_[static_cast<std::size_t>(k) * nb + i] = at(k, i) - jp;
        }
        below = upto;
      }
      // J_P sigma = S_coag up to the dropped round-off (checked at the first call)
      if (!checked_) {
        double scale = 0.0;
        for (int k = 0; k < nb; ++k) scale = std::max(scale, std::abs(upto[k]));
        for (int k = 0; k < nb; ++k) {
          double js = 0.0;
          for (int i = 0; i < nb; ++i)
            js += (at(k, i) - before_[static_cast<std::size_t>(k) * nb + i]) * sigma[i];
          worst_ = std::max(worst_, scale > 0.0 ? std::abs(js - upto[k]) / scale : 0.0);
        }
      }
    }
    if (!checked_)
      std::printf(
          "J_P sigma against S_coag: largest deviation %.2e of a cell's largest "
          "rate\n",
          worst_);
    checked_ = true;
  }

 private:
  const Simulation& sim_;
  const SizeDistribution& dist_;
  int n_cells_;
  std::vector<long> pos_;
  mutable std::vector<double> before_;  // the block less J_P (the check)
  mutable bool checked_ = false;
  mutable double worst_ = 0.0;
};

//! One linearly implicit Euler step of dt from (t, y) on the Jacobian `jac` (the
//! integrator's arithmetic; no halving: a singular matrix ends the run).
void own_step(BlockBandedLU& lu, const std::vector<std::size_t>& diag,
              std::vector<double>& jac, std::span<const double> f, double dt,
              std::vector<double>& y) {
  newton_matrix(jac, diag, dt, jac);
  std::vector<double> delta(f.size());
  for (std::size_t i = 0; i < f.size(); ++i) delta[i] = dt * f[i];
  if (!lu.factorize(jac) || !lu.solve(delta))
    throw std::runtime_error("bench_ie_steps: the Newton matrix is singular");
  for (std::size_t i = 0; i < y.size(); ++i) y[i] += delta[i];
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr,
                 "usage: %s SCENE [--set k=v ...] [--no-gas] [--edge N] [--floor-reset] "
                 "[--picard [--picard-cells K]] [--own] [--window-yr T] [--log FILE] "
                 "[--log-from-yr T]\n",
                 argv[0]);
    return 2;
  }
  const Args a = parse(argc, argv);
  Simulation sim(load_scene(a.scene, a.sets));
  DiskModel& model = sim.model();
  const StateLayout& L = model.layout();
  IntegratorOptions opt = sim.integrator_options();
  // the rule's components: DustPy's floors, less those a variant leaves out
  std::vector<double> rule_floor = opt.step_floor;
  const std::vector<double> floor = opt.step_floor;
  for (long i = 0; i < L.size(); ++i) {
    const int c = L.cell_of(i);
    const bool gas = L.info_of(i).name == "sigma_g";
    if ((a.no_gas && gas) || (c >= 0 && (c < a.edge || c >= L.n_cells() - a.edge)))
      rule_floor[static_cast<std::size_t>(i)] = kInf;
  }
  opt.step_floor = rule_floor;
  const bool own = a.own || a.floor_reset || a.picard;
  const auto reset = [&](std::vector<double>& y) {
    for (long i = 0; i < L.size(); ++i) {
      const auto u = static_cast<std::size_t>(i);
      if (std::isfinite(floor[u]) && L.info_of(i).name != "sigma_g" && y[u] <= floor[u])
        y[u] = 0.1 * floor[u];
    }
  };
  const std::vector<double> times = sim.output_times();
  std::vector<double> y = sim.initial_state();
  if (a.floor_reset) reset(y);
  sim.refresh_local_gas(y);
  ImplicitEulerIntegrator ie(model, times.front(), y, opt);
  BlockBandedLU lu(model.pattern(), L.n_cells(), L.n_cell_vars());
  const std::vector<std::size_t> diag = model.pattern().diagonal_positions();
  std::vector<double> f(y.size()), jac(static_cast<std::size_t>(model.pattern().nnz()));
  std::unique_ptr<PicardMatrix> picard;
  if (a.picard) picard = std::make_unique<PicardMatrix>(sim, a.picard_cells);

  FILE* log = a.log.empty() ? nullptr : std::fopen(a.log.c_str(), "w");
  if (log) std::fprintf(log, "step,t_yr,dt_yr,cell,variable,value,value_over_floor\n");
  std::map<std::pair<std::string, int>, long> limits;  // (variable, cell) -> steps
  std::map<std::string, long> limits_by_var;
  long nst = 0;
  double t = times.front();
  const auto record = [&](double t_new, double dt, long lim,
                          std::span<const double> ynow) {
    ++nst;
    if (t_new / units::kYr <= a.window_yr) return;
    const int cell = lim >= 0 ? L.cell_of(lim) : -1;
    const std::string var = lim >= 0 ? L.info_of(lim).name : "(output time)";
    ++limits[{var, cell}];
    ++limits_by_var[var != "sigma_g" && var.rfind("sigma_", 0) == 0 ? "sigma_k" : var];
    if (log && t_new / units::kYr > a.log_from_yr) {
      const double v = lim >= 0 ? ynow[static_cast<std::size_t>(lim)] : 0.0;
      const double fl = lim >= 0 ? floor[static_cast<std::size_t>(lim)] : 1.0;
      std::fprintf(log, "%ld,%.6e,%.6e,%d,%s,%.6e,%.6e\n", nst, t_new / units::kYr,
                   dt / units::kYr, cell, var.c_str(), v, v / fl);
    }
  };
  const double cpu0 = static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
  std::printf("| t [yr] | steps |\n|---|---|\n");
  for (std::size_t k = 1; k < times.size(); ++k) {
    if (!own) {
      double t_prev = t;
      ie.advance_to(times[k], [&](double tn, long) {
        record(tn, tn - t_prev, ie.limiting_component(), ie.state());
        t_prev = tn;
      });
      y.assign(ie.state().begin(), ie.state().end());
    } else {
      while (t < times[k]) {
        model.rhs(t, y, f);
        long lim = -1;
        double dt = ImplicitEulerIntegrator::step_size(y, f, rule_floor, opt.cfl, &lim);
        const bool to_output = dt >= times[k] - t;
        if (to_output) {
          dt = times[k] - t;
          lim = -1;
        }
        model.jacobian(t, y, jac);
        if (picard) picard->apply(y, jac);
        own_step(lu, diag, jac, f, dt, y);
        const double t_new = to_output ? times[k] : std::min(t + dt, times[k]);
        if (a.floor_reset) reset(y);
        record(t_new, dt, lim, y);
        t = t_new;
      }
    }
    t = times[k];
    std::printf("| %.4g | %ld |\n", times[k] / units::kYr, nst);
    std::fflush(stdout);
    sim.refresh_local_gas(y);  // as panoptic run (solver.reinit_at_snapshots)
    if (!own) ie.reinit(t, y);
  }
  if (log) std::fclose(log);
  std::printf("\nCPU %.1f s. After %.4g yr the steps were set by (%zu kinds):\n",
              static_cast<double>(std::clock()) / CLOCKS_PER_SEC - cpu0, a.window_yr,
              limits.size());
  for (const auto& [var, n] : limits_by_var)
    std::printf("  %s: %ld steps\n", var.c_str(), n);
  std::vector<std::pair<long, std::pair<std::string, int>>> top;
  for (const auto& [key, n] : limits) top.emplace_back(n, key);
  std::sort(top.rbegin(), top.rend());
  std::printf("| variable | cell | steps |\n|---|---|---|\n");
  for (std::size_t i = 0; i < std::min<std::size_t>(top.size(), 15); ++i)
    std::printf("| %s | %d | %ld |\n", top[i].second.first.c_str(), top[i].second.second,
                top[i].first);
  return 0;
}
