#pragma once
//! The output file of a run: a new one, or the one of the run a restart continues.
#include <filesystem>
#include <string>
#include <vector>

#include "src/io/run_output.hpp"
#include "src/run/variant.hpp"

namespace panoptic {

class Config;
class Simulation;
struct RestartPoint;

//! output.file of the scene, else out/<label>.h5 (`label`: variant_label(), the scene
//! file's stem with the overrides).
std::filesystem::path default_output(const Config& cfg, const std::string& label);

//! A new output file with /grid, /disk, the snapshot fields declared and the variant's
//! root attributes `label` and `overrides`. An existing output without --overwrite stops
//! the run, naming it and the options (-o, --overwrite, --restart); checkpoints left next
//! to it by a run it replaces are removed (they belong to that run), with --overwrite
//! only, and only files panoptic wrote as checkpoints: anything else at those paths, or a
//! checkpoint without --overwrite, stops the run before a file is touched (exit 4).
RunOutput new_output(const Config& cfg, const Simulation& sim,
                     const std::filesystem::path& path, bool overwrite,
                     const Variant& variant);

//! The output of the checkpoint's run, reopened to continue it: `output` (-o) when
//! given, else the file of the recorded name next to the checkpoint, else the recorded
//! path. Checks, before changing anything, that it is that run's file (run_id, and
//! the time of the checkpoint's snapshot); then cuts the snapshots written after the
//! checkpoint, stores the new resolved scene as config_toml and adds a line to the root
//! attribute `restarts`. IoError naming the file and the fix.
RunOutput continue_output(const RestartPoint& restart,
                          const std::filesystem::path& output, const Config& cfg,
                          const std::vector<std::string>& changed);

}  // namespace panoptic
