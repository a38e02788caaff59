// panoptic: dust evolution of a whole protoplanetary disk. The program as a numbered
// script (Athena++ style):
//   1 command line -> 2 scene (file < --set overrides), validated before anything is
//   written -> 3 grid, gas disk, modules, state layout (Simulation) -> 4 output file ->
//   5 CVODE -> 6 loop over the snapshot times -> 7 solver statistics and mass budget.
// Exit codes: 0 ok, 2 bad input, 3 solver failure, 4 I/O error, 130 interrupted.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "src/config.hpp"
#include "src/cvode_integrator.hpp"
#include "src/error.hpp"
#include "src/run_output.hpp"
#include "src/simulation.hpp"
#include "src/units.hpp"

namespace fs = std::filesystem;
using namespace panoptic;

namespace {

std::atomic<int> g_signal{0};
extern "C" void on_signal(int sig) { g_signal = sig; }

struct Interrupted {
  int signal;
};

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

//! One status line on a terminal, overwritten in place; nothing when stdout is a file.
class Progress {
 public:
  Progress(double t_end)
      : t_end_(t_end), tty_(isatty(STDOUT_FILENO)), start_(Clock::now()) {}
  void update(double t, long nst) {
    if (!tty_) return;
    const double wall = seconds_since(start_);
    if (wall - last_ < 0.2) return;
    last_ = wall;
    // progress in log time: snapshots and the work are spread roughly evenly in log t
    const double t_ref = 1e2 * units::kYr;
    const double frac = std::log1p(t / t_ref) / std::log1p(t_end_ / t_ref);
    const double eta = frac > 1e-3 ? wall * (1.0 - frac) / frac : NAN;
    std::printf("\r  t = %.3e yr  (%5.1f%%)  steps %ld  wall %.1f s  ETA %.0f s   ",
                t / units::kYr, 100.0 * frac, nst, wall, eta);
    std::fflush(stdout);
  }
  void done() {
    if (tty_ && last_ > 0.0) std::printf("\n");
  }

