#pragma once
//! `panoptic scan SCAN.toml -o DIR`: expand the scan into DIR/manifest.toml, validate
//! every run's scene, then execute the runs not yet complete: serially, with -j N local
//! workers, under MPI (mpirun -n N; rank 0 hands out run ids one at a time, so uneven run
//! costs balance), or one entry (--task I, for job arrays); finally rebuild
//! DIR/summary.h5 and DIR/summary.csv from the run files. Each run is a child process
//! (src/scan/scan_exec.hpp).
#include <optional>
#include <string>

namespace panoptic {

struct ScanOptions {
  std::string scan_file;
  std::string dir;  //!< -o
  int jobs = 1;     //!< -j: concurrent runs per process
  //! --task I as given (checked by run_scan: an integer id of the manifest; an empty
  //! value, an unset $SLURM_ARRAY_TASK_ID, is refused, not taken as "every run")
  std::optional<std::string> task;
  bool dry_run = false;
  bool force = false;    //!< replace a manifest that differs
  std::string run_exe;   //!< the panoptic that runs the scenes (default: this one)
  std::string progress;  //!< --progress INTERVAL, passed to every run ("" = none)
  int threads = 1;  //!< --threads N, passed to every run (src/core/worker_threads.hpp)
};

//! Returns the exit code: 0 every run complete, 3 some runs failed (recorded in the
//! summary), 75 stopped by SIGINT/SIGTERM (rerun to continue), 2 bad scan, 4 I/O error.
int run_scan(const ScanOptions& options);

//! True when this panoptic was built with MPI.
bool scan_has_mpi();

}  // namespace panoptic
