#pragma once
//! The HDF5 file of one run (style guide "Output"): root attributes (config_toml,
//! git_sha, version, scene), /grid, /disk, time-stacked /snapshots, /solver. Flushed
//! after every snapshot and, once set up, written in HDF5's SWMR mode (start_appending),
//! so a run killed at any moment, in a flush included, leaves a file that opens and holds
//! every snapshot flushed before.
#include <filesystem>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "src/core/digest.hpp"
#include "src/core/error.hpp"
#include "src/io/h5.hpp"
#include "src/io/output_entry.hpp"

namespace panoptic {

struct SolverStats;

struct RunMetadata {
  std::string scene;        //!< scene name (file stem)
  std::string config_toml;  //!< the resolved scene
  std::string git_sha;
  std::string version;
};

//! Continue the output of an interrupted run: keep its first `n_snapshots` snapshots.
//! `digests`: the checkpoint's digests of the rows written up to it (empty for a
//! checkpoint written before they were kept), to verify the kept rows against.
struct ContinueRun {
  std::size_t n_snapshots = 0;
  RowDigests digests;
};

//! Writes NaN into the rows below `rows` of every dataset of /<group> that the file has
//! lost or garbled: rows whose chunk the file no longer has (they would read back as 0),
//! and rows whose digest differs from the one in `expected` (when it has the dataset):
//! a writer killed while HDF5 flushed its unjournaled chunk index can lose rows flushed
//! long before, or leave their index entries pointing at other data. Returns them, e.g.
//! "/snapshots/St row 51", "; "-separated; "" when none. Stores in `kept` the digests
//! of the rows below `rows` as they are now.
std::string mark_lost_rows(hid_t file, const std::string& group, hsize_t rows,
                           const RowDigests& expected, RowDigests& kept);

class RunOutput {
 public:
  //! Creates the file (and its directory). An existing file is an IoError unless
  //! `overwrite`: a run never silently replaces data. The file gets a fresh random
  //! root attribute run_id, which its checkpoints record.
  RunOutput(const std::filesystem::path& path, bool overwrite, const RunMetadata& meta);
  //! Continues an existing output (restart) in a fresh copy of it (rebuild_note), which
  //! start_appending puts in its place (until then the output is as it was): every
  //! /snapshots stack is cut to its first `keep.n_snapshots` rows (rows after them were
  //! written after the checkpoint and will be written again) and the declared fields are
  //! those in the file. IoError when the file is missing or holds fewer snapshots.
  RunOutput(const std::filesystem::path& path, ContinueRun keep);
  RunOutput(RunOutput&&) = default;  // (a moved-from output has no file, nothing to do)
  //! After a restart: the kept /snapshots rows the file had lost or garbled (see
  //! mark_lost_rows), now NaN; "" when none.
  const std::string& lost_rows() const { return lost_; }
  //! After a restart: the fields this run writes that the checkpoint's run did not (an
  //! earlier panoptic), with their kept rows, now NaN; "" when none.
  const std::string& new_fields() const { return new_fields_; }
  //! After a restart: "" when the file was rebuilt as a fresh copy before it was
  //! continued (run_output.cpp, rebuild), else why it could not be (it is then continued
  //! in place).
  const std::string& rebuild_note() const { return rebuild_note_; }
  //! After a restart: when `e` is HDF5's own failure on this file (the file is damaged
  //! beyond what a restart repairs), throws an IoError that says so, names the file and
  //! the fix; otherwise returns (the caller rethrows `e`).
  void throw_if_damaged(const IoError& e) const;
  //! After a restart: cuts nothing, but verifies the first `rows` rows of every dataset
  //! of /<group> against the checkpoint's digests (mark_lost_rows), writes NaN into those
  //! lost and returns them; the digests of the kept rows continue from there.
  std::string keep_rows(const std::string& group, hsize_t rows);
  //! Digests of every row of /snapshots and of the series written so far (kept rows
  //! included after a restart), by "group/name": what a checkpoint records.
  const RowDigests& row_digests() const { return digests_; }
  ~RunOutput();

  const std::filesystem::path& path() const { return path_; }
  //! The HDF5 file, to read, or to change before start_appending.
  hid_t file() const { return file_.get(); }
  //! Root attribute run_id ("" for a file written before run ids existed).
  const std::string& run_id() const { return run_id_; }
  //! /snapshots/time [yr], every row.
  std::vector<double> times_yr() const;
  //! Sets a root string attribute (e.g. config_toml after a restart) and flushes.
  void set_root_attr(const std::string& name, const std::string& value);
  //! A root string attribute, "" when absent.
  std::string root_attr(const std::string& name) const;

