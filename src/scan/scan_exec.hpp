#pragma once
//! One run of a scan as a child process: `panoptic run SCENE --set ... -o
//! DIR/runs/run_00017.h5 --overwrite`, its stdout and stderr in run_00017.log and .err,
//! and, when it ends, its outcome in run_00017.status (exit code or signal, wall time,
//! worker, the tail of stderr). A run that crashes, even by SIGSEGV or abort(), ends only
//! its own process: the scan records it and goes on. The child gets SIGKILL when the
//! process that started it dies (PR_SET_PDEATHSIG), so a killed scan leaves no run
//! behind to race with the rerun.
#include <sys/types.h>

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace panoptic {

//! Everything a worker needs to execute one run (sent as bytes to MPI workers).
struct ScanTask {
  long id = 0;
  std::string name;               //!< run_00017
  std::vector<std::string> argv;  //!< the child's command line, argv[0] = executable
  std::string h5, log, err, status;
  //! the run's resolved scene (its manifest entry's): a checkpoint is continued only
  //! when it holds this scene
  std::string config_toml;

  std::string serialize() const;
  static ScanTask deserialize(std::string_view bytes);
};

//! What a worker records about a finished run (DIR/runs/<name>.status).
struct RunRecord {
  long id = 0;
  std::string outcome;  //!< "completed", "failed", "interrupted"
  int exit_code = 0;    //!< the child's exit code; -N when killed by signal N
  double wall_s = 0.0;  //!< wall time of the child process
  std::string worker;   //!< "local/0", "rank2/0"
  std::string host;
  std::string error;  //!< why it failed: signal and the last lines of its stderr
};

//! The path of this executable (/proc/self/exe).
std::string self_executable();

//! Starts the run of `task` (removing a status file left by an earlier attempt) and
//! returns the child's pid. Throws IoError when fork fails.
pid_t start_task(const ScanTask& task);

//! The record of a run whose child ended with `wait_status` (waitpid), written
//! atomically to task.status.
RunRecord finish_task(const ScanTask& task, int wait_status, double wall_s,
                      const std::string& worker);

//! True when the run of `task` can be continued from its checkpoint bit for bit: its
//! output exists and its checkpoint (or, when that one is unreadable, the previous
//! checkpoint, which `panoptic run --restart` falls back on) holds exactly the run's
//! scene, task.config_toml. A checkpoint of another scene (after --force: another end
//! time or solver setting, which a restart would accept) is not continued: the run
//! starts again from t = 0, as a new scan of its manifest would run it.
bool can_continue(const ScanTask& task);

//! This machine's host name ("" when it cannot be read): a run's worker, and part of a
//! temporary file's name that processes on other nodes must not share.
std::string hostname();

//! Reads a status file; nullopt when absent or unreadable.
std::optional<RunRecord> read_record(const std::filesystem::path& status);

//! What a run's HDF5 file holds, checked, not assumed from its existence.
struct RunInspection {
  bool complete = false;
  std::string why;  //!< why it is not complete
  long steps = -1;  //!< /solver nst
  double wall_s = -1.0;
  //! /summary scalars (t_first_pl reduced to its minimum over the cells, NaN: none).
  std::map<std::string, double> summary;
  //! the `units` attribute of each /summary dataset (t_first_pl_min: t_first_pl's)
  std::map<std::string, std::string> units;
};

//! Complete means: the file opens, its root attribute config_toml is `config_toml` (the
//! run of this manifest entry, not of another scan or scene), /solver status is
//! "completed", /summary exists and the last snapshot is at `t_end_yr`.
RunInspection inspect_run(const std::filesystem::path& h5, const std::string& config_toml,
                          double t_end_yr);

}  // namespace panoptic
