#pragma once
//! The HDF5 file of one run (style guide "Output"): root attributes (config_toml,
//! git_sha, version, scene), /grid, /disk, time-stacked /snapshots, /solver. Flushed
//! after every snapshot, so a run killed at any moment between snapshots leaves a
//! readable file.
#include <filesystem>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "src/h5.hpp"

namespace panoptic {

struct SolverStats;

struct RunMetadata {
  std::string scene;        //!< scene name (file stem)
  std::string config_toml;  //!< the resolved scene
  std::string git_sha;
  std::string version;
};

class RunOutput {
 public:
  //! Creates the file (and its directory). An existing file is an IoError unless
  //! `overwrite`: a run never silently replaces data.
  RunOutput(const std::filesystem::path& path, bool overwrite, const RunMetadata& meta);
  ~RunOutput();

  const std::filesystem::path& path() const { return path_; }
  hid_t file() const { return file_.get(); }

  //! Writes a fixed dataset /<group>/<name> (group created on first use).
  void write_static(const std::string& group, const std::string& name,
                    std::span<const double> data, const std::string& units,
                    const std::string& description);
  void set_group_attr(const std::string& group, const std::string& name, double value);

  //! Declares /snapshots/<name>, `width` values per snapshot (0: a scalar per snapshot).
  void add_field(const std::string& name, std::size_t width, const std::string& units,
                 const std::string& description);
  //! Appends one snapshot: /snapshots/time and every declared field, then flushes.
  void write_snapshot(double t_yr,
                      const std::map<std::string, std::vector<double>>& fields);
  std::size_t n_snapshots() const { return n_snapshots_; }

  //! Writes /solver attributes (overwritten on every call) and flushes.
  void write_solver(const SolverStats& stats, double wall_s, const std::string& status);
  void flush();

 private:
  void ensure_group(const std::string& group);

  std::filesystem::path path_;
  h5::Handle file_;
  std::map<std::string, std::size_t> fields_;
  std::size_t n_snapshots_ = 0;
};

}  // namespace panoptic
