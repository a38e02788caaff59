#pragma once
//! The restart policy: which checkpoint a restart continues (the one given, else the
//! previous one next to it), whether the scene may continue it (only the output times,
//! the solver, checkpoint, observe and meta keys may change) and the snapshot times after
//! it. The checkpoint file itself: src/io/checkpoint.hpp.
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "src/io/checkpoint.hpp"

namespace panoptic {

class Config;
class StateLayout;

//! A checkpoint to restart from, and which file it came from.
struct RestartPoint {
  Checkpoint chk;
  std::filesystem::path path;  //!< the file actually read
  std::string fallback_note;   //!< non-empty when the previous checkpoint was used: why
};

//! Reads `path`; when that fails and a previous checkpoint exists next to it
//! (`<stem>.chk.prev.h5`), reads that one instead and says why in fallback_note. Throws
//! IoError naming both files when neither can be used.
RestartPoint load_restart_point(const std::filesystem::path& path);

//! The scene of a restart given no scene file (`panoptic run --restart CHK`): the
//! checkpoint's stored scene, named as the scene file of the run that wrote it (its
//! first line), with `overrides` (--set) over it. ConfigError naming the checkpoint when
//! the stored scene does not load in this version, or naming the --set item.
Config checkpoint_scene(const RestartPoint& restart,
                        std::span<const std::string> overrides);

//! True for the keys a restart may change: output times and the output file, solver
//! settings, checkpoint settings, [meta]. Everything else (grid, disk, processes,
//! initial condition, ...) defines the state being continued.
bool may_change_on_restart(std::string_view key);

//! Throws ConfigError (exit 2) when `cfg` cannot continue `chk`: names every key whose
//! value differs from the checkpoint's scene and may not change, with both values, or
//! the differing layout (StateLayout::signature); says what may change and the fix.
//! Returns the keys that differ and may, as "key = value (was value)" (for the output's
//! record of restarts and the run's notice).
std::vector<std::string> check_compatible(const Checkpoint& chk,
                                          const std::filesystem::path& chk_path,
                                          const Config& cfg, const StateLayout& layout);

//! The keys whose values differ between two scenes, in schema order.
std::vector<std::string> changed_keys(const Config& before, const Config& now);

//! The snapshot times [s] of a run continued at t_restart: t_restart, then the scene's
//! snapshot times after it. Throws ConfigError naming output.t_end_yr when the scene
//! ends at or before t_restart.
std::vector<double> times_after_restart(std::span<const double> output_times,
                                        double t_restart);

}  // namespace panoptic
