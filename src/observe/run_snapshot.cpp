#include "src/observe/run_snapshot.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <tuple>

#include "src/core/error.hpp"
#include "src/io/h5.hpp"

namespace fs = std::filesystem;

namespace panoptic {
namespace {

//! Row k (of `width` values) of the dataset /snapshots/<name>.
std::vector<double> row(hid_t g, const std::string& name, long k, std::size_t width,
                        const std::string& file) {
  const std::vector<double> all = h5::read_doubles(g, name);
  if (all.size() < (static_cast<std::size_t>(k) + 1) * width)
    throw ConfigError(file + ": /snapshots/" + name +
                      " has fewer rows than /snapshots/time" +
                      ": the file is damaged or not a panoptic run");
  return {all.begin() + static_cast<std::ptrdiff_t>(k * width),
          all.begin() + static_cast<std::ptrdiff_t>((k + 1) * width)};
}

}  // namespace

RunSnapshot read_run_snapshot(const std::string& file, double time_yr) {
  h5::quiet_errors();
  std::error_code ec;
  if (!fs::is_regular_file(file, ec))
    throw ConfigError(file +
                      (fs::exists(file, ec) ? ": not a regular file (a directory?)"
                                            : ": no such file") +
                      "; give the HDF5 output of `panoptic run`");
  h5::Handle f;
  try {
    f = h5::open_file(file, false);
  } catch (const IoError&) {
    throw ConfigError(file + ": not an HDF5 file; give the output of `panoptic run`");
  }
  for (const char* p :
       {"snapshots/time", "snapshots/sigma_d", "grid/r_c", "grid/r_f", "disk/T"})
    if (!h5::exists(f.get(), "snapshots") || !h5::exists(f.get(), "grid") ||
        !h5::exists(f.get(), "disk") || !h5::exists(f.get(), p) ||
        !h5::has_attr(f.get(), "config_toml"))
      throw ConfigError(
          file + ": not a panoptic run (no /" + p +
          " or no config_toml attribute); give the output of `panoptic run`");
  RunSnapshot s;
  s.config_toml = h5::get_attr_string(f.get(), "config_toml");
  if (h5::has_attr(f.get(), "run_id")) s.run_id = h5::get_attr_string(f.get(), "run_id");
  h5::Handle grid = h5::open_group(f.get(), "grid");
  s.r_c_au = h5::read_doubles(grid.get(), "r_c");
  s.r_f_au = h5::read_doubles(grid.get(), "r_f");
  h5::Handle disk = h5::open_group(f.get(), "disk");
  s.T = h5::read_doubles(disk.get(), "T");
  if (h5::has_attr(disk.get(), "r_snow_au"))
    s.r_snow_au = h5::get_attr_double(disk.get(), "r_snow_au");
  const std::size_t n = s.r_c_au.size();
  if (n == 0 || s.r_f_au.size() != n + 1 || s.T.size() != n)
    throw ConfigError(file + ": /grid and /disk/T disagree in size: damaged file");
  h5::Handle snap = h5::open_group(f.get(), "snapshots");
  const std::vector<double> times = h5::read_doubles(snap.get(), "time");
  if (times.empty()) throw ConfigError(file + ": holds no snapshot yet");
  // time must lie within the run (a hair of round-off allowed at the end)
  const double t_last = times.back();
  if (!(time_yr >= 0.0) || time_yr > t_last * (1.0 + 1e-9))
    throw ConfigError("--time-yr " + num(time_yr) + ": outside the run (snapshots from " +
                      num(times.front()) + " to " + num(t_last) + " yr in " + file +
                      "); choose a time in that range");
  long best = 0;
  for (std::size_t k = 1; k < times.size(); ++k)
    if (std::abs(times[k] - time_yr) < std::abs(times[best] - time_yr))
      best = static_cast<long>(k);
  s.index = best;
  s.time_yr = times[best];
  s.sigma_d = row(snap.get(), "sigma_d", best, n, file);
  // a single-size run with growth writes its particle's a, phi and rho_int; a size
  // distribution the mass-dominating bin's a, and phi and rho_int only with porous bins
  if (h5::exists(snap.get(), "a")) s.a = row(snap.get(), "a", best, n, file);
  if (h5::exists(snap.get(), "phi")) {
    s.phi = row(snap.get(), "phi", best, n, file);
    s.rho_int = row(snap.get(), "rho_int", best, n, file);
  }
  if (h5::exists(snap.get(), "sigma")) {
    if (!h5::exists(grid.get(), "m_bins"))
      throw ConfigError(file + ": /snapshots/sigma without /grid/m_bins: damaged file");
    s.m_bins = h5::read_doubles(grid.get(), "m_bins");
    const std::size_t width = n * s.m_bins.size();
    if (width == 0) throw ConfigError(file + ": /grid/m_bins is empty: damaged file");
    s.sigma_bins = row(snap.get(), "sigma", best, width, file);
    if (h5::exists(snap.get(), "phi_bins"))
      s.phi_bins = row(snap.get(), "phi_bins", best, width, file);
  }
  return s;
}

void check_observable(const RunSnapshot& s, const std::string& file, bool a_cm_given) {
  // a snapshot of a run that failed can hold NaN (its last rows): say so, rather than
  // write an observation of NaN with exit 0 (a bin's value names its cell: the bins are
  // cell by cell, nb of them in each)
  const std::size_t one = 1, nb = std::max(one, s.m_bins.size());
  for (const auto& [name, v, per_cell] : {std::tuple{"sigma_d", &s.sigma_d, one},
                                          {"a", &s.a, one},
                                          {"phi", &s.phi, one},
                                          {"rho_int", &s.rho_int, one},
                                          {"T", &s.T, one},
                                          {"sigma", &s.sigma_bins, nb},
                                          {"phi_bins", &s.phi_bins, nb}})
    for (std::size_t i = 0; i < v->size(); ++i)
      if (!std::isfinite((*v)[i]))
        throw ConfigError(file + ": snapshot " + std::to_string(s.index) +
                          " (t = " + num(s.time_yr) + " yr) has " + name + " = " +
                          num((*v)[i]) + " at r = " + num(s.r_c_au[i / per_cell]) +
                          " au: not a state to observe (did the run fail? its exit code "
                          "and /solver status say); choose another --time-yr");
  if (s.a.empty() && !a_cm_given)
    throw ConfigError(file +
                      ": the run has no particle sizes (/snapshots/a: growth was off); "
                      "give one with --a-cm");
}

}  // namespace panoptic
