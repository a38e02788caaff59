#pragma once
//! Step 2 of a run: where it starts. A new run starts at t = 0 with a new output; a
//! restart (--restart CHK) continues a checkpoint's state, statistics and wall time in
//! its run's output. Every difference between the two is decided here, so that the steps
//! after it (run.cpp) integrate, write and checkpoint alike.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "src/io/run_output.hpp"
#include "src/run/restart.hpp"
#include "src/solver/solver_stats.hpp"

namespace panoptic {

class Config;
class RunDiagnostics;
class Simulation;
struct RunArgs;

struct RunStart {
  std::optional<RestartPoint> restart;  //!< the checkpoint continued; none: a new run
  RunOutput out;
  std::vector<double> times;  //!< snapshot times [s]: times[0] the start, then the rest
  std::vector<double> y0;     //!< the state at times[0]
  SolverStats stats;          //!< the run's CVODE statistics up to times[0]
  long snapshot_index = 0;    //!< the snapshot of times[0]
  double wall_s = 0.0;        //!< wall time the run used up to times[0] [s]
};

//! The restart point (a whole checkpoint, else its predecessor, compatible with the
//! scene: the notes of what the restart changes go to stderr), the snapshot times, the
//! output (new, or the checkpoint's run's file cut to its snapshots, its fields declared
//! again) and the initial state; prints the run's banner. Throws before any file is
//! touched when the scene cannot continue the checkpoint.
//! `preloaded`: the restart point when run_scene has read it already (a restart given no
//! scene file takes its scene from it).
RunStart start_run(const RunArgs& a, const Config& cfg, Simulation& sim,
                   std::optional<RestartPoint> preloaded);

//! After a restart, once the diagnostics have read the kept rows: the rows the output
//! lost before it (a run killed while HDF5 flushed the file), said aloud and recorded in
//! the root attribute `restarts`; and why the output could not be rebuilt as a copy.
void report_restart_losses(RunOutput& out, const RunDiagnostics& diag);

}  // namespace panoptic
