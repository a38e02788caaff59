#include "src/run/restart.hpp"

#include <algorithm>
#include <cstdio>

#include "build_info.hpp"  // PANOPTIC_GIT_SHA (generated at build time)
#include "src/core/error.hpp"
#include "src/core/units.hpp"
#include "src/scene/config.hpp"
#include "src/scene/toml_literal.hpp"
#include "src/solver/state_layout.hpp"

namespace fs = std::filesystem;

namespace panoptic {
namespace {

// Why a checkpoint's stored scene cannot be continued: `e`, its load in this version.
std::string stored_scene_refusal(const Checkpoint& chk, const ConfigError& e) {
  return std::string(
             "the scene stored in the checkpoint does not load in this version "
             "of panoptic (" PANOPTIC_VERSION ", " PANOPTIC_GIT_SHA "):\n") +
         e.what() + "\nrestart with the version that wrote it, panoptic " + chk.version +
         " (" + chk.git_sha + ")";
}

}  // namespace

RestartPoint load_restart_point(const fs::path& path) {
  try {
    return {read_checkpoint(path), path, ""};
  } catch (const IoError& first) {
    const fs::path prev = previous_checkpoint_path(path);
    std::error_code ec;
    if (prev == path || !fs::exists(prev, ec))
      throw IoError(std::string(first.what()) + "; there is no previous checkpoint " +
                    prev.string() +
                    " to fall back on: start the run again without --restart");
    try {
      return {read_checkpoint(prev), prev, first.what()};
    } catch (const IoError& second) {
      throw IoError(std::string(first.what()) +
                    "\n  and the previous checkpoint: " + second.what() +
                    "\n  neither can be used: start the run again without --restart");
    }
  }
}

Config checkpoint_scene(const RestartPoint& restart,
                        std::span<const std::string> overrides) {
  const Checkpoint& chk = restart.chk;
  std::string name = resolved_scene_file(chk.config_toml);
  if (name.empty()) name = restart.path.string() + " (its stored scene)";
  try {
    load_scene_text(chk.config_toml, name);
  } catch (const ConfigError& e) {
    throw ConfigError(restart.path.string() + ": " + stored_scene_refusal(chk, e));
  }
  return load_scene_text(chk.config_toml, name, overrides);
}

bool may_change_on_restart(std::string_view key) {
  // Listed one by one (not solver.* or output.*): a key added later must be judged
  // before a restart may change it, so the safe answer for an unknown key is no.
  static const std::vector<std::string_view> kKeys = {
      "output.t_end_yr",    "output.t_first_yr",
      "output.n_snapshots", "output.times_yr",
      "output.file",        "solver.rtol",
      "solver.atol_sigma",  "solver.max_steps",
      "solver.max_dt_yr",   "solver.reinit_at_snapshots",
      "solver.newton_coef", "solver.steps_per_jacobian",
      "solver.linear"};
  if (key.starts_with("checkpoint.") || key.starts_with("meta.") ||
      key.starts_with("observe."))  // read by `panoptic observe` only
    return true;
  return std::find(kKeys.begin(), kKeys.end(), key) != kKeys.end();
}

std::vector<std::string> changed_keys(const Config& before, const Config& now) {
  std::vector<std::string> out;
  for (const KeySpec& spec : scene_keys()) {
    const auto a = before.values_.find(spec.key);
    const auto b = now.values_.find(spec.key);
    const bool in_a = a != before.values_.end(), in_b = b != now.values_.end();
    if (in_a != in_b || (in_a && a->second != b->second)) out.push_back(spec.key);
  }
  return out;
}

std::vector<std::string> check_compatible(const Checkpoint& chk, const fs::path& chk_path,
                                          const Config& cfg, const StateLayout& layout) {
  const std::string layout_signature = layout.signature();
  const std::string chk_name = chk_path.string();
  Config before;
  try {
    before = load_scene_text(chk.config_toml, chk_name + " (its stored scene)");
  } catch (const ConfigError& e) {
    throw ConfigError(chk_name + ": " + stored_scene_refusal(chk, e));
  }
  std::string differing;
  std::string example;
  std::vector<std::string> allowed;
  for (const std::string& key : changed_keys(before, cfg)) {
    if (may_change_on_restart(key)) {
      const auto text_of = [&](const Config& c) {
        const auto it = c.values_.find(key);
        return it == c.values_.end() ? std::string("unset") : toml_value(it->second);
      };
      allowed.push_back(key + " = " + text_of(cfg) + " (was " + text_of(before) + ")");
      continue;
    }
    const std::string was = toml_value(before.values_.at(key));
    differing += "\n  " + key + " = " + toml_value(cfg.values_.at(key)) + " (" +
                 cfg.where(key) + "), the checkpoint has " + was;
    if (example.empty()) example = " (e.g. --set " + key + "=" + was + ")";
  }
  if (!differing.empty())
    throw ConfigError(
        cfg.file().string() + ": cannot restart from " + chk_name +
        ": the scene differs from the checkpoint's in keys that define the state being "
        "continued:" +
        differing +
        "\nA restart may change only the output times (output.t_end_yr, t_first_yr, "
        "n_snapshots, times_yr), output.file, the solver.* settings, checkpoint.*, "
        "observe.* and meta.*. "
        "Set these keys back to the checkpoint's values" +
        example + ", or start a new run without --restart.");
  if (chk.layout_signature != layout_signature)
    throw ConfigError(cfg.file().string() + ": cannot restart from " + chk_name +
                      ": the state layout differs (checkpoint: " + chk.layout_signature +
                      "; this scene: " + layout_signature +
                      "): the program that wrote the checkpoint registers other "
                      "variables; restart with panoptic " +
                      chk.version + " (" + chk.git_sha +
                      "), or start a new run without --restart");
  if (static_cast<long>(chk.y.size()) != layout.size() || chk.n_cells != layout.n_cells())
    throw IoError(chk_name + ": the state holds " + std::to_string(chk.y.size()) +
                  " values for " + std::to_string(chk.n_cells) +
                  " cells, but its layout needs " + std::to_string(layout.size()) +
                  "; the checkpoint is damaged: use " +
                  previous_checkpoint_path(chk_path).string());
  return allowed;
}

std::vector<double> times_after_restart(std::span<const double> output_times,
                                        double t_restart) {
  std::vector<double> t{t_restart};
  for (const double x : output_times)
    if (x > t_restart) t.push_back(x);
  if (t.size() == 1) {
    char buf[200];
    std::snprintf(buf, sizeof buf,
                  "output.t_end_yr = %.6g: the checkpoint is at t = %.6g yr, at or "
                  "after the end of this run; raise output.t_end_yr (e.g. --set "
                  "output.t_end_yr=%.3g) to continue the run",
                  output_times.empty() ? 0.0 : output_times.back() / units::kYr,
                  t_restart / units::kYr, 10.0 * t_restart / units::kYr);
    throw ConfigError(buf);
  }
  return t;
}

}  // namespace panoptic
