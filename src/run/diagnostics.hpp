#pragma once
//! What a run reports besides its snapshots (spec §8; issue "disk-wide answer"):
//! - /timeseries: the pebble flux through the monitored radii, the cumulative mass
//! through
//!   each and the mass budget, sampled on a time grid finer than the snapshots (at the
//!   first CVODE step past each sample time, so it costs one flux evaluation per sample);
//! - the time of first planetesimal formation in every cell (checked after every step);
//! - /summary at the end: planetesimal mass and radial range by channel, first-formation
//!   time over r, pebble mass through the snow line and r_in, final dust mass, a size
//!   distribution's largest top-bin fraction (warned about above kTopBinWarning);
//!   printed too.
#include <map>
#include <span>
#include <string>
#include <vector>

#include "src/io/output_entry.hpp"
#include "src/solver/physics_module.hpp"

namespace panoptic {

class Simulation;
class RunOutput;

class RunDiagnostics {
 public:
  //! `t_start` [s]: 0 for a new run; for a restart, the checkpoint's time (the samples
  //! after it are cut from /timeseries, the first-formation times are read back from the
  //! last kept snapshot).
  RunDiagnostics(const Simulation& sim, RunOutput& out, double t_start);
  //! After every CVODE step.
  void on_step(double t, std::span<const double> y);
  //! Writes the buffered /timeseries rows (call before the snapshot's flush).
  void flush();
  //! The diagnostics' own snapshot fields, declared here as the modules declare theirs
  //! (OutputField, filled from the run's history rather than from one state): the time of
  //! first planetesimal formation, when a channel is on.
  static std::vector<OutputField> output_fields(const Simulation& sim);
  //! The /timeseries stacks the constructor declares and flush() appends to, and the
  //! group's attribute (the names of the mass budget's columns): their one declaration.
  static std::vector<OutputField> timeseries_fields(const Simulation& sim);
  static std::vector<OutputAttribute> timeseries_attributes(const Simulation& sim);
  //! The /summary datasets finish() writes, in its order (fill unused: finish() has the
  //! values).
  static std::vector<OutputField> summary_fields(const Simulation& sim);
  //! Adds the diagnostics' snapshot fields (output_fields) to `fields`.
  void add_snapshot_fields(std::map<std::string, std::vector<double>>& fields) const;
  //! At each snapshot (time t [s]) with its fields: a size distribution's largest
  //! fraction of a cell's dust in the mass grid's top bin so far, which finish()
  //! writes and warns about.
  void note_snapshot(double t, const std::map<std::string, std::vector<double>>& fields);
  //! Writes /summary and returns it as text for the terminal.
  std::string finish(double t, std::span<const double> y);
  //! After a restart: the kept /timeseries rows the file had lost (mark_lost_rows), now
  //! NaN; "" when none.
  const std::string& lost_rows() const { return lost_; }

 private:
  void sample(double t, std::span<const double> y);
  //! note_snapshot's work on one snapshot's top-bin fractions (per cell) at time t [s].
  void note_top_bin(double t, std::span<const double> fraction);

  const Simulation& sim_;
  RunOutput& out_;
  std::vector<double> sample_times_;  //!< [s]
  std::size_t next_sample_ = 0;
  double last_sample_t_ = -1.0;  //!< time of the last row sampled by this process [s]
  std::string lost_;
  std::vector<std::vector<double>> rows_time_, rows_flux_, rows_mass_, rows_budget_;
  std::vector<double> t_first_;  //!< per cell, first planetesimal formation [s]
  //! a size distribution's largest top-bin fraction over the snapshots (note_snapshot),
  //! with its cell's radius [au] and time [yr]
  struct TopBin {
    double fraction = 0.0, r_au = 0.0, t_yr = 0.0;
  } top_bin_;
  std::vector<double> threshold_;  //!< per cell: Sigma_pl that counts as formed
};

}  // namespace panoptic
