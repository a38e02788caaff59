// panoptic: dust evolution of a whole protoplanetary disk. The program as a numbered
// script (Athena++ style):
//   1 command line -> 2 scene (file < --set overrides), validated before anything is
//   written -> 3 grid, gas disk, modules, state layout (Simulation) -> 4 restart point:
//   t = 0, or a checkpoint that is whole and that the scene is compatible with -> 5
//   output file (new, or the checkpoint's run's, continued) -> 6 CVODE -> 7 loop over the
//   snapshot times, checkpointing at snapshots -> 8 final checkpoint, solver statistics
//   and mass budget.
// Exit codes: 0 ok, 2 bad input, 3 solver failure, 4 I/O error, 75 stopped to be
// restarted (SIGINT, SIGTERM or --max-wall; EX_TEMPFAIL of sysexits.h: "try again").
#include <hdf5.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "build_info.hpp"  // PANOPTIC_GIT_SHA (generated at build time)
#include "src/core/error.hpp"
#include "src/core/exit_codes.hpp"
#include "src/core/signals.hpp"
#include "src/core/units.hpp"
#include "src/core/wall_clock.hpp"
#include "src/io/checkpoint.hpp"
#include "src/io/durable_file.hpp"
#include "src/io/run_output.hpp"
#include "src/model/output_table.hpp"
#include "src/model/simulation.hpp"
#include "src/model/track.hpp"
#include "src/observe/observe.hpp"
#include "src/run/diagnostics.hpp"
#include "src/scan/scan.hpp"
#include "src/scene/config.hpp"
#include "src/scene/presets.hpp"
#include "src/solver/cvode_integrator.hpp"

namespace fs = std::filesystem;
using namespace panoptic;

