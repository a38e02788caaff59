#pragma once
//! The reader of `panoptic observe`: one snapshot of a run's output file, with the grid,
//! the gas temperature and the scene it was run with; of a size-distribution run
//! (model.kind = "distribution") also its bins.
#include <limits>
#include <string>
#include <vector>

namespace panoptic {

//! What `observe` needs of one snapshot of a run file.
struct RunSnapshot {
  std::string config_toml, run_id;
  long index = 0;                                                   //!< row of /snapshots
  double time_yr = 0.0;                                             //!< its time
  std::vector<double> r_c_au, r_f_au, T, sigma_d, a, phi, rho_int;  //!< a etc. empty
                                                                    //!< without growth
  double r_snow_au = std::numeric_limits<double>::quiet_NaN();
  //! The size distribution (empty for a single-size run): /grid/m_bins [g], and the
  //! snapshot's sigma(r, m) [g cm^-2] and phi(r, m) (empty: compact bins), cell by cell
  //! with the bins of m_bins in each, as the run writes them.
  std::vector<double> m_bins, sigma_bins, phi_bins;
  bool distribution() const { return !m_bins.empty(); }
};

//! The snapshot of `file` nearest `time_yr`. Throws ConfigError, naming the fix, for a
//! file that is not a panoptic run (missing, not HDF5, without its groups), a damaged
//! one, or a time outside the run.
RunSnapshot read_run_snapshot(const std::string& file, double time_yr);

//! Throws ConfigError when the snapshot cannot be observed: a value that is not finite
//! (the last rows of a run that failed, the bins included), or no particle sizes without
//! --a-cm.
void check_observable(const RunSnapshot& s, const std::string& file, bool a_cm_given);

}  // namespace panoptic