  //! Writes a fixed dataset /<group>/<name> (group created on first use; an existing
  //! dataset of that name is replaced).
  void write_static(const std::string& group, const std::string& name,
                    std::span<const double> data, const std::string& units,
                    const std::string& description);
  //! Writes an attribute of the root or of a group (created on first use).
  void write_attribute(const OutputAttribute& attribute);
  //! Declares an extendible dataset /<group>/<name> of `width` values per row (0: scalar
  //! rows), for series not tied to the snapshots (e.g. /timeseries).
  void add_series(const std::string& group, const std::string& name, std::size_t width,
                  const std::string& units, const std::string& description);
  //! Appends one row to a series declared with add_series (no flush: the next snapshot
  //! flushes).
  void append_series(const std::string& group, const std::string& name,
                     std::span<const double> row);

  //! Declares /snapshots/<name>, `width` values per snapshot (0: a scalar per snapshot).
  //! For a continued output (restart), a field already in the file is kept; one the
  //! file lost (unreadable, left out of the restart's copy) is recreated with NaN rows
  //! up to the checkpoint's snapshot, and named in lost_rows(); one the checkpoint's run
  //! never wrote (an earlier panoptic) likewise, named in new_fields(). `compressed`: its
  //! rows are deflated (h5::create_stack).
  void add_field(const std::string& name, std::size_t width, const std::string& units,
                 const std::string& description, bool compressed = false);
  //! Appends one snapshot: /snapshots/time and every declared field, then flushes.
  void write_snapshot(double t_yr,
                      const std::map<std::string, std::vector<double>>& fields);
  std::size_t n_snapshots() const { return n_snapshots_; }

  //! Called once the file holds the groups, datasets and attributes that the snapshots
  //! need: flushes, and from there on writes the file in SWMR mode
  //! (h5::start_swmr_write). Returns "" or, when HDF5 cannot (an output in the HDF5 1.8
  //! format that a restart could not rebuild, a file system on which HDF5 cannot lock
  //! it), why: the file is then written as before, and a run killed in the middle of a
  //! flush can leave it unreadable.
  std::string start_appending();
  //! Whether rows go to the file in SWMR mode now. Adding a group, dataset or attribute
  //! (write_static, set_*attr, add_*, write_solver: the end of a run) leaves the mode
  //! first, since HDF5 1.10 does not support those in it: from there on the writes go
  //! to a copy of the file that close() puts in its place (leave_swmr).
  bool in_swmr_mode() const { return swmr_; }
  //! Writes /solver attributes (overwritten on every call) and flushes.
  void write_solver(const SolverStats& stats, double wall_s, const std::string& status);
  //! The root attributes the constructor writes (the scene's metadata and `run_id`).
  static std::vector<OutputAttribute> root_attributes(const RunMetadata& meta,
                                                      const std::string& run_id);
  //! The /snapshots/time stack every output has (the other stacks are declared by the
  //! model, add_field).
  static OutputEntry snapshot_time();
  //! The /solver attributes write_solver writes.
  static std::vector<OutputAttribute> solver_attributes(const SolverStats& stats,
                                                        double wall_s,
                                                        const std::string& status);
  void flush();
  //! Flushes and closes the file (after leave_swmr: the copy, which then replaces the
  //! output). IoError when that fails: the output then holds every row, without what
  //! was written after the mode was left. The destructor closes too, and only warns.
  void close();

 private:
  void ensure_group(const std::string& group);
  void leave_swmr();
  //! Closes the file set up aside (staging_) and removes it: a set-up that failed or
  //! was never started; the file at path_ is as it was.
  void discard_staging();

  std::filesystem::path path_;
  //! Where the file is set up, until start_appending renames it to path_: a new
  //! output's `<out>.setup.tmp`, a restart's fresh copy `<out>.restart.tmp` (empty
  //! after, and for an output continued in place).
  std::filesystem::path staging_;
  bool overwrite_ = false;
  bool swmr_ = false;
  //! The copy that the closing writes go to (leave_swmr), empty before.
  std::filesystem::path finishing_;
  h5::Handle file_;
  std::map<std::string, std::size_t> fields_;
  std::size_t n_snapshots_ = 0;
  std::string lost_;
  std::string new_fields_;
  std::string run_id_;
  std::string rebuild_note_;
  RowDigests digests_;          //!< of the rows in the file
  RowDigests restart_digests_;  //!< the checkpoint's, to verify the kept rows
};

}  // namespace panoptic