 private:
  double t_end_;
  bool tty_;
  Clock::time_point start_;
  double last_ = 0.0;
};

fs::path default_output(const Config& cfg) {
  if (!cfg.str("output.file").empty()) return cfg.str("output.file");
  return fs::path("out") / (cfg.file().stem().string() + ".h5");
}

void print_budget(const Simulation& sim, std::span<const double> y) {
  const double m0 = sim.initial_dust_mass();
  const double grid = sim.dust_mass_on_grid(y), out = sim.dust_mass_out(y);
  std::printf(
      "dust budget [M_earth]: on grid %.6g + through r_in %.6g = %.6g; initial %.6g;"
      " relative error %.2e\n",
      grid / units::kMearth, out / units::kMearth, (grid + out) / units::kMearth,
      m0 / units::kMearth, std::abs(grid + out - m0) / m0);
}

int run(const std::string& scene, const std::vector<std::string>& overrides,
        const std::string& out_opt, bool overwrite) {
  // 2 scene
  const Config cfg = load_scene(scene, overrides);
  validate_scene(cfg);
  // 3 model
  Simulation sim(cfg);
  const fs::path out_path = out_opt.empty() ? default_output(cfg) : fs::path(out_opt);
  // 4 output
  RunOutput out(out_path, overwrite,
                {cfg.file().stem().string(), cfg.resolved_toml(), PANOPTIC_GIT_SHA,
                 PANOPTIC_VERSION});
  sim.prepare_output(out);
  std::printf("panoptic %s: scene %s -> %s\n%s", PANOPTIC_VERSION, scene.c_str(),
              out_path.c_str(), sim.summary().c_str());
  std::fflush(stdout);
  // 5 integrator
  const auto times = sim.output_times();
  const auto y0 = sim.initial_state();
  CvodeIntegrator cvode(sim.model(), times.front(), y0, sim.integrator_options());
  out.write_snapshot(0.0, sim.snapshot_fields(y0));
  // 6 snapshots
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  const auto start = Clock::now();
  Progress progress(times.back());
  std::string status = "completed";
  int code = 0;
  try {
    for (std::size_t k = 1; k < times.size(); ++k) {
      cvode.advance_to(times[k], [&](double t, long nst) {
        if (g_signal != 0) throw Interrupted{g_signal};
        progress.update(t, nst);
      });
      out.write_snapshot(times[k] / units::kYr, sim.snapshot_fields(cvode.state()));
    }
  } catch (const Interrupted& i) {
    status = "interrupted by signal " + std::to_string(i.signal);
    code = 130;
  } catch (const SolverError&) {
    progress.done();
    out.write_solver(cvode.stats(), seconds_since(start), "failed");
    throw;
  }
  progress.done();
  // 7 statistics
  const double wall = seconds_since(start);
  const SolverStats s = cvode.stats();
  out.write_solver(s, wall, status);
  std::printf("%s at t = %.4g yr: %zu snapshots in %s\n", status.c_str(),
              cvode.time() / units::kYr, out.n_snapshots(), out_path.c_str());
  std::printf(
      "solver: %ld steps, %ld RHS, %ld Jacobian evaluations, %ld error-test and %ld "
      "nonlinear convergence failures, %.3f s wall\n",
      s.nst, s.nfe, s.nje, s.netf, s.nncf, wall);
  print_budget(sim, cvode.state());
  return code;
}

int check(const std::string& scene, const std::vector<std::string>& overrides) {
  const Config cfg = load_scene(scene, overrides);
  validate_scene(cfg);
  Simulation sim(cfg);
  std::printf("# scene %s is valid.\n", scene.c_str());
  std::string summary = sim.summary(), commented;
  for (std::size_t a = 0, b; a < summary.size(); a = b + 1) {
    b = summary.find('\n', a);
    if (b == std::string::npos) b = summary.size();
    commented += "# " + summary.substr(a, b - a) + "\n";
  }
  std::printf("%s\n%s", commented.c_str(), cfg.resolved_toml().c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  // 1 command line
  CLI::App app{
      "panoptic: dust evolution of a whole protoplanetary disk, from monomers to "
      "planetesimals"};
  app.set_version_flag("--version", std::string("panoptic ") + PANOPTIC_VERSION + " (" +
                                        PANOPTIC_GIT_SHA + ")");
  app.require_subcommand(1);
  std::string scene, out_opt;
  std::vector<std::string> overrides;
  bool overwrite = false;

  auto* run_cmd = app.add_subcommand("run", "run a scene and write its HDF5 output");
  run_cmd->add_option("scene", scene, "scene file (TOML)")->required();
  run_cmd->add_option("--set", overrides, "override a scene key: table.key=value")
      ->take_all();
  run_cmd->add_option("-o,--output", out_opt, "output file (default out/<scene>.h5)");
  run_cmd->add_flag("--overwrite", overwrite, "replace an existing output file");

  auto* check_cmd = app.add_subcommand(
      "check", "validate a scene and print it resolved, with defaults");
  check_cmd->add_option("scene", scene, "scene file (TOML)")->required();
  check_cmd->add_option("--set", overrides, "override a scene key: table.key=value")
      ->take_all();

  auto* ref_cmd = app.add_subcommand(
      "reference",
      "print every scene key with its default and unit (params/reference.toml)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return 2;
  }

  try {
    if (*run_cmd) return run(scene, overrides, out_opt, overwrite);
    if (*check_cmd) return check(scene, overrides);
    if (*ref_cmd) {
      std::fputs(reference_toml().c_str(), stdout);
      return 0;
    }
  } catch (const Error& e) {
    std::fprintf(stderr, "panoptic: error: %s\n", e.what());
    return e.exit_code();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "panoptic: internal error: %s\n", e.what());
    return 1;
  }
  return 0;
}
