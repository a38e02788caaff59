// `panoptic run` (run.hpp) as numbered steps: 1 set up (signals, scene, model) -> 2 open
// or restart the output (start.cpp: the one place a restart differs) -> 3 integrator ->
// 4 integrate to each snapshot time, checkpointing when due and at a stop -> 5 finish:
// final checkpoint, solver statistics and mass budget.
#include "src/run/run.hpp"

#include <cstdio>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "build_info.hpp"  // PANOPTIC_GIT_SHA (generated at build time)
#include "src/core/error.hpp"
#include "src/core/exit_codes.hpp"
#include "src/core/signals.hpp"
#include "src/core/units.hpp"
#include "src/core/wall_clock.hpp"
#include "src/core/worker_threads.hpp"
#include "src/io/checkpoint.hpp"
#include "src/io/run_output.hpp"
#include "src/model/scene_validation.hpp"
#include "src/model/simulation.hpp"
#include "src/run/checkpoint_schedule.hpp"
#include "src/run/diagnostics.hpp"
#include "src/run/max_wall.hpp"
#include "src/run/progress.hpp"
#include "src/run/report.hpp"
#include "src/run/restart.hpp"
#include "src/run/start.hpp"
#include "src/scene/config.hpp"
#include "src/solver/cvode_integrator.hpp"
#include "src/solver/integrator.hpp"

namespace fs = std::filesystem;

