#pragma once
//! What a run says besides its output: warnings about the scene, the command that
//! continues a stopped run, the dust mass budget at the end.
#include <filesystem>
#include <span>
#include <string>

namespace panoptic {

class Config;
class Simulation;
struct RunArgs;

//! One warning per key the scene set that this run does not read (disk.r_c_au without
//! disk.model = "lbp"): to stderr, the exit code unchanged.
void warn_unused_keys(const Config& cfg);

//! The command that continues this run from `chk`, for copy and paste.
std::string restart_command(const RunArgs& a, const std::filesystem::path& chk);

//! The dust budget at state y: every term, the total, the initial mass and the relative
//! error, with a warning when it does not close.
void print_budget(const Simulation& sim, std::span<const double> y);

}  // namespace panoptic
