#include "src/run/start.hpp"

#include <cstdio>

#include "build_info.hpp"  // PANOPTIC_VERSION (generated at build time)
#include "src/core/error.hpp"
#include "src/core/units.hpp"
#include "src/io/durable_file.hpp"
#include "src/model/simulation.hpp"
#include "src/run/diagnostics.hpp"
#include "src/run/open_output.hpp"
#include "src/run/run.hpp"
#include "src/scene/config.hpp"
#include "src/scene/presets.hpp"

namespace fs = std::filesystem;

namespace panoptic {
namespace {

//! The checkpoint of --restart, checked against the scene; the keys the restart
//! changes (output times, solver settings) in `changed`.
RestartPoint restart_point(const RunArgs& a, const Config& cfg, const Simulation& sim,
                           std::vector<std::string>& changed,
                           std::optional<RestartPoint> preloaded) {
  RestartPoint restart =
      preloaded ? std::move(*preloaded) : load_restart_point(a.restart);
  if (!restart.fallback_note.empty())
    std::fprintf(stderr,
                 "panoptic: %s\npanoptic: restarting from the previous checkpoint %s "
                 "instead (t = %.6g yr, snapshot %ld)\n",
                 restart.fallback_note.c_str(), restart.path.c_str(),
                 restart.chk.t / units::kYr, restart.chk.snapshot_index);
  try {
    changed = check_compatible(restart.chk, restart.path, cfg, sim.model().layout());
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
  return restart;
}

}  // namespace

RunStart start_run(const RunArgs& a, const Config& cfg, Simulation& sim,
                   std::optional<RestartPoint> preloaded) {
  // the restart point; the snapshot times are then those of the scene after its time
  std::optional<RestartPoint> restart;
  std::vector<std::string> changed;
  if (!a.restart.empty())
    restart = restart_point(a, cfg, sim, changed, std::move(preloaded));
  std::vector<double> times =
      restart ? times_after_restart(sim.output_times(), restart->chk.t)
              : sim.output_times();
  // the output: new, or the checkpoint's run's file cut to the checkpoint's snapshots
  const Variant variant{variant_label(cfg.file().stem().string(), a.preset, a.sets),
                        a.overrides};
  const fs::path out_path =
      a.output.empty() ? default_output(cfg, variant.label) : fs::path(a.output);
  refuse_output_is_input(out_path, a.scene, "the scene the run reads");
  if (restart)
    refuse_output_is_input(out_path, restart->path, "the checkpoint it restarts from");
  RunOutput out = restart ? continue_output(*restart, a.output, cfg, changed)
                          : new_output(cfg, sim, out_path, a.overwrite, variant);
  // a continued output's /grid, /disk and fields declared again: a field that the
  // restart's copy could not read is recreated (RunOutput::add_field)
  if (restart) sim.prepare_output(out);
  std::printf("panoptic %s: scene %s%s -> %s\n", PANOPTIC_VERSION, cfg.file().c_str(),
              a.scene.empty() ? " (stored in the checkpoint)" : "", out.path().c_str());
  if (!restart && !a.overrides.empty()) {  // the variant: its label and its options
    std::string options = a.preset.empty() ? "" : " --" + a.preset;
    for (const std::string& s : a.sets) options += " --set " + s;
    std::printf("variant %s:%s\n", variant.label.c_str(), options.c_str());
  }
  std::fputs(sim.summary().c_str(), stdout);
  if (restart)
    std::printf("restart from %s at t = %.6g yr (snapshot %ld)\n", restart->path.c_str(),
                restart->chk.t / units::kYr, restart->chk.snapshot_index);
  std::fflush(stdout);
  // the state, from the initial condition or the checkpoint's (with its statistics)
  std::vector<double> y0 = restart ? restart->chk.y : sim.initial_state();
  const SolverStats stats = restart ? restart->chk.stats : SolverStats{};
  const long index0 = restart ? restart->chk.snapshot_index : 0;
  const double wall0 = restart ? restart->chk.wall_s : 0.0;
  return RunStart{std::move(restart),
                  std::move(out),
                  std::move(times),
                  std::move(y0),
                  stats,
                  index0,
                  wall0};
}

void report_restart_losses(RunOutput& out, const RunDiagnostics& diag) {
  if (!out.rebuild_note().empty())
    std::fprintf(stderr, "panoptic: warning: %s: %s\n", out.path().c_str(),
                 out.rebuild_note().c_str());
  if (!out.new_fields().empty()) {
    std::fprintf(stderr,
                 "panoptic: note: %s: fields that the checkpoint's run did not write (an "
                 "earlier panoptic) are added, NaN in the snapshots before the restart: "
                 "%s\n",
                 out.path().c_str(), out.new_fields().c_str());
    out.set_root_attr("restarts", out.root_attr("restarts") +
                                      "; fields added (NaN before): " + out.new_fields());
  }
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

}  // namespace panoptic
