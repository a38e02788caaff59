#include "src/run/open_output.hpp"

#include <cstdio>

#include "build_info.hpp"  // PANOPTIC_GIT_SHA (generated at build time)
#include "src/core/error.hpp"
#include "src/core/units.hpp"
#include "src/io/checkpoint.hpp"
#include "src/io/h5.hpp"
#include "src/model/simulation.hpp"
#include "src/run/restart.hpp"
#include "src/scene/config.hpp"

namespace fs = std::filesystem;

namespace panoptic {

fs::path default_output(const Config& cfg, const std::string& label) {
  if (!cfg.str("output.file").empty()) return cfg.str("output.file");
  return fs::path("out") / (label + ".h5");
}

RunOutput new_output(const Config& cfg, const Simulation& sim, const fs::path& path,
                     bool overwrite, const Variant& variant) {
  const fs::path chk = checkpoint_path(path);
  std::error_code ec;
  if (!overwrite && fs::exists(fs::symlink_status(path, ec)) &&
      fs::is_regular_file(path, ec))
    throw IoError(path.string() +
                  ": output file exists (an earlier run's); write this run to another "
                  "file with -o FILE, or replace it with --overwrite" +
                  (is_checkpoint_file(chk)
                       ? ", or continue that run with --restart " + chk.string() +
                             " (with a later output.t_end_yr if it completed)"
                       : std::string()));
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
  for (const OutputAttribute& a : variant_attributes(variant)) out.write_attribute(a);
  sim.prepare_output(out);
  for (const fs::path& stale : {chk, previous_checkpoint_path(chk)})
    if (fs::remove(stale, ec))
      std::printf("removed %s: a checkpoint of the run this output replaces\n",
                  stale.c_str());
  return out;
}

RunOutput continue_output(const RestartPoint& restart, const fs::path& output,
                          const Config& cfg, const std::vector<std::string>& changed) {
  const Checkpoint& chk = restart.chk;
  const std::string chk_name = restart.path.string();
  fs::path path = output;
  std::error_code ec;
  if (path.empty()) {
    // The output is written next to its checkpoints: prefer the file there, so that a
    // run directory copied or moved as a whole continues its own output; the recorded
    // path serves a checkpoint moved alone.
    const fs::path sibling =
        restart.path.parent_path() / fs::path(chk.output_file).filename();
    path = fs::exists(sibling, ec) ? sibling : fs::path(chk.output_file);
    if (!fs::exists(path, ec))
      throw IoError(chk_name + ": the run's output file " + chk.output_file +
                    " does not exist" +
                    (fs::weakly_canonical(sibling, ec) ==
                             fs::weakly_canonical(fs::path(chk.output_file), ec)
                         ? std::string()
                         : " (nor " + sibling.string() + ")") +
                    "; pass it with -o, or start a new run without --restart");
  } else if (!fs::exists(path, ec)) {
    // was "cannot read the run's output file ...: it is damaged"
    throw ConfigError("-o " + path.string() +
                      ": no such file; with --restart, -o names the existing output to "
                      "continue (the checkpoint's run wrote " +
                      chk.output_file + "); leave -o out to continue that one");
  }
  const auto n_keep = static_cast<std::size_t>(chk.snapshot_index) + 1;
  // Read-only first: a wrong file must be refused before a row of it is cut.
  {
    h5::quiet_errors();
    h5::Handle f;
    std::vector<double> t_yr;
    std::string run_id;
    try {
      f = h5::open_file(path.string(), false);
      if (h5::has_attr(f.get(), "run_id"))
        run_id = h5::get_attr_string(f.get(), "run_id");
      h5::Handle g = h5::open_group(f.get(), "snapshots");
      t_yr = h5::read_doubles(g.get(), "time");
    } catch (const IoError& e) {
      throw IoError(path.string() + ": cannot read the run's output file (" + e.what() +
                    "): it is damaged (truncated or overwritten) or not a panoptic "
                    "output, and cannot be continued; restore it, pass the run's output "
                    "with -o, or start the run again without --restart");
    }
    if (run_id != chk.run_id)
      throw IoError(path.string() + ": not the output of the run of checkpoint " +
                    chk_name + " (run_id " + run_id + ", the checkpoint's " + chk.run_id +
                    "); pass that run's output file with -o");
    if (t_yr.size() < n_keep || t_yr[n_keep - 1] != chk.t / units::kYr)
      throw IoError(path.string() + ": does not hold snapshot " +
                    std::to_string(chk.snapshot_index) + " at t = " +
                    std::to_string(chk.t / units::kYr) + " yr of checkpoint " + chk_name +
                    " (it has " + std::to_string(t_yr.size()) +
                    " snapshots); pass that run's output file with -o");
    if (t_yr.size() > n_keep)  // said aloud: a copied or older checkpoint cuts a run
      std::fprintf(
          stderr,
          "panoptic: warning: %s: its %zu snapshot%s after the checkpoint's (t = "
          "%.6g yr, snapshot %ld) up to t = %.6g yr %s cut and computed again\n",
          path.c_str(), t_yr.size() - n_keep, t_yr.size() - n_keep == 1 ? "" : "s",
          chk.t / units::kYr, chk.snapshot_index, t_yr.back(),
          t_yr.size() - n_keep == 1 ? "is" : "are");
  }
  RunOutput out(path, ContinueRun{n_keep, chk.row_digests});
  char line[160];
  std::snprintf(line, sizeof line, "t = %.17g yr (snapshot %ld): restarted from ",
                chk.t / units::kYr, chk.snapshot_index);
  std::string note =
      line + chk_name + " by panoptic " PANOPTIC_VERSION " (" PANOPTIC_GIT_SHA ")";
  if (!changed.empty()) {
    note += "; changed:";
    for (std::size_t k = 0; k < changed.size(); ++k)
      note += (k ? ", " : " ") + changed[k];
  }
  const std::string before = out.root_attr("restarts");
  out.set_root_attr("restarts", before.empty() ? note : before + "\n" + note);
  out.set_root_attr("config_toml", cfg.resolved_toml());
  return out;
}

}  // namespace panoptic