namespace panoptic {
namespace {

//! Thrown to stop the run at the next step or snapshot, with why.
struct Stop {
  std::string reason;
};

}  // namespace

int run_scene(const RunArgs& a) {
  // 1 set up. Stop signals first: SIGINT or SIGTERM during the set-up (a restart's copy
  // of a large output takes a while) is then handled at the first step like any other,
  // with the checkpoint and exit 75, instead of killing the process before the handlers
  // are in place. A parent (panoptic scan) may have blocked them until now; a stop that
  // arrived meanwhile is delivered here.
  install_stop_handlers(SecondStop::kUnlessFromParent);
  block_stop_signals(false);
  if (a.threads < 1)
    throw ConfigError("--threads " + std::to_string(a.threads) +
                      ": the number of worker threads must be at least 1; give "
                      "--threads 1 (the default) or the number of cores to share the "
                      "cells among");
  set_worker_threads(a.threads);
  // the scene: the file, or with --restart alone the checkpoint's (read here first)
  std::optional<RestartPoint> restart;
  if (a.scene.empty()) restart = load_restart_point(a.restart);
  const Config cfg = restart ? checkpoint_scene(*restart, a.overrides)
                             : load_scene(a.scene, a.overrides);
  validate_scene(cfg);
  warn_unused_keys(cfg);
  const double max_wall = a.max_wall_given ? parse_duration(a.max_wall) : 0.0;
  const double progress_s =
      a.progress.empty() ? 0.0 : parse_duration(a.progress, a.progress_source);
  Simulation sim(cfg);
  const StateLayout& layout = sim.model().layout();
  // 2 open or restart the output: every difference between a new run and a restart is
  // decided in start_run; the steps below treat both alike
  RunStart start_point = start_run(a, cfg, sim, std::move(restart));
  RunOutput& out = start_point.out;
  const std::vector<double>& times = start_point.times;
  const std::vector<double>& y0 = start_point.y0;
  const long index0 = start_point.snapshot_index;
  const double wall0 = start_point.wall_s;
  const bool restarted = start_point.restart.has_value();
  const fs::path chk_path = checkpoint_path(out.path());
  // 3 integrator, from the start's state with the run's statistics so far
  sim.refresh_local_gas(y0);  // eta and v_g of the particle laws (evolving gas)
  const std::unique_ptr<Integrator> integrator =
      make_integrator(sim.model(), times.front(), y0, sim.integrator_options());
  Integrator& solver = *integrator;
  solver.carry_stats(start_point.stats);
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
                      solver.stats(),
                      wall0 + seconds_since(start),
                      fs::absolute(out.path()).string(),
                      out.run_id(),
                      PANOPTIC_GIT_SHA,
                      PANOPTIC_VERSION,
                      {}};
  };
  Checkpoint last = record(times.front(), y0, index0);
  RowCounts last_rows;  // counted once the rows of `last`'s snapshot are in the output
  RunDiagnostics diag(sim, out, times.front());
  if (restarted) report_restart_losses(out, diag);
  // Every object is in the file: rows only from here on, written in SWMR mode.
  if (const std::string why = out.start_appending(); !why.empty())
    std::fprintf(stderr, "panoptic: warning: %s\n", why.c_str());
  const auto snapshot = [&](double t, std::span<const double> y) {
    auto fields = sim.snapshot_fields(y);
    diag.add_snapshot_fields(fields);
    diag.note_snapshot(t, fields);
    diag.flush();
    out.write_snapshot(t / units::kYr, fields);
  };
  if (!restarted) snapshot(0.0, y0);
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
  // 4 integrate to each snapshot time: the integrator is reinitialised at each (so a
  // restart is bit for bit); a checkpoint is written at a snapshot when due; a stop
  // checkpoints the last one (a stop signalled during the set-up above: at the first
  // step)
  const bool reinit = cfg.flag("solver.reinit_at_snapshots");
  CheckpointSchedule schedule(cfg.real("checkpoint.every_wall_s"),
                              cfg.integer("checkpoint.every_snapshots"), 0.0);
  const auto stop_if_asked = [&] {
    if (stop_signal() != 0) throw Stop{stop_signal_name(stop_signal())};
    if (max_wall > 0.0 && seconds_since(start) >= max_wall)
      throw Stop{"--max-wall " + a.max_wall};
  };
  Progress progress(times.front(), times.back(), progress_s);
  std::string status = "completed";
  int code = 0;
  try {
    for (std::size_t k = 1; k < times.size(); ++k) {
      const double segment_start = seconds_since(start);
      solver.advance_to(times[k], [&](double t, long nst) {
        stop_if_asked();
        diag.on_step(t, solver.state());
        progress.update(t, nst);
      });
      snapshot(times[k], solver.state());
      std::vector<double> y(solver.state().begin(), solver.state().end());
      if (reinit) {  // the particle laws' eta and v_g from this snapshot's gas on
        sim.refresh_local_gas(y);
        solver.reinit(times[k], y);
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
        stop.reason.c_str(), solver.time() / units::kYr, last.snapshot_index,
        last.t / units::kYr, chk_path.c_str(), restart_command(a, chk_path).c_str());
    if (!a.scene.empty()) {  // the checkpoint holds the scene, --set options included
      RunArgs alone;
      alone.program = a.program;
      std::printf("or, from the checkpoint alone: %s\n",
                  restart_command(alone, chk_path).c_str());
    }
  } catch (const SolverError&) {
    progress.done();
    out.write_solver(solver.stats(), wall0 + seconds_since(start), "failed");
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
  // 5 finish: final checkpoint (a later output.t_end_yr continues from it), statistics,
  // budget
  if (code == 0) {
    progress.done();
    std::fputs(diag.finish(solver.time(), solver.state()).c_str(), stdout);
    checkpoint_last();
  }
  const double wall = wall0 + seconds_since(start);
  const SolverStats s = solver.stats();
  out.write_solver(s, wall, status);
  out.close();
  std::printf("%s at t = %.4g yr: %zu snapshots in %s\n",
              code == 0 ? "completed" : "stopped", solver.time() / units::kYr,
              out.n_snapshots(), out.path().c_str());
  std::printf(
      "solver: %ld steps, %ld RHS, %ld Jacobian evaluations, %ld error-test and %ld "
      "nonlinear convergence failures, %ld reinitialisations, %.3f s wall\n",
      s.nst, s.nfe, s.nje, s.netf, s.nncf, s.nreinit, wall);
  // GMRES's counters: this process's, not the checkpoint's
  const auto* cvode = dynamic_cast<const CvodeIntegrator*>(integrator.get());
  if (cvode && cfg.str("solver.linear") == "gmres") {
    const KrylovStats k = cvode->krylov_stats();
    const long nni = s.nni - (restarted ? start_point.stats.nni : 0);
    std::printf(
        "GMRES: %ld linear iterations (%.2f per Newton iteration), %ld "
        "preconditioner solves, %ld linear convergence failures\n",
        k.nli, nni > 0 ? static_cast<double>(k.nli) / nni : 0.0, k.nps, k.nlcf);
  }
  if (restarted)  // the counts above are the run's; what this process did since the
                  // restart
    std::printf("this process: %ld steps, %ld RHS from t = %.6g yr, %.3f s wall\n",
                s.nst - start_point.stats.nst, s.nfe - start_point.stats.nfe,
                times.front() / units::kYr, seconds_since(start));
  print_budget(sim, solver.state());
  return code;
}

}  // namespace panoptic
