// Why CVODE's Newton iteration fails on a scene (not a test; written for the porous
// size-distribution runs, tests/bench/results/porous_newton.md). Integrates the scene
// as `panoptic run` does (CVODE reinitialised at every snapshot) and prints the solver
// counters per snapshot interval with the CPU time, and the wall time spent in CVODE's
// callbacks at the end. With --limiting 1, the components whose weighted local error
// was the largest, with the number of steps each. With --probe N, at the first N steps
// that followed a Newton convergence failure it keeps the state, and afterwards, at each:
// * the bins whose sigma or psi is <= 0 or whose psi/sigma < 1 (phi > 1);
// * the implicit-Euler Newton iteration y = y0 + h f(y) from the predictor y0 + h y0'
//   (y0' CVODE's derivative), h = the failed step (4x the step that then passed), with
//   the model's Jacobian and with a central finite-difference Jacobian of the whole RHS
//   (columns coloured by cell mod 3): the weighted RMS norm of each Newton correction,
//   so that their ratio (the contraction) tells whether the Jacobian or the equations
//   stop Newton; then full Newton (the model's Jacobian at every iterate) and 12
//   iterations of the modified one, each with the components of its last correction and
//   their bins' sigma, u, z = ln floor + ln u and r h (the floor's relaxation rate times
//   the step) at the start and at the last iterate;
// * the largest entries of h (J - J_fd) in the error weights' units, by variable.
// Usage: build/tests/bench_porous_newton SCENE [--set key=value ...] [--probe N]
//        [--every K] (probe every K-th failure) [--threads T] (worker threads,
//        src/core/worker_threads.hpp: the CPU time is then that of all threads)
//        [--limiting 1] [--lts 1] (what local time stepping could save at best:
//        tests/bench/lts_estimate.hpp); or --restart CHK.h5 instead of SCENE: from a
//        checkpoint's state and time on, with its stored scene (--set may change the
//        output times and the solver, as `panoptic run --restart`), to the scene's
//        snapshot times after it
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "physics/modules/dust_face_flux.hpp"
#include "physics/modules/dust_transport.hpp"
#include "physics/modules/size_distribution.hpp"
#include "src/core/units.hpp"
#include "src/core/worker_threads.hpp"
#include "src/model/scene_validation.hpp"
#include "src/model/simulation.hpp"
#include "src/run/restart.hpp"
#include "src/scene/config.hpp"
#include "src/solver/block_banded_lu.hpp"
#include "src/solver/cvode_integrator.hpp"
#include "tests/bench/lts_estimate.hpp"

using namespace panoptic;

