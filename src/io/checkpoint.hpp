#pragma once
//! Checkpoints: the state of a run at a snapshot time, enough to continue it with
//! `panoptic run SCENE --restart out/<run>.chk.h5` and write the same snapshots,
//! bit for bit, as the run that was never stopped (src/run/README.md, Restart).
//!
//! A checkpoint is a small HDF5 file next to the output: `<stem>.chk.h5`, the one before
//! kept as `<stem>.chk.prev.h5`. It holds the raw CVODE state y at t, the layout
//! signature, the resolved scene, the snapshot index reached, the solver statistics, the
//! output file and its run_id, the digest of every row written to the output so far
//! (group row_digests: a restart verifies the rows it keeps against them), a checksum
//! of all of these (FNV-1a, 64 bit) and, written last, a completeness flag. It is written
//! to `<stem>.chk.h5.tmp`, fsynced, and renamed over `<stem>.chk.h5` (then the directory
//! is fsynced), so that at every moment of a crash `<stem>.chk.h5` is a whole checkpoint,
//! the new one or the old one.
//!
//! Which checkpoint a restart uses and whether a scene may continue it:
//! src/run/restart.hpp. Bit-for-bit continuation rests on two rules (src/run/run.cpp):
//! checkpoints are taken only at snapshot times, and with solver.reinit_at_snapshots
//! every run reinitialises CVODE at every snapshot time, so CVODE's history (which cannot
//! be saved) is never used across a snapshot.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "src/core/digest.hpp"
#include "src/solver/solver_stats.hpp"

namespace panoptic {

struct Checkpoint {
  double t = 0.0;                //!< simulated time of the state [s], a snapshot time
  std::vector<double> y;         //!< the raw CVODE state at t (StateLayout order)
  std::string layout_signature;  //!< StateLayout::signature() of the run
  long n_cells = 0;              //!< radial cells
  long snapshot_index = 0;       //!< /snapshots row of t (0 = t = 0); rows after it go
  std::string config_toml;       //!< the resolved scene (Config::resolved_toml)
  SolverStats stats;             //!< CVODE statistics of the run up to t
  double wall_s = 0.0;           //!< wall time the run has used up to t [s]
  std::string output_file;       //!< absolute path of the run's HDF5 output
  std::string run_id;            //!< the output's root attribute run_id
  std::string git_sha;           //!< of the program that wrote the checkpoint
  std::string version;
  //! Digests of the output's rows written up to the checkpoint (RunOutput::row_digests),
  //! to verify them on restart; empty in checkpoints written before they were kept.
  RowDigests row_digests;
};

//! The checksum of every field of a checkpoint except the strings git_sha and version:
//! verified on load, so a flipped bit anywhere in the payload is noticed.
std::uint64_t checkpoint_checksum(const Checkpoint& chk);

//! `out/run.h5` -> `out/run.chk.h5`.
std::filesystem::path checkpoint_path(const std::filesystem::path& output);
//! `out/run.chk.h5` -> `out/run.chk.prev.h5` (the fallback).
std::filesystem::path previous_checkpoint_path(const std::filesystem::path& checkpoint);

//! Writes `chk` atomically to `path` (see the file comment). A checkpoint already at
//! `path` becomes the previous one, `<stem>.chk.prev.h5`, if it is readable and whole;
//! a damaged one is replaced without being kept, so the fallback stays good. Throws
//! IoError naming the file; no temporary file is left behind.
void write_checkpoint(const std::filesystem::path& path, const Checkpoint& chk);

//! Whether `path`, a checkpoint path, holds a file that panoptic wrote as a checkpoint
//! and a new run may replace: an HDF5 file with the checkpoint format attribute (any
//! version), a damaged one (the HDF5 signature, but HDF5 cannot open it) or an empty
//! file; false for anything else (a text file, another run's output). main.cpp.
bool is_checkpoint_file(const std::filesystem::path& path);

//! Reads and verifies a checkpoint: throws IoError saying what is wrong (missing,
//! truncated or not HDF5, incomplete, checksum mismatch) and naming the file.
Checkpoint read_checkpoint(const std::filesystem::path& path);

}  // namespace panoptic
