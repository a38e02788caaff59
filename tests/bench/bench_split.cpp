// Benchmark (not a test): how large the operator-splitting error of the fiducial scene
// is, for the multirate question of issues 3 and 7 (tests/bench/README.md, "Performance":
// a scheme that steps each cell's local physics with its own step size would need few
// transport steps, fewer than ~500 per Myr, to beat the coupled system). Strang splitting
//   L(dt/2) T(dt) L(dt/2),  L = porous growth + planetesimals (cell-local),
//                           T = dust transport (drift, diffusion, snow line, bookings),
// each stage integrated by its own CVODE (same rtol, restarted at every stage), over M
// macro steps log-spaced in time from t_1 to t_end. Compared with the coupled system
// (as `panoptic run` integrates it) on the same grid and tolerance: the planetesimal
// mass, the pebble mass through the snow line, and Sigma_d at t_end (L1 over the cells,
// mass-weighted). Here both stages are still global CVODE integrations, so the cost
// printed is not that of a multirate code; only the splitting error is measured.
// Usage: build/tests/bench_split [--macro M ...] [--t1-yr T] [--set key=value ...]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include "src/core/units.hpp"
#include "src/model/simulation.hpp"
#include "src/scene/config.hpp"
#include "src/solver/cvode_integrator.hpp"
#include "src/solver/grid.hpp"
#include "tests/bench/fiducial_outcome.hpp"

using namespace panoptic;

namespace {

struct Outcome : FiducialOutcome {
  long steps_l = 0, steps_t = 0;
  double wall = 0.0;
};

Outcome measure(const Simulation& sim, std::span<const double> y) {
  return {measure_outcome(sim, y)};
}

Outcome coupled(Simulation& sim) {
  const auto times = sim.output_times();
  const auto y0 = sim.initial_state();
  const auto t0 = std::chrono::steady_clock::now();
  CvodeIntegrator cvode(sim.model(), times.front(), y0, sim.integrator_options());
  for (std::size_t k = 1; k < times.size(); ++k) {
    cvode.advance_to(times[k]);
    const std::vector<double> y(cvode.state().begin(), cvode.state().end());
    cvode.reinit(times[k], y);
  }
  Outcome o = measure(sim, cvode.state());
  o.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  o.steps_l = cvode.stats().nst;
  return o;
}

Outcome split(Simulation& sim, int macro, double t1) {
  DiskModel& model = sim.model();
  const auto local = [](std::string_view n) {
    return n == "porous_growth" || n == "planetesimals";
  };
  const auto transport = [&](std::string_view n) { return !local(n); };
  const double t_end = sim.output_times().back();
  std::vector<double> tb{0.0};
  for (int k = 0; k < macro; ++k)
    tb.push_back(t1 * std::pow(t_end / t1, double(k) / double(macro - 1)));
  std::vector<double> y = sim.initial_state();
  const auto t0 = std::chrono::steady_clock::now();
  CvodeIntegrator cl(model, 0.0, y, sim.integrator_options());
  CvodeIntegrator ct(model, 0.0, y, sim.integrator_options());
  for (std::size_t k = 1; k < tb.size(); ++k) {
    const double ta = tb[k - 1], tm = 0.5 * (tb[k - 1] + tb[k]), te = tb[k];
    model.set_active(local);
    cl.reinit(ta, y);
    cl.advance_to(tm);
    y.assign(cl.state().begin(), cl.state().end());
    model.set_active(transport);
    ct.reinit(ta, y);
    ct.advance_to(te);
    y.assign(ct.state().begin(), ct.state().end());
    model.set_active(local);
    cl.reinit(tm, y);
    cl.advance_to(te);
    y.assign(cl.state().begin(), cl.state().end());
  }
  model.set_active(nullptr);
  Outcome o = measure(sim, y);
  o.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  o.steps_l = cl.stats().nst;
  o.steps_t = ct.stats().nst;
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> macros;
  double t1_yr = 1.0;
  std::vector<std::string> sets;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--macro") && i + 1 < argc) {
      macros.push_back(std::atoi(argv[++i]));
    } else if (!std::strcmp(argv[i], "--t1-yr") && i + 1 < argc) {
      t1_yr = std::atof(argv[++i]);
    } else if (!std::strcmp(argv[i], "--set") && i + 1 < argc) {
      sets.emplace_back(argv[++i]);
    } else {
      std::fprintf(
          stderr,
          "usage: bench_split [--macro M ...] [--t1-yr T] [--set key=value ...]\n");
      return 2;
    }
  }
  if (macros.empty()) macros = {100, 300, 1000, 3000};
  const std::string scene = std::string(PANOPTIC_SOURCE_DIR) + "/params/fiducial.toml";
  const Config cfg = load_scene(scene, sets);
  Simulation sim(cfg);
  const Outcome ref = coupled(sim);
  const Grid& g = sim.grid();
  std::printf("params/fiducial.toml to %g yr, %d cells", cfg.real("output.t_end_yr"),
              static_cast<int>(cfg.integer("grid.n_cells")));
  for (const auto& s : sets) std::printf(", %s", s.c_str());
  std::printf(
      "\ncoupled: %ld steps, %.2f s; m_pl = %.5g M_earth, pebbles through the snow "
      "line %.5g M_earth\n\n",
      ref.steps_l, ref.wall, ref.m_pl, ref.m_peb_snow);
  std::printf(
      "| macro steps | first [yr] | L steps | T steps | wall [s] | m_pl error | "
      "m_peb_snow error | Sigma_d(t_end) L1 |\n|---|---|---|---|---|---|---|---|\n");
  for (int m : macros) {
    const Outcome o = split(sim, m, t1_yr * units::kYr);
    std::printf("| %d | %g | %ld | %ld | %.2f | %.2e | %.2e | %.2e |\n", m, t1_yr,
                o.steps_l, o.steps_t, o.wall, std::abs(o.m_pl / ref.m_pl - 1.0),
                std::abs(o.m_peb_snow / ref.m_peb_snow - 1.0),
                sigma_l1(g, o.sigma_d, ref.sigma_d));
    std::fflush(stdout);
  }
  return 0;
}
