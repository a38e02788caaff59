// panoptic: dust evolution of a whole protoplanetary disk. This file parses the command
// line (CLI11) and dispatches to the subcommands: run (src/run/run.hpp), check and track
// (src/run/commands.hpp), observe (src/observe), reference (src/scene), scan
// (src/scan). The exit codes are listed in src/core/exit_codes.hpp.
#include <hdf5.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "build_info.hpp"  // PANOPTIC_GIT_SHA (generated at build time)
#include "src/core/error.hpp"
#include "src/core/exit_codes.hpp"
#include "src/observe/observe.hpp"
#include "src/run/commands.hpp"
#include "src/run/output_reference.hpp"
#include "src/run/run.hpp"
#include "src/scan/scan.hpp"
#include "src/scene/config.hpp"
#include "src/scene/presets.hpp"

using namespace panoptic;

namespace {

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

//! The default of --progress for batch jobs: $PANOPTIC_PROGRESS, when set and not empty.
void progress_from_environment(RunArgs& args) {
  const char* env = std::getenv("PANOPTIC_PROGRESS");
  if (env == nullptr || *env == '\0') return;
  args.progress = env;
  args.progress_source = "PANOPTIC_PROGRESS (environment) =";
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
  run_cmd->add_option("scene", scene,
                      "scene file (TOML); with --restart it may be left out: the "
                      "checkpoint holds the scene");
  run_cmd->add_option("--set", overrides, "override a scene key: table.key=value")
      ->take_all();
  run_cmd->add_option("-o,--output", args.output,
                      "output file (default out/<scene>.h5, out/<scene>+<key>=<value>.h5 "
                      "with --set; with --restart: the "
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
  auto* fast_opt = run_cmd->add_flag("--fast", fast,
                                     "preset: coarser grid and looser tolerance "
                                     "(tests/bench/README.md, Work-precision)");
  run_cmd
      ->add_flag("--accurate", accurate,
                 "preset: finer grid and tighter tolerance (tests/bench/README.md, "
                 "Work-precision)")
      ->excludes(fast_opt);
  run_cmd->add_option("--max-wall", args.max_wall,
                      "stop with a checkpoint (exit code 75) before this wall time, "
                      "e.g. 90m, 2h, 1h30m, 3600s");
  run_cmd->add_option("--threads", args.threads,
                      "worker threads sharing the size distribution's cells (default 1); "
                      "the results are the same to the bit for any number");
  run_cmd->add_option("--progress", args.progress,
                      "when stdout is not a terminal (a batch job's log), print a line "
                      "of progress (time, steps, wall time, ETA) every INTERVAL, e.g. "
                      "60, 5m (default: $PANOPTIC_PROGRESS, else none)");

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
                    "print the table of every dataset and attribute of a run's output "
                    "(Markdown: path, units, description), from their declarations");

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
  scan_cmd->add_option("--threads", scan_opts.threads,
                       "worker threads of each run (panoptic run --threads; default 1)");
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
  scan_cmd->add_option(
      "--progress", scan_opts.progress,
      "a line of progress every INTERVAL in each run's log (panoptic run "
      "--progress; $PANOPTIC_PROGRESS reaches the runs as well)");

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
    if (*run_cmd && scene.empty() && args.restart.empty())
      throw ConfigError(
          "panoptic run: a scene file is required (panoptic run SCENE.toml), or "
          "--restart CHK.h5 to continue a run from its checkpoint");
    if (*run_cmd) {
      args.preset = fast ? "fast" : accurate ? "accurate" : "";
      args.sets = overrides;
      overrides = with_preset(args.preset, overrides);
      args.max_wall_given = run_cmd->count("--max-wall") > 0;
      if (run_cmd->count("--progress") == 0) progress_from_environment(args);
      return run_scene(args);
    }
    if (*check_cmd) return check_scene(scene, overrides);
    if (*scan_cmd) return run_scan(scan_opts);
    if (*track_cmd) return track_command(scene, overrides, r0_au, a_stop_cm, t_max_yr);
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
    if (*ref_cmd && outputs) {
      std::fputs(output_reference_markdown().c_str(), stdout);
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