namespace {

double cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

struct Probe {
  double t = 0.0, h = 0.0;
  std::vector<double> y, ydot;
};

//! Central-difference Jacobian of the model's RHS at y on the pattern's entries
//! (CSC order); columns of cells i = c mod 3 perturbed together (the pattern couples a
//! cell to its neighbours only: checked; globals alone). Returns the entries the FD
//! finds outside the pattern (count).
long fd_jacobian(const DiskModel& model, const std::vector<double>& y0,
                 std::vector<double>& values) {
  const SparsityPattern& p = model.pattern();
  const StateLayout& L = model.layout();
  const long n = p.size();
  const int nv = L.n_cell_vars(), nc = L.n_cells();
  const auto col_ptr = p.col_ptr();
  const auto rows = p.row_index();
  values.assign(static_cast<std::size_t>(p.nnz()), 0.0);
  std::vector<double> y = y0, fp(n), fm(n), h(n);
  for (long j = 0; j < n; ++j) h[j] = y0[j] != 0.0 ? 1e-6 * std::abs(y0[j]) : 1e-40;
  std::vector<long> row_owner(n, -1);
  long outside = 0;
  auto run_color = [&](const std::vector<long>& cols) {
    for (long j : cols) y[j] = y0[j] + h[j];
    model.rhs(0.0, y, fp);
    for (long j : cols) y[j] = y0[j] - h[j];
    model.rhs(0.0, y, fm);
    for (long j : cols) y[j] = y0[j];
    std::fill(row_owner.begin(), row_owner.end(), -1);
    for (long j : cols)
      for (auto k = col_ptr[j]; k < col_ptr[j + 1]; ++k) {
        if (row_owner[rows[k]] >= 0) std::fprintf(stderr, "colouring conflict\n");
        row_owner[rows[k]] = j;
      }
    for (long j : cols)
      for (auto k = col_ptr[j]; k < col_ptr[j + 1]; ++k)
        values[k] = (fp[rows[k]] - fm[rows[k]]) / (2.0 * h[j]);
    for (long r = 0; r < n; ++r)
      if (row_owner[r] < 0 && fp[r] != fm[r]) ++outside;
  };
  for (int v = 0; v < nv; ++v)
    for (int c0 = 0; c0 < 3; ++c0) {
      std::vector<long> cols;
      for (int i = c0; i < nc; i += 3) cols.push_back(L.index(i, v));
      run_color(cols);
    }
  for (long j = static_cast<long>(nc) * nv; j < n; ++j) run_color({j});
  return outside;
}

//! The bin of a distribution's state variable i: its cell, its index k and the indices
//! of its sigma_k and psi_k.
struct BinOf {
  int cell = 0, k = 0;
  long sigma = 0, psi = 0;
};
BinOf bin_of(const StateLayout& L, const SizeDistribution& d, long i) {
  BinOf b;
  b.cell = static_cast<int>(i / L.n_cell_vars());
  b.k = static_cast<int>(i % L.n_cell_vars() - d.bin_slot(0)) % d.n_bins();
  b.sigma = L.index(b.cell, d.bin_slot(b.k));
  b.psi = L.index(b.cell, d.psi_slot(b.k));
  return b;
}

//! Implicit Euler from y0 over h by Newton with the Jacobian `jac` (fixed, evaluated at
//! the predictor): the weighted RMS norm of each correction.
std::vector<double> newton_corrections(const DiskModel& model, const Probe& pr,
                                       const std::vector<double>& jac,
                                       const std::vector<double>& w, int iters,
                                       bool show_stuck = false, bool refresh = false,
                                       const Simulation* sim = nullptr) {
  const SparsityPattern& p = model.pattern();
  const StateLayout& L = model.layout();
  const long n = p.size();
  const auto col_ptr = p.col_ptr();
  const auto rows = p.row_index();
  std::vector<double> m(jac.size());
  for (long c = 0; c < n; ++c)
    for (auto k = col_ptr[c]; k < col_ptr[c + 1]; ++k)
      m[k] = (rows[k] == c ? 1.0 : 0.0) - pr.h * jac[k];
  BlockBandedLU lu(p, L.n_cells(), L.n_cell_vars());
  std::vector<double> out;
  if (!lu.factorize(m)) return out;
  std::vector<double> y(n), f(n), d(n);
  for (long i = 0; i < n; ++i) y[i] = pr.y[i] + pr.h * pr.ydot[i];
  std::vector<double> jnow(jac.size());
  for (int it = 0; it < iters; ++it) {
    if (refresh && it > 0) {  // full Newton: the Jacobian at the iterate
      model.jacobian(pr.t + pr.h, y, jnow);
      for (long c = 0; c < n; ++c)
        for (auto k = col_ptr[c]; k < col_ptr[c + 1]; ++k)
          m[k] = (rows[k] == c ? 1.0 : 0.0) - pr.h * jnow[k];
      if (!lu.factorize(m)) break;
    }
    model.rhs(pr.t + pr.h, y, f);
    for (long i = 0; i < n; ++i) d[i] = -(y[i] - pr.y[i] - pr.h * f[i]);
    if (!lu.solve(d)) break;
    double s = 0.0;
    for (long i = 0; i < n; ++i) {
      y[i] += d[i];
      s += (d[i] * w[i]) * (d[i] * w[i]);
    }
    out.push_back(std::sqrt(s / static_cast<double>(n)));
  }
  if (show_stuck) {  // the components of the last correction, largest weighted first
    std::vector<std::pair<double, long>> v;
    for (long i = 0; i < n; ++i) v.push_back({std::abs(d[i] * w[i]), i});
    std::sort(v.rbegin(), v.rend());
    const auto* dist = sim != nullptr ? sim->distribution() : nullptr;
    for (int q = 0; q < 8; ++q) {
      const long i = v[q].second;
      std::printf("      last correction %.2e (weighted) in %s: y0 %.4e, iterate %.4e\n",
                  v[q].first, L.describe(i).c_str(), pr.y[i], y[i]);
      if (dist == nullptr || !dist->porous()) continue;
      const BinOf b = bin_of(L, *dist, i);
      auto show = [&](const char* what, const std::vector<double>& yy) {
        const auto c = dist->coefficients(b.cell, yy);
        const double u = dist->porosity(b.cell, b.k, yy).u;  // bin_porosity's rule
        const double z = c.ln_phi_floor.empty() ? 0.0 : c.ln_phi_floor[b.k] + std::log(u);
        std::printf("        %s: sigma %.4e u %.4e z %.4e r*h %.3e\n", what, yy[b.sigma],
                    u, z, c.relax_rate.empty() ? 0.0 : c.relax_rate[b.k] * pr.h);
      };
      show("y0  ", pr.y);
      show("iter", y);
    }
  }
  return out;
}

void print_norms(const char* what, const std::vector<double>& d) {
  std::printf("    %-22s", what);
  for (std::size_t k = 0; k < d.size(); ++k) std::printf(" %.2e", d[k]);
  std::printf("   ratios");
  for (std::size_t k = 1; k < d.size(); ++k)
    std::printf(" %.2f", d[k - 1] > 0.0 ? d[k] / d[k - 1] : 0.0);
  std::printf("\n");
}

void analyse(const Simulation& sim, const Probe& pr, const IntegratorOptions& opt) {
  const DiskModel& model = sim.model();
  const StateLayout& L = model.layout();
  const SparsityPattern& p = model.pattern();
  const long n = p.size();
  std::vector<double> w(n);
  for (long i = 0; i < n; ++i) w[i] = 1.0 / (opt.rtol * std::abs(pr.y[i]) + opt.atol[i]);
  const auto* d = sim.distribution();
  int neg_sigma = 0, neg_psi = 0, phi_above_1 = 0;
  if (d != nullptr && d->porous())
    for (int i = 0; i < L.n_cells(); ++i)
      for (int k = 0; k < d->n_bins(); ++k) {
        const double s = pr.y[L.index(i, d->bin_slot(k))];
        const double q = pr.y[L.index(i, d->psi_slot(k))];
        neg_sigma += s <= 0.0;
        neg_psi += q <= 0.0;
        phi_above_1 += s > 0.0 && q > 0.0 && q < s;
      }
  std::printf(
      "  probe t = %.6g yr, h = %.3g s: bins with sigma <= 0: %d, psi <= 0: %d, "
      "0 < psi < sigma: %d\n",
      pr.t / units::kYr, pr.h, neg_sigma, neg_psi, phi_above_1);
  std::vector<double> yp(n);
  for (long i = 0; i < n; ++i) yp[i] = pr.y[i] + pr.h * pr.ydot[i];
  std::vector<double> ja(static_cast<std::size_t>(p.nnz())), jf;
  model.jacobian(pr.t + pr.h, yp, ja);
  const double t0 = cpu_seconds();
  const long outside = fd_jacobian(model, yp, jf);
  std::printf("    FD Jacobian: %.1f s CPU, %ld entries outside the pattern\n",
              cpu_seconds() - t0, outside);
  print_norms("Newton, model J:", newton_corrections(model, pr, ja, w, 6));
  print_norms("full Newton, model J:",
              newton_corrections(model, pr, ja, w, 12, true, true, &sim));
  print_norms("Newton, model J, 12:",
              newton_corrections(model, pr, ja, w, 12, true, false, &sim));
  print_norms("Newton, FD J:", newton_corrections(model, pr, jf, w, 6, true));
  // largest h |J - J_fd|_ij w_i / w_j
  struct Entry {
    double e;
    long r, c;
    double a, f;
  };
  std::vector<Entry> top;
  const auto col_ptr = p.col_ptr();
  const auto rows = p.row_index();
  for (long c = 0; c < n; ++c)
    for (auto k = col_ptr[c]; k < col_ptr[c + 1]; ++k) {
      const double e = pr.h * std::abs(ja[k] - jf[k]) * w[rows[k]] / w[c];
      if (e > 1e-3) top.push_back({e, rows[k], c, ja[k], jf[k]});
    }
  std::sort(top.begin(), top.end(),
            [](const Entry& a, const Entry& b) { return a.e > b.e; });
  std::printf("    %zu entries with h |J - J_fd| w_r / w_c > 1e-3; largest:\n",
              top.size());
  for (std::size_t k = 0; k < top.size() && k < 12; ++k)
    std::printf("      %.2e  d(%s)/d(%s): J %.4e, FD %.4e; y_r %.3e, y_c %.3e\n",
                top[k].e, L.describe(top[k].r).c_str(), L.describe(top[k].c).c_str(),
                top[k].a, top[k].f, yp[top[k].r], yp[top[k].c]);
  if (!top.empty() && d != nullptr && d->porous()) {  // the worst entry's bin
    const BinOf b = bin_of(L, *d, top[0].r);
    const int cell = b.cell, k = b.k;
    const long is = b.sigma, ip = b.psi;
    auto show = [&](const char* what, const std::vector<double>& yy) {
      const auto c = d->coefficients(cell, yy);
      std::vector<double> f(n);
      model.rhs(0.0, yy, f);
      std::printf(
          "    %s: sigma %.6e psi %.6e; ln floor %.6e, relax %.6e, dpsi/dt %.6e\n", what,
          yy[is], yy[ip], c.ln_phi_floor.empty() ? 0.0 : c.ln_phi_floor[k],
          c.relax_rate.empty() ? 0.0 : c.relax_rate[k], f[ip]);
    };
    show("at yp", yp);
    std::vector<double> y2 = yp;
    y2[ip] *= 1.0 + 1e-6;
    show("psi*(1+1e-6)", y2);
    y2 = yp;
    y2[is] *= 1.0 + 1e-6;
    show("sigma*(1+1e-6)", y2);
    for (int other = 0; other < L.n_cells(); ++other) {
      if (other == cell) continue;
      y2 = yp;
      y2[L.index(other, d->psi_slot(k))] *= 1.0 + 1e-6;
      std::vector<double> f(n), f0(n);
      model.rhs(0.0, y2, f);
      model.rhs(0.0, yp, f0);
      if (f[ip] != f0[ip])
        std::printf("    psi_k of cell %d moves this row: %.6e -> %.6e\n", other, f0[ip],
                    f[ip]);
    }
  }
  if (!top.empty()) {  // the worst entry's row in full
    const long r = top[0].r;
    std::printf("    row %s, entries with |J| or |FD| y_c > 1e-3 of the row's largest:\n",
                L.describe(r).c_str());
    double big = 0.0;
    for (long c = 0; c < n; ++c) {
      const long k = p.position(r, c);
      if (k >= 0)
        big = std::max(big, std::max(std::abs(ja[k]), std::abs(jf[k])) * std::abs(yp[c]));
    }
    for (long c = 0; c < n; ++c) {
      const long k = p.position(r, c);
      if (k >= 0 &&
          std::max(std::abs(ja[k]), std::abs(jf[k])) * std::abs(yp[c]) > 1e-3 * big)
        std::printf("      d/d(%s): J %.4e, FD %.4e, y_c %.3e\n", L.describe(c).c_str(),
                    ja[k], jf[k], yp[c]);
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  const bool from_checkpoint = argc > 1 && std::string(argv[1]) == "--restart";
  if (argc < (from_checkpoint ? 3 : 2)) {
    std::fprintf(
        stderr,
        "usage: %s SCENE|--restart CHK.h5 [--set k=v ...] [--probe N] [--every K] "
        "[--threads T] [--limiting 1] [--lts 1]\n",
        argv[0]);
    return 2;
  }
  std::vector<std::string> sets;
  int n_probe = 0, every = 1;
  bool count_limiting = false, lts = false;
  for (int i = from_checkpoint ? 3 : 2; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--set")
      sets.emplace_back(argv[i + 1]);
    else if (a == "--probe")
      n_probe = std::stoi(argv[i + 1]);
    else if (a == "--every")
      every = std::stoi(argv[i + 1]);
    else if (a == "--limiting")
      count_limiting = std::stoi(argv[i + 1]) != 0;
    else if (a == "--lts")
      lts = std::stoi(argv[i + 1]) != 0;
    else if (a == "--threads")
      set_worker_threads(std::stoi(argv[i + 1]));
  }
  std::optional<RestartPoint> restart;
  if (from_checkpoint) restart = load_restart_point(argv[2]);
  const Config cfg =
      restart ? checkpoint_scene(*restart, sets) : load_scene(argv[1], sets);
  validate_scene(cfg);  // as panoptic run: a --set that the scene or checkpoint refuses
  Simulation sim(cfg);
  if (restart) check_compatible(restart->chk, restart->path, cfg, sim.model().layout());
  const IntegratorOptions opt = sim.integrator_options();
  const std::vector<double> times =
      restart ? times_after_restart(sim.output_times(), restart->chk.t)
              : sim.output_times();
  std::vector<double> y = restart ? restart->chk.y : sim.initial_state();
  sim.refresh_local_gas(y);  // as panoptic run (the particle laws' eta and v_g)
  CvodeIntegrator cvode(sim.model(), times.front(), y, opt);
  CallbackTimes cb;
  cvode.set_profile(&cb);
  std::vector<Probe> probes;
  std::map<std::string, long> limiting_kind;  // steps by variable kind ("psi", "sigma_g")
  // the module that carries the dust: a cell's Sigma_d for the estimate
  const DustCarrier& dust = sim.distribution() != nullptr
                                ? static_cast<const DustCarrier&>(*sim.distribution())
                                : sim.transport();
  bench::LtsEstimate estimate(sim.model().layout());
  std::vector<double> sigma_d(static_cast<std::size_t>(sim.grid().n_cells()));
  long last_nncf = 0, failures_seen = 0;
  SolverStats prev;
  double cpu0 = cpu_seconds(), cpu_prev = cpu0;
  std::printf(
      "| t [yr] | steps | RHS | Jacobians | Newton its | Newton failures | "
      "error-test failures | CPU [s] |\n|---|---|---|---|---|---|---|---|\n");
  for (std::size_t k = 1; k < times.size(); ++k) {
    std::map<long, int> limiting;  // steps each component limited (largest error)
    cvode.advance_to(times[k], [&](double t, long) {
      if (lts) {
        const auto info = cvode.step_info(0, true);
        for (std::size_t c = 0; c < sigma_d.size(); ++c)
          sigma_d[c] = dust.sigma_d(static_cast<int>(c), cvode.state());
        estimate.add(info.weighted_errors, info.h_last, info.order_last,
                     times[k] - times[k - 1], sigma_d);
      }
      if (count_limiting) {
        const auto info = cvode.step_info(1);
        if (!info.largest_errors.empty()) {
          const long i = info.largest_errors[0].first;
          ++limiting[i];
          const std::string& name = sim.model().layout().info_of(i).name;
          const auto digit = name.find_last_not_of("0123456789");
          ++limiting_kind[name.back() >= '0' && name.back() <= '9' &&
                                  digit != name.size() - 1
                              ? name.substr(0, digit)
                              : name];
        }
      }
      const long nncf = cvode.stats().nncf;
      if (nncf == last_nncf) return;
      last_nncf = nncf;
      if (failures_seen++ % every != 0 || static_cast<int>(probes.size()) >= n_probe)
        return;
      Probe pr;
      pr.t = t;
      pr.h = 4.0 * cvode.step_info(0).h_last;
      pr.y.assign(cvode.state().begin(), cvode.state().end());
      pr.ydot.resize(pr.y.size());
      cvode.derivative(pr.ydot);
      probes.push_back(std::move(pr));
    });
    const SolverStats s = cvode.stats();
    const double cpu = cpu_seconds();
    std::printf("| %.4g | %ld | %ld | %ld | %ld | %ld | %ld | %.1f |\n",
                times[k] / units::kYr, s.nst - prev.nst, s.nfe - prev.nfe,
                s.nje - prev.nje, s.nni - prev.nni, s.nncf - prev.nncf,
                s.netf - prev.netf, cpu - cpu_prev);
    if (count_limiting) {
      std::vector<std::pair<int, long>> v;
      for (const auto& [i, c] : limiting) v.push_back({c, i});
      std::sort(v.rbegin(), v.rend());
      for (std::size_t q = 0; q < v.size() && q < 6; ++q) {
        const auto& L = sim.model().layout();
        const long i = v[q].second;
        std::printf("    largest error in %d steps: %s = %.3e", v[q].first,
                    L.describe(i).c_str(), cvode.state()[i]);
        const std::string& name = L.info_of(i).name;
        if (name.rfind("psi_", 0) == 0)  // a bin's volume measure: with the bin's sigma
          if (const auto s = L.find_cell_var("sigma_" + name.substr(4));
              s && L.cell_of(i) >= 0)
            std::printf(" (%s = %.3e)", L.cell_var(*s).name.c_str(),
                        cvode.state()[L.index(L.cell_of(i), *s)]);
        std::printf("\n");
      }
    }
    std::fflush(stdout);
    prev = s;
    cpu_prev = cpu;
    y.assign(cvode.state().begin(), cvode.state().end());
    if (sim.config().flag("solver.reinit_at_snapshots")) {  // as panoptic run
      sim.refresh_local_gas(y);
      cvode.reinit(times[k], y);
    }
  }
  const SolverStats s = cvode.stats();
  std::printf(
      "total: %ld steps, %ld RHS, %ld Jacobians, %ld Newton iterations, %ld "
      "Newton failures, %ld error-test failures, %.1f s CPU; budget error %.1e\n",
      s.nst, s.nfe, s.nje, s.nni, s.nncf, s.netf, cpu_seconds() - cpu0,
      sim.budget_error(y));
  if (opt.linear == LinearSolverKind::gmres) {
    const KrylovStats ks = cvode.krylov_stats();
    std::printf(
        "GMRES: %ld iterations, %ld preconditioner solves, %ld convergence failures\n",
        ks.nli, ks.nps, ks.nlcf);
  }
  if (count_limiting) {
    std::printf("steps limited by (largest weighted local error):");
    for (const auto& [kind, n] : limiting_kind) std::printf(" %s %ld", kind.c_str(), n);
    std::printf("\n");
  }
  std::printf(
      "wall s in CVODE's callbacks (calls): RHS %.2f (%ld), Jacobian %.2f (%ld), "
      "linear set-up %.2f (%ld), linear solve %.2f (%ld)\n",
      cb.rhs_s, cb.n_rhs, cb.jac_s, cb.n_jac, cb.lsetup_s, cb.n_lsetup, cb.lsolve_s,
      cb.n_lsolve);
  if (lts) estimate.print(s.nst);
  for (const Probe& pr : probes) analyse(sim, pr, opt);
  return 0;
}