namespace {

//! Thrown to stop the run at the next step or snapshot, with why.
struct Stop {
  std::string reason;
};

//! One status line on a terminal, overwritten in place; nothing when stdout is a file.
class Progress {
 public:
  Progress(double t_end)
      : t_end_(t_end), tty_(isatty(STDOUT_FILENO)), start_(WallClock::now()) {}
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
  WallClock::time_point start_;
  double last_ = 0.0;
};

struct RunArgs {
  std::string program;  //!< argv[0], for the restart command we print
  std::string scene;
  std::vector<std::string> overrides;
  std::string output;  //!< -o
  bool overwrite = false;
  std::string restart;   //!< --restart CHK.h5
  std::string max_wall;  //!< --max-wall DURATION
  //! --max-wall was given, so that `--max-wall ""` (an unset variable) is refused
  bool max_wall_given = false;
  std::string preset;  //!< --fast / --accurate: "fast", "accurate" or ""
};

fs::path default_output(const Config& cfg) {
  if (!cfg.str("output.file").empty()) return cfg.str("output.file");
  return fs::path("out") / (cfg.file().stem().string() + ".h5");
}

//! A new output file with /grid, /disk and the snapshot fields declared. Checkpoints
//! left next to it by a run it replaces are removed (they belong to that run), with
//! --overwrite only, and only files panoptic wrote as checkpoints: anything else at
//! those paths, or a checkpoint without --overwrite, stops the run before a file is
//! touched (exit 4).
RunOutput new_output(const Config& cfg, const Simulation& sim, const fs::path& path,
                     bool overwrite) {
  const fs::path chk = checkpoint_path(path);
  std::error_code ec;
  for (const fs::path& p : {chk, previous_checkpoint_path(chk)}) {
    if (!fs::exists(fs::symlink_status(p, ec))) continue;
    if (!is_checkpoint_file(p))
      throw IoError(p.string() +
                    ": exists and is not a panoptic checkpoint, but a run writing " +
                    path.string() +
                    " keeps its checkpoints there; move that file or choose another -o");
    if (!overwrite)
      throw IoError(
          p.string() + ": a checkpoint of an earlier run to " + path.string() +
          (fs::exists(path, ec)
               ? "; continue that run with --restart " + chk.string() + ", or pass "
               : ", whose output is gone, so it cannot be continued; pass ") +
          "--overwrite to start a new one (the checkpoint is removed)");
  }
  RunOutput out(path, overwrite,
                {cfg.file().stem().string(), cfg.resolved_toml(), PANOPTIC_GIT_SHA,
                 PANOPTIC_VERSION});
  sim.prepare_output(out);
  for (const fs::path& stale : {chk, previous_checkpoint_path(chk)})
    if (fs::remove(stale, ec))
      std::printf("removed %s: a checkpoint of the run this output replaces\n",
                  stale.c_str());
  return out;
}

//! One warning per key the scene set that this run does not read (disk.r_c_au without
//! disk.model = "lbp"): to stderr, the exit code unchanged.
void warn_unused_keys(const Config& cfg) {
  if (const std::string w = empty_scene_warning(cfg); !w.empty())
    std::fprintf(stderr, "%s\n", w.c_str());
  for (const std::string& w : unused_key_warnings(cfg))
    std::fprintf(stderr, "%s\n", w.c_str());
}

//! The command that continues this run from `chk`, for copy and paste.
std::string restart_command(const RunArgs& a, const fs::path& chk) {
  const auto quote = [](const std::string& s) {
    if (s.find_first_of(" \t\"'$`\\*?[]()<>|;&!#~{}") == std::string::npos) return s;
    std::string q = "'";
    for (const char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
  };
  std::string cmd =
      quote(a.program) + " run " + quote(a.scene) + " --restart " + quote(chk.string());
  for (const std::string& s : a.overrides) cmd += " --set " + quote(s);
  if (!a.output.empty()) cmd += " -o " + quote(a.output);
  return cmd;
}

void print_budget(const Simulation& sim, std::span<const double> y) {
  const auto masses = sim.budget_masses(y);
  std::string terms;
  double total = 0.0;
  char buf[96];
  for (std::size_t k = 0; k < masses.size(); ++k) {
    std::snprintf(buf, sizeof buf, "%s%s %.6g", k ? " + " : "",
                  sim.budget_terms()[k].label.c_str(), masses[k] / units::kMearth);
    terms += buf;
    total += masses[k];
  }
  const double m0 = sim.initial_dust_mass();  // the error as Simulation::budget_error
  const double error = std::abs(total - m0) / m0;
  std::printf("dust budget [M_earth]: %s = %.6g; initial %.6g; relative error %.2e\n",
              terms.c_str(), total / units::kMearth, m0 / units::kMearth, error);
  // The terms are integrated with the state, so the budget closes to round-off (<= 7e-14
  // over every scene and the extremes matrix): more means a sink or source that is not
  // booked as a budget term, a bug of the model, not of the integration.
  if (!(error <= 1e-10))
    std::printf(
        "WARNING: the dust budget does not close (%.2e > 1e-10): some dust leaves or "
        "enters the grid without a budget term; a module's sink or source is not booked "
        "(README, Adding a physical process)\n",
        error);
}

int run(const RunArgs& a) {
  // 1 stop signals first: SIGINT or SIGTERM during the set-up (a restart's copy of a
  // large output takes a while) is then handled at the first step like any other, with
  // the checkpoint and exit 75, instead of killing the process before the handlers are
  // in place. A parent (panoptic scan) may have blocked them until now; a stop that
  // arrived meanwhile is delivered here.
  install_stop_handlers(SecondStop::kUnlessFromParent);
  block_stop_signals(false);
  // 2 scene
  const Config cfg = load_scene(a.scene, a.overrides);
  validate_scene(cfg);
  warn_unused_keys(cfg);
  const double max_wall = a.max_wall_given ? parse_duration(a.max_wall) : 0.0;
  // 3 model
  Simulation sim(cfg);
  const StateLayout& layout = sim.model().layout();
  // 4 restart point: a whole checkpoint (else its predecessor), compatible with the
  // scene; the snapshot times are then those of the scene after the checkpoint's time
  std::optional<RestartPoint> restart;
  std::vector<std::string> changed;
  if (!a.restart.empty()) {
    restart = load_restart_point(a.restart);
    if (!restart->fallback_note.empty())
      std::fprintf(stderr,
                   "panoptic: %s\npanoptic: restarting from the previous checkpoint %s "
                   "instead (t = %.6g yr, snapshot %ld)\n",
                   restart->fallback_note.c_str(), restart->path.c_str(),
                   restart->chk.t / units::kYr, restart->chk.snapshot_index);
    try {
      changed = check_compatible(restart->chk, restart->path, cfg, layout);
      // The keys a restart may change (output times, solver settings) change the run
      // silently otherwise: a restart without the stopped run's --set options would
      // continue it with the scene file's values.
      for (const std::string& c : changed)
        std::fprintf(stderr,
                     "panoptic: note: this restart changes %s (if not meant, restart "
                     "with the stopped run's --set options: the restart command it "
                     "printed)\n",
                     c.c_str());
    } catch (const ConfigError& e) {
      if (a.preset.empty()) throw;
      std::string sets;
      for (const std::string& s : preset_overrides(a.preset)) sets += " " + s;
      throw ConfigError(std::string(e.what()) + "\n(--" + a.preset + " sets" + sets +
                        ", shown above as --set: restart without --" + a.preset +
                        " to continue the run with its own grid and tolerances)");
    }
  }
  const std::vector<double> times =
      restart ? times_after_restart(sim.output_times(), restart->chk.t)
              : sim.output_times();
  // 5 output: new, or the checkpoint's run's file cut to the checkpoint's snapshots
  const fs::path out_path = a.output.empty() ? default_output(cfg) : fs::path(a.output);
  refuse_output_is_input(out_path, a.scene, "the scene the run reads");
  if (restart)
    refuse_output_is_input(out_path, restart->path, "the checkpoint it restarts from");
  RunOutput out = restart ? continue_output(*restart, a.output, cfg, changed)
                          : new_output(cfg, sim, out_path, a.overwrite);
  // a continued output's /grid, /disk and fields declared again: a field that the
  // restart's copy could not read is recreated (RunOutput::add_field)
  if (restart) sim.prepare_output(out);
  const fs::path chk_path = checkpoint_path(out.path());
  std::printf("panoptic %s: scene %s -> %s\n%s", PANOPTIC_VERSION, a.scene.c_str(),
              out.path().c_str(), sim.summary().c_str());
  if (restart)
    std::printf("restart from %s at t = %.6g yr (snapshot %ld)\n", restart->path.c_str(),
                restart->chk.t / units::kYr, restart->chk.snapshot_index);
  std::fflush(stdout);
  // 6 integrator, from the initial state or the checkpoint's (with its statistics)
  const std::vector<double> y0 = restart ? restart->chk.y : sim.initial_state();
  sim.refresh_local_gas(y0);  // eta and v_g of the particle laws (evolving gas)
  CvodeIntegrator cvode(sim.model(), times.front(), y0, sim.integrator_options());
  if (restart) cvode.carry_stats(restart->chk.stats);
  const long index0 = restart ? restart->chk.snapshot_index : 0;
  const double wall0 = restart ? restart->chk.wall_s : 0.0;
  const auto start = WallClock::now();
  // What a checkpoint of the snapshot just written holds; `last` is kept in memory so
  // that a stop between snapshots can checkpoint the last one. Its row digests are
  // filled in only when it is written (checkpoint_last), from the rows counted in
  // `last_rows` at its snapshot.
  const auto record = [&](double t, std::vector<double> y, long index) {
    return Checkpoint{t,
                      std::move(y),
                      layout.signature(),
                      layout.n_cells(),
                      index,
                      cfg.resolved_toml(),
                      cvode.stats(),
                      wall0 + seconds_since(start),
                      fs::absolute(out.path()).string(),
                      out.run_id(),
                      PANOPTIC_GIT_SHA,
                      PANOPTIC_VERSION,
                      {}};
  };
  Checkpoint last = record(times.front(), y0, index0);
  RowCounts last_rows;  // counted once the rows of `last`'s snapshot are in the output
  RunDiagnostics diag(sim, out, restart ? times.front() : 0.0);
  if (restart && !out.rebuild_note().empty())
    std::fprintf(stderr, "panoptic: warning: %s: %s\n", out.path().c_str(),
                 out.rebuild_note().c_str());
  if (restart) {  // rows the file lost before this restart: said aloud and recorded
    std::string lost = out.lost_rows();
    if (!diag.lost_rows().empty()) lost += (lost.empty() ? "" : "; ") + diag.lost_rows();
    if (!lost.empty()) {
      std::fprintf(stderr,
                   "panoptic: warning: %s had lost or garbled rows written before the "
                   "checkpoint (a run killed while HDF5 flushed the file): %s; they are "
                   "NaN now, the run goes on\n",
                   out.path().c_str(), lost.c_str());
      out.set_root_attr("restarts",
                        out.root_attr("restarts") + "; lost rows (now NaN): " + lost);
    }
  }
  // Every object is in the file: rows only from here on, written in SWMR mode.
  if (const std::string why = out.start_appending(); !why.empty())
    std::fprintf(stderr, "panoptic: warning: %s\n", why.c_str());
  const auto snapshot = [&](double t, std::span<const double> y) {
    auto fields = sim.snapshot_fields(y);
    diag.add_snapshot_fields(fields);
    diag.flush();
    out.write_snapshot(t / units::kYr, fields);
  };
  if (!restart) snapshot(0.0, y0);
  // The rows of the first checkpointable snapshot: t = 0 just written, or after a
  // restart the rows kept up to its checkpoint, /timeseries included (RunDiagnostics
  // kept those), so that a stop before the next snapshot checkpoints all their digests.
  last_rows = row_counts(out.row_digests());
  long checkpointed = -1;  // snapshot index of the checkpoint on disk
  const auto checkpoint_last = [&] {
    if (last.snapshot_index == checkpointed) return;
    last.row_digests = first_rows(out.row_digests(), last_rows);
    write_checkpoint(chk_path, last);
    checkpointed = last.snapshot_index;
  };
  // 7 snapshots: CVODE is reinitialised at each (so a restart is bit for bit); a
  // checkpoint is written at a snapshot when due; a stop checkpoints the last one (a
  // stop signalled during the set-up above: at the first step)
  const bool reinit = cfg.flag("solver.reinit_at_snapshots");
  CheckpointSchedule schedule(cfg.real("checkpoint.every_wall_s"),
                              cfg.integer("checkpoint.every_snapshots"), 0.0);
  const auto stop_if_asked = [&] {
    if (stop_signal() != 0) throw Stop{stop_signal_name(stop_signal())};
    if (max_wall > 0.0 && seconds_since(start) >= max_wall)
      throw Stop{"--max-wall " + a.max_wall};
  };
  Progress progress(times.back());
  std::string status = "completed";
  int code = 0;
  try {
    for (std::size_t k = 1; k < times.size(); ++k) {
      const double segment_start = seconds_since(start);
      cvode.advance_to(times[k], [&](double t, long nst) {
        stop_if_asked();
        diag.on_step(t, cvode.state());
        progress.update(t, nst);
      });
      snapshot(times[k], cvode.state());
      std::vector<double> y(cvode.state().begin(), cvode.state().end());
      if (reinit) {  // the particle laws' eta and v_g from this snapshot's gas on
        sim.refresh_local_gas(y);
        cvode.reinit(times[k], y);
      }
      last = record(times[k], std::move(y), index0 + static_cast<long>(k));
      last_rows = row_counts(out.row_digests());
      if (k + 1 == times.size()) break;
      const double now = seconds_since(start);
      if (schedule.due(last.snapshot_index, now)) {
        try {
          checkpoint_last();
        } catch (const IoError& e) {
          std::fprintf(stderr, "panoptic: warning: %s; the run goes on\n", e.what());
        }
        schedule.taken(now);
      }
      stop_if_asked();
      // Stop now rather than lose the next segment to the limit: it would take about
      // as long as this one.
      if (max_wall > 0.0 && 2.0 * now - segment_start > max_wall)
        throw Stop{"--max-wall " + a.max_wall +
                   " (the next snapshot would come too late)"};
    }
  } catch (const Stop& stop) {
    progress.done();
    checkpoint_last();
    status = "stopped by " + stop.reason + "; restart from " + chk_path.string();
    code = exit_codes::kStopped;
    std::printf(
        "stopped by %s at t = %.4g yr; the last snapshot (snapshot %ld, t = %.4g yr) "
        "is checkpointed in %s\nrestart with: %s\n",
        stop.reason.c_str(), cvode.time() / units::kYr, last.snapshot_index,
        last.t / units::kYr, chk_path.c_str(), restart_command(a, chk_path).c_str());
  } catch (const SolverError&) {
    progress.done();
    out.write_solver(cvode.stats(), wall0 + seconds_since(start), "failed");
    try {
      checkpoint_last();
      std::fprintf(stderr,
                   "panoptic: the last snapshot (t = %.4g yr) is checkpointed in %s: a "
                   "restart may change the solver.* settings\n",
                   last.t / units::kYr, chk_path.c_str());
    } catch (const IoError&) {
    }
    throw;
  }
  // 8 final checkpoint (a later output.t_end_yr continues from it), statistics, budget
  if (code == 0) {
    progress.done();
    std::fputs(diag.finish(cvode.time(), cvode.state()).c_str(), stdout);
    checkpoint_last();
  }
  const double wall = wall0 + seconds_since(start);
  const SolverStats s = cvode.stats();
  out.write_solver(s, wall, status);
  out.close();
  std::printf("%s at t = %.4g yr: %zu snapshots in %s\n",
              code == 0 ? "completed" : "stopped", cvode.time() / units::kYr,
              out.n_snapshots(), out.path().c_str());
  std::printf(
      "solver: %ld steps, %ld RHS, %ld Jacobian evaluations, %ld error-test and %ld "
      "nonlinear convergence failures, %ld reinitialisations, %.3f s wall\n",
      s.nst, s.nfe, s.nje, s.netf, s.nncf, s.nreinit, wall);
  if (restart)  // the counts above are the run's; what this process did since the restart
    std::printf("this process: %ld steps, %ld RHS from t = %.6g yr, %.3f s wall\n",
                s.nst - restart->chk.stats.nst, s.nfe - restart->chk.stats.nfe,
                restart->chk.t / units::kYr, seconds_since(start));
  print_budget(sim, cvode.state());
  return code;
}

int check(const std::string& scene, const std::vector<std::string>& overrides) {
  const Config cfg = load_scene(scene, overrides);
  validate_scene(cfg);
  warn_unused_keys(cfg);
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

//! `panoptic track`: one particle along its drift path (spec §13).
int track(const std::string& scene, const std::vector<std::string>& overrides,
          double r0_au, double a_stop_cm, double t_max_yr) {
  const Config cfg = load_scene(scene, overrides);
  validate_scene(cfg);
  if (!(r0_au > cfg.real("grid.r_in_au") && r0_au <= 1e6))
    throw ConfigError(
        "--r0-au " + num(r0_au) + ": must be > the inner edge grid.r_in_au = " +
        num(cfg.real("grid.r_in_au")) + " and <= 1e6 [au]; release the particle there");
  // a time or size of 0, below, NaN or inf ended the track at once with exit 0 (or
  // failed in CVODE)
  if (!(t_max_yr >= 1e-6 && t_max_yr <= 1e12))
    throw ConfigError("--t-max-yr " + num(t_max_yr) +
                      ": must be >= 1e-6 and <= 1e12 [yr]");
  if (!(a_stop_cm > 0.0 && std::isfinite(a_stop_cm)))
    throw ConfigError("--a-stop-cm " + num(a_stop_cm) + ": must be a radius > 0 [cm]");
  const TrackResult res =
      track_particle(cfg, r0_au * units::kAu, a_stop_cm, t_max_yr * units::kYr);
  std::printf("# panoptic track %s: monomer released at %.4g au (%ld CVODE steps)\n",
              scene.c_str(), r0_au, res.steps);
  std::printf("# %12s %10s %12s %12s %12s %12s\n", "t [yr]", "r [au]", "m [g]", "phi",
              "a [cm]", "St");
  // about 40 rows, log-spaced in time; the last the stop itself (interpolated to
  // a = a_stop) when the particle got there, not the step that went past it
  const auto row = [](const TrackPoint& p) {
    std::printf("  %12.5g %10.4g %12.5g %12.5g %12.5g %12.5g\n", p.t / units::kYr,
                p.r / units::kAu, p.m, p.phi, p.a, p.St);
  };
  const std::size_t n_rows = res.points.size() - (res.reached ? 1 : 0);
  double next = 0.0;
  for (std::size_t k = 0; k < n_rows; ++k) {
    const TrackPoint& p = res.points[k];
    if (p.t < next && (res.reached || k + 1 != n_rows)) continue;
    row(p);
    next = std::max(p.t * 1.25, 1.0 * units::kYr);
  }
  if (res.reached) row(res.at_stop);
  if (res.reached)
    std::printf("reached a = %.4g cm at t = %.4g yr, r = %.4g au\n", a_stop_cm,
                res.at_stop.t / units::kYr, res.at_stop.r / units::kAu);
  else
    std::printf(
        "did not reach a = %.4g cm (last: t = %.4g yr, r = %.4g au, a = %.4g cm)\n",
        a_stop_cm, res.points.back().t / units::kYr, res.points.back().r / units::kAu,
        res.points.back().a);
  return 0;
}

//! "0.87,1.3,3.0" -> numbers; a clear error naming the option otherwise.
std::vector<double> parse_list(const std::string& option, const std::string& text) {
  std::vector<double> out;
  std::size_t a = 0;
  while (a <= text.size()) {
    std::size_t b = text.find(',', a);
    if (b == std::string::npos) b = text.size();
    const std::string item = text.substr(a, b - a);
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (item.empty() || end == item.c_str() || *end != '\0')
      throw ConfigError(option + " " + text + ": '" + item +
                        "' is not a number; give comma-separated numbers, e.g. " +
                        option +
                        (option == "--lambda-mm" ? " 0.87,1.3,3.0" : " 0.05,0.04,30"));
    out.push_back(v);
    a = b + 1;
  }
  return out;
}

}  // namespace

namespace {
int run_command_line(int argc, char** argv);
}  // namespace

//! A write that failed (disk full, quota) can leave HDF5 holding a file it cannot close,
//! and its clean-up at exit (H5_term_library) then crashes on it (SIGSEGV instead of
//! the command's exit code; HDF5 1.10.8, sec2 driver). Every Handle is closed by the
//! time the command returns, so a file still open here is such a file: the process
//! ends without HDF5's clean-up, with the command's exit code; the files that did
//! close are complete on disk.
int main(int argc, char** argv) {
  const int code = run_command_line(argc, argv);
  // also after a success: a periodic checkpoint that failed to write (the run goes on
  // without it, warned) can leave its file behind in HDF5
  if (H5Fget_obj_count(H5F_OBJ_ALL, H5F_OBJ_FILE) > 0) {
    std::fflush(nullptr);
    std::_Exit(code);
  }
  return code;
}

namespace {
int run_command_line(int argc, char** argv) {
  // 1 command line
  CLI::App app{
      "panoptic: dust evolution of a whole protoplanetary disk, from monomers to "
      "planetesimals"};
  app.set_version_flag("--version", std::string("panoptic ") + PANOPTIC_VERSION + " (" +
                                        PANOPTIC_GIT_SHA + ")" +
                                        (scan_has_mpi() ? " with MPI" : ""));
  app.require_subcommand(1);
  RunArgs args;
  args.program = argc > 0 ? argv[0] : "panoptic";
  std::string& scene = args.scene;
  std::vector<std::string>& overrides = args.overrides;

  auto* run_cmd = app.add_subcommand("run", "run a scene and write its HDF5 output");
  run_cmd->add_option("scene", scene, "scene file (TOML)")->required();
  run_cmd->add_option("--set", overrides, "override a scene key: table.key=value")
      ->take_all();
  run_cmd->add_option("-o,--output", args.output,
                      "output file (default out/<scene>.h5; with --restart: the "
                      "checkpoint's)");
  auto* overwrite_opt =
      run_cmd->add_flag("--overwrite", args.overwrite, "replace an existing output file");
  run_cmd
      ->add_option("--restart", args.restart,
                   "continue the run of this checkpoint (<output>.chk.h5); the output "
                   "file is continued")
      ->excludes(overwrite_opt);
  // accuracy presets (src/scene/presets.hpp): overrides applied before --set, so --set
  // wins
  bool fast = false, accurate = false;
  auto* fast_opt = run_cmd->add_flag(
      "--fast", fast,
      "preset: coarser grid and looser tolerance (README, Work-precision)");
  run_cmd
      ->add_flag("--accurate", accurate,
                 "preset: finer grid and tighter tolerance (README, Work-precision)")
      ->excludes(fast_opt);
  run_cmd->add_option("--max-wall", args.max_wall,
                      "stop with a checkpoint (exit code 75) before this wall time, "
                      "e.g. 90m, 2h, 1h30m, 3600s");

  auto* check_cmd = app.add_subcommand(
      "check", "validate a scene and print it resolved, with defaults");
  check_cmd->add_option("scene", scene, "scene file (TOML)")->required();
  check_cmd->add_option("--set", overrides, "override a scene key: table.key=value")
      ->take_all();

  double r0_au = 10.0, a_stop_cm = 1e5, t_max_yr = 1e7;
  auto* track_cmd = app.add_subcommand(
      "track",
      "follow one particle along its drift path with the growth model (spec §13)");
  track_cmd->add_option("scene", scene, "scene file (TOML)")->required();
  track_cmd->add_option("--set", overrides, "override a scene key: table.key=value")
      ->take_all();
  track_cmd->add_option("--r0-au", r0_au, "release radius [au]")->required();
  track_cmd->add_option("--a-stop-cm", a_stop_cm, "stop at this particle radius [cm]")
      ->capture_default_str();
  track_cmd->add_option("--t-max-yr", t_max_yr, "stop at this time [yr]")
      ->capture_default_str();

  ObserveArgs obs;
  std::string lambda_text, beam_text;
  auto* obs_cmd = app.add_subcommand(
      "observe",
      "synthetic continuum images of a run's snapshot: Mie opacities, beam-convolved "
      "images, radial profiles, spectral index (absorption only)");
  obs_cmd->add_option("run", obs.run_file, "output file of `panoptic run` (HDF5)")
      ->required();
  obs_cmd->add_option("--time-yr", obs.time_yr, "time [yr]: the nearest snapshot is used")
      ->required();
  obs_cmd->add_option("--lambda-mm", lambda_text, "wavelengths [mm], e.g. 0.87,1.3,3.0")
      ->required();
  obs_cmd->add_option("--distance-pc", obs.distance_pc, "distance [pc]")
      ->capture_default_str();
  obs_cmd->add_option("--incl-deg", obs.incl_deg, "inclination [deg], 0 = face-on")
      ->capture_default_str();
  obs_cmd
      ->add_option("--pa-deg", obs.pa_deg,
                   "position angle of the major axis, north through east [deg]")
      ->capture_default_str();
  obs_cmd->add_option(
      "--beam-arcsec", beam_text,
      "beam FWHM major,minor [arcsec] and PA [deg] (default 0.05,0.05,0)");
  obs_cmd->add_option("--a-cm", obs.a_cm,
                      "particle radius [cm] in every cell, phi = 1 (for runs without "
                      "growth; replaces the run's sizes)");
  obs_cmd
      ->add_option("--set", obs.overrides, "override an observe.* key: observe.key=value")
      ->take_all();
  obs_cmd->add_option("-o,--output", obs.output, "output file (default <run>_obs.h5)");
  obs_cmd->add_flag("--overwrite", obs.overwrite, "replace an existing output file");

  auto* ref_cmd = app.add_subcommand(
      "reference",
      "print every scene key with its default and unit (params/reference.toml)");
  bool outputs = false;
  ref_cmd->add_flag("--outputs", outputs,
                    "print the table of every snapshot field (Markdown: field, units, "
                    "description), from the fields the modules declare");

  ScanOptions scan_opts;
  auto* scan_cmd = app.add_subcommand(
      "scan",
      "run a parameter scan: serially, with -j N workers, under mpirun, or one entry "
      "(--task I); rerun to resume");
  scan_cmd->add_option("scan_file", scan_opts.scan_file, "scan file (TOML)")->required();
  scan_cmd->add_option("-o,--output", scan_opts.dir,
                       "scan directory (manifest, runs/, summary); required "
                       "unless --dry-run");
  scan_cmd->add_option("-j,--jobs", scan_opts.jobs, "runs at once (per MPI rank)")
      ->capture_default_str();
  std::string task_text;
  auto* task_opt =
      scan_cmd->add_option("--task", task_text, "run only manifest entry I (job arrays)");
  scan_cmd->add_flag("--dry-run", scan_opts.dry_run,
                     "validate and print the manifest; write nothing");
  scan_cmd->add_flag("--force", scan_opts.force,
                     "replace a manifest in DIR that differs from the scan's");
  scan_cmd->add_option(
      "--run-exe", scan_opts.run_exe,
      "the panoptic executable that runs the scenes (default: this one)");

  try {
    app.parse(argc, argv);
    if (*scan_cmd && !scan_opts.dry_run && scan_opts.dir.empty())
      throw CLI::RequiredError("-o DIR (the scan directory)");
    if (task_opt->count() > 0) scan_opts.task = task_text;  // checked by run_scan
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return exit_codes::kBadInput;
  }

  try {
    // -o "" (an unset variable in a batch script) wrote to the default output instead
    for (auto* cmd : {run_cmd, obs_cmd})
      if (*cmd && cmd->count("--output") > 0 &&
          (cmd == run_cmd ? args.output : obs.output).empty())
        throw ConfigError(std::string("-o \"\": an empty output path (an unset "
                                      "variable?); give a file name, or leave -o out for "
                                      "the default ") +
                          (cmd == run_cmd ? "out/<scene>.h5" : "<run>_obs.h5"));
    if (*run_cmd) {
      args.preset = fast ? "fast" : accurate ? "accurate" : "";
      overrides = with_preset(args.preset, overrides);
      args.max_wall_given = run_cmd->count("--max-wall") > 0;
      return run(args);
    }
    if (*check_cmd) return check(scene, overrides);
    if (*scan_cmd) return run_scan(scan_opts);
    if (*track_cmd) return track(scene, overrides, r0_au, a_stop_cm, t_max_yr);
    if (*obs_cmd) {
      obs.lambda_mm = parse_list("--lambda-mm", lambda_text);
      if (!beam_text.empty()) {
        const std::vector<double> b = parse_list("--beam-arcsec", beam_text);
        if (b.size() != 3)
          throw ConfigError(
              "--beam-arcsec " + beam_text +
              ": give three numbers bmaj,bmin,bpa (FWHM [arcsec], PA [deg])");
        obs.bmaj_arcsec = b[0];
        obs.bmin_arcsec = b[1];
        obs.bpa_deg = b[2];
      }
      obs.a_cm_given = obs_cmd->count("--a-cm") > 0;
      return observe(obs);
    }
    if (*ref_cmd && outputs) {  // every module on, so every field is declared
      const Simulation every(every_process_scene());
      std::vector<OutputField> fields = every.output_fields();
      for (OutputField& f : RunDiagnostics::output_fields(every)) fields.push_back(f);
      std::fputs(output_table_markdown(every.static_fields(), fields).c_str(), stdout);
      return 0;
    }
    if (*ref_cmd) {
      std::fputs(reference_toml().c_str(), stdout);
      return 0;
    }
  } catch (const Error& e) {
    std::fprintf(stderr, "panoptic: error: %s\n", e.what());
    return e.exit_code();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "panoptic: internal error: %s\n", e.what());
    return exit_codes::kInternal;
  }
  return 0;
}
}  // namespace
