#pragma once
//! `panoptic run`: a scene integrated to its snapshot times, written to its HDF5 output,
//! checkpointed, stoppable (SIGINT, SIGTERM, --max-wall) and restartable. The steps are
//! in run.cpp; README.md of this folder describes them.
#include <string>
#include <vector>

namespace panoptic {

//! The command line of `panoptic run`.
struct RunArgs {
  std::string program;  //!< argv[0], for the restart command we print
  std::string scene;
  //! the overrides applied on top of the scene file: the preset's, then `sets`
  std::vector<std::string> overrides;
  std::vector<std::string> sets;  //!< the --set items alone
  std::string output;             //!< -o
  bool overwrite = false;
  std::string restart;   //!< --restart CHK.h5
  std::string max_wall;  //!< --max-wall DURATION
  //! --max-wall was given, so that `--max-wall ""` (an unset variable) is refused
  bool max_wall_given = false;
  std::string preset;  //!< --fast / --accurate: "fast", "accurate" or ""
  //! --progress INTERVAL (a duration, as --max-wall), else PANOPTIC_PROGRESS; "" = none
  std::string progress;
  //! where `progress` came from, for its error message: "--progress" or
  //! "PANOPTIC_PROGRESS="
  std::string progress_source = "--progress";
  //! --threads N: the worker threads that share the cells (src/core/worker_threads.hpp)
  int threads = 1;
};

//! Runs the scene; returns the exit code (0, or exit_codes::kStopped when stopped with a
//! checkpoint). Throws the Error of a failure.
int run_scene(const RunArgs& args);

}  // namespace panoptic
