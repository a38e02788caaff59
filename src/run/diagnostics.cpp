#include "src/run/diagnostics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "src/core/units.hpp"
#include "src/io/h5.hpp"
#include "src/io/run_output.hpp"
#include "src/model/simulation.hpp"

namespace panoptic {

using units::kMearth;
using units::kYr;

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// A cell has formed planetesimals once its Sigma_pl exceeds 1e-6 of the largest initial
// Sigma_d of the disk. (A threshold relative to the cell's own dust would count the
// outer edge of an LBP disk, where the gas is so thin that monomers already have
// St > St_pl and a negligible mass is converted at once.)
constexpr double kFormedFraction = 1e-6;
// 1 M_earth / Myr in g/s (spec §8: 1.892e14 g/s)
constexpr double kMearthPerMyr = units::kMearth / units::kMyr;
// the snapshot field of the first-formation times
constexpr const char* kFirstFormation = "t_first_pl";
// A size distribution whose top bin held more than this fraction of a cell's dust at a
// snapshot is warned about: products beyond the top bin do not stick (as in DustPy),
// so the largest aggregates are missing and their parents pile up in the top bin. The
// porous DustPy disk on DustPy's grid to 1e5 g held up to 7e-3 there from 3e4 yr; on a
// grid to 1e9 g 3e-3 of a cell's dust lay above 1e5 g, Sigma_d and the mass-dominating
// St the same to 1e-3 (tests/bench/results/dustpy_anchor.md, porous section).
constexpr double kTopBinWarning = 1e-3;
constexpr const char* kTopBinMax = "top_bin_fraction_max";

// The /summary dataset of the pebble mass through a monitor: the snow line's and
// r_in's have one, "" for the others.
std::string summary_pebble_key(const PebbleMonitor& mon) {
  if (mon.name == "r_in") return "m_peb_r_in";
  if (mon.name == "snow line") return "m_peb_snowline";
  return "";
}
}  // namespace

std::vector<OutputField> RunDiagnostics::output_fields(const Simulation& sim) {
  if (!sim.planetesimals()) return {};
  return {{kFirstFormation, static_cast<std::size_t>(sim.grid().n_cells()), "yr",
           "time of first planetesimal formation in each cell so far (NaN: not yet; "
           "formed: Sigma_pl > /summary/formed_threshold)",
           nullptr}};
}

std::vector<OutputField> RunDiagnostics::timeseries_fields(const Simulation& sim) {
  const std::size_t nm = sim.pebble_monitors().size();
  // one column per budget term (Simulation::budget_terms), then |sum - initial|
  std::string labels;
  for (const auto& term : sim.budget_terms()) labels += term.label + ", ";
  return {{"time", 0, "yr", "sample times (first CVODE step past each)", nullptr},
          {"pebble_flux", nm, "M_earth Myr^-1",
           "inward dust mass flow through each /pebbles/r_au", nullptr},
          {"m_through", nm, "M_earth", "cumulative dust mass through each /pebbles/r_au",
           nullptr},
          {"mass_budget", sim.budget_terms().size() + 1, "M_earth",
           "dust " + labels +
               "|sum - initial| (columns; attribute mass_budget_columns of /timeseries)",
           nullptr}};
}

std::vector<OutputAttribute> RunDiagnostics::timeseries_attributes(
    const Simulation& sim) {
  std::string names;
  for (const auto& term : sim.budget_terms()) names += term.name + ";";
  return {{"timeseries", "mass_budget_columns", "",
           "names of the columns of mass_budget (;-separated), error last",
           names + "error"}};
}

std::vector<OutputField> RunDiagnostics::summary_fields(const Simulation& sim) {
  std::vector<OutputField> fields;
  auto scalar = [&](const std::string& name, const std::string& units,
                    const std::string& what) {
    fields.push_back({name, 0, units, what, nullptr});
  };
  for (const std::string ch : {"coag", "si"}) {
    scalar("m_pl_" + ch, "M_earth", "planetesimal mass formed by channel " + ch);
    scalar("r_min_pl_" + ch, "au", "innermost cell with planetesimals (" + ch + ")");
    scalar("r_max_pl_" + ch, "au", "outermost cell with planetesimals (" + ch + ")");
  }
  fields.push_back({kFirstFormation, static_cast<std::size_t>(sim.grid().n_cells()), "yr",
                    "time of first planetesimal formation in each cell (NaN: never)",
                    nullptr});
  for (const PebbleMonitor& mon : sim.pebble_monitors())
    if (const std::string key = summary_pebble_key(mon); !key.empty())
      scalar(key, "M_earth", "pebble mass that crossed " + mon.name + " inward");
  scalar("formed_threshold", "g cm^-2",
         "Sigma_pl above which a cell counts as having formed planetesimals (1e-6 of the "
         "largest initial Sigma_d)");
  scalar("m_dust_final", "M_earth", "dust left on the grid");
  if (sim.distribution() != nullptr)
    scalar(kTopBinMax, "",
           "largest fraction of a cell's dust in the mass grid's top bin at a snapshot "
           "(snapshots/top_bin_fraction): products beyond it do not stick, so above 1e-3 "
           "(a warning) the largest aggregates are missing; raise model.m_max_g");
  scalar("budget_error", "",
         "|sum of the budget terms (mass_budget_columns of /timeseries) - initial| / "
         "initial");
  return fields;
}

RunDiagnostics::RunDiagnostics(const Simulation& sim, RunOutput& out, double t_start)
    : sim_(sim), out_(out) {
  const auto& cfg = sim.config();
  const auto snaps = sim.output_times();
  const long per = cfg.integer("pebbles.samples_per_snapshot");
  // sample grid: `per` log-spaced samples in every snapshot interval (linear in the
  // first), the last exactly at the snapshot: CVODE's step lands there (its stop time),
  // so the sample is taken at the snapshot's state, and finish() does not repeat it at
  // t_end (a last sample rounded below t_end used to give two rows at t_end)
  for (std::size_t k = 1; k < snaps.size(); ++k)
    for (long j = 1; j <= per; ++j) {
      const double a = snaps[k - 1], b = snaps[k];
      sample_times_.push_back(j == per ? b
                              : k == 1 || a <= 0.0
                                  ? a + (b - a) * double(j) / double(per)
                                  : a * std::pow(b / a, double(j) / double(per)));
    }
  const int n = sim.grid().n_cells();
  t_first_.assign(n, kNaN);
  threshold_.assign(n, kFormedFraction * sim.initial_sigma_d_max());

  for (const OutputField& f : output_fields(sim))
    out_.add_field(f.name, f.width, f.units, f.description);
  for (const OutputField& f : timeseries_fields(sim))
    out_.add_series("timeseries", f.name, f.width, f.units, f.description);
  for (const OutputAttribute& a : timeseries_attributes(sim)) out_.write_attribute(a);
  if (t_start > 0.0) {  // restart: keep what was sampled up to the checkpoint
    try {
      h5::Handle g = h5::open_group(out_.file(), "timeseries");
      const auto times = h5::read_doubles(g.get(), "time");
      // The rows sampled up to the checkpoint: times rise (sample times are > 0 and one
      // row per CVODE step at most). Stop at the first row that does not rise as well as
      // at the first after t_start: a run killed while it cut the file (SIGKILL during an
      // earlier restart) can leave rows read back as the fill value 0 after the valid
      // ones, and those must not be kept (regression.test_restart_bitwise). Rows whose
      // chunk is gone (a writer killed while HDF5 flushed its chunk index) are passed
      // over here; they, and kept rows whose digest differs from the checkpoint's, are
      // written as NaN below (RunOutput::keep_rows).
      std::vector<char> gone(times.size(), 0);
      for (const auto& [first, last] :
           h5::unallocated_rows(g.get(), "time", times.size()))
        std::fill(gone.begin() + static_cast<long>(first),
                  gone.begin() + static_cast<long>(last), 1);
      hsize_t keep = 0;
      double previous = 0.0;
      for (hsize_t i = 0; i < times.size(); ++i) {
        if (gone[i]) continue;
        // compared in years, as the rows were written (t / kYr): a row at the
        // checkpoint's own time is kept, whatever the rounding of kYr
        if (!(times[i] > 0.0 && times[i] >= previous && times[i] <= t_start / kYr)) break;
        previous = times[i];
        keep = i + 1;
      }
      h5::truncate_stack(g.get(), "time", keep);  // time first: rows need a time
      for (const OutputField& f : timeseries_fields(sim))
        if (f.name != "time") h5::truncate_stack(g.get(), f.name, keep);
      lost_ = out_.keep_rows("timeseries", keep);
      out_.flush();  // the cut on disk now, not at the first snapshot: a shorter window
                     // in which a kill leaves the file half cut
    } catch (const IoError& e) {
      out_.throw_if_damaged(e);
      throw;
    }
    while (next_sample_ < sample_times_.size() && sample_times_[next_sample_] <= t_start)
      ++next_sample_;
    h5::Handle s = h5::open_group(out_.file(), "snapshots");
    if (sim.planetesimals()) {
      const auto rows = h5::read_doubles(s.get(), kFirstFormation);
      if (rows.size() >= t_first_.size())
        for (std::size_t i = 0; i < t_first_.size(); ++i)
          t_first_[i] = rows[rows.size() - t_first_.size() + i] * kYr;
    }
    // the top-bin fractions of the snapshots kept up to the checkpoint (a file written
    // before the field had it not: then from the restart on)
    const char* top = sim.top_bin_fraction_field();
    if (sim.distribution() != nullptr && h5::exists(s.get(), top)) {
      const auto times = h5::read_doubles(s.get(), "time");
      const auto rows = h5::read_doubles(s.get(), top);
      const auto cells = static_cast<std::size_t>(n);
      for (std::size_t k = 0; k < times.size() && (k + 1) * cells <= rows.size(); ++k)
        note_top_bin(times[k] * kYr, std::span(rows).subspan(k * cells, cells));
    }
  }
}

void RunDiagnostics::add_snapshot_fields(
    std::map<std::string, std::vector<double>>& fields) const {
  if (!sim_.planetesimals()) return;
  std::vector<double> t(t_first_.size());
  for (std::size_t i = 0; i < t.size(); ++i) t[i] = t_first_[i] / kYr;
  fields[kFirstFormation] = std::move(t);
}

void RunDiagnostics::note_snapshot(
    double t, const std::map<std::string, std::vector<double>>& fields) {
  if (const auto it = fields.find(sim_.top_bin_fraction_field()); it != fields.end())
    note_top_bin(t, it->second);
}

void RunDiagnostics::note_top_bin(double t, std::span<const double> fraction) {
  for (std::size_t i = 0; i < fraction.size(); ++i)
    if (fraction[i] > top_bin_.fraction)
      top_bin_ = {fraction[i], sim_.grid().r_c(static_cast<int>(i)) / units::kAu,
                  t / kYr};
}

void RunDiagnostics::on_step(double t, std::span<const double> y) {
  while (next_sample_ < sample_times_.size() && t >= sample_times_[next_sample_]) {
    ++next_sample_;
    if (next_sample_ == sample_times_.size() || t < sample_times_[next_sample_])
      sample(t, y);
  }
  if (!sim_.planetesimals()) return;
  const auto c = sim_.sigma_pl(y, false), s = sim_.sigma_pl(y, true);
  for (std::size_t i = 0; i < t_first_.size(); ++i) {
    if (!std::isnan(t_first_[i])) continue;
    const double pl = (c.empty() ? 0.0 : c[i]) + (s.empty() ? 0.0 : s[i]);
    if (pl > threshold_[i]) t_first_[i] = t;
  }
}

void RunDiagnostics::sample(double t, std::span<const double> y) {
  std::vector<double> flux = sim_.pebble_flux(y), mass = sim_.pebble_mass(y);
  for (auto& f : flux) f /= kMearthPerMyr;
  for (auto& m : mass) m /= kMearth;
  std::vector<double> budget = sim_.budget_masses(y);
  double total = 0.0;
  for (double& m : budget) {
    total += m;
    m /= kMearth;
  }
  budget.push_back(std::abs(total - sim_.initial_dust_mass()) / kMearth);
  last_sample_t_ = t;
  rows_time_.push_back({t / kYr});
  rows_flux_.push_back(std::move(flux));
  rows_mass_.push_back(std::move(mass));
  rows_budget_.push_back(std::move(budget));
}

void RunDiagnostics::flush() {
  for (std::size_t k = 0; k < rows_time_.size(); ++k) {
    // time last: a reader trusts only rows that have a time
    out_.append_series("timeseries", "pebble_flux", rows_flux_[k]);
    out_.append_series("timeseries", "m_through", rows_mass_[k]);
    out_.append_series("timeseries", "mass_budget", rows_budget_[k]);
    out_.append_series("timeseries", "time", rows_time_[k]);
  }
  rows_time_.clear();
  rows_flux_.clear();
  rows_mass_.clear();
  rows_budget_.clear();
}

std::string RunDiagnostics::finish(double t, std::span<const double> y) {
  if (!(last_sample_t_ >= t)) sample(t, y);  // unless the last step's sample is at t
  flush();
  std::ostringstream txt;
  const auto& grid = sim_.grid();
  const int n = grid.n_cells();
  std::map<std::string, std::vector<double>> values;  // of summary_fields()
  // planetesimals by channel: mass and radial range where Sigma_pl > the formed threshold
  const auto [coag, si] = sim_.planetesimal_mass(y);
  txt << "outcome at t = " << t / kYr << " yr:\n";
  for (int c = 0; c < 2; ++c) {
    const std::string ch = c == 0 ? "coag" : "si";
    const auto sig = sim_.sigma_pl(y, c == 1);
    double r_lo = kNaN, r_hi = kNaN;
    for (int i = 0; i < int(sig.size()); ++i)
      if (sig[i] > threshold_[i]) {
        if (std::isnan(r_lo)) r_lo = grid.r_c(i) / units::kAu;
        r_hi = grid.r_c(i) / units::kAu;
      }
    const double m = (c == 0 ? coag : si) / kMearth;
    values["m_pl_" + ch] = {m};
    values["r_min_pl_" + ch] = {r_lo};
    values["r_max_pl_" + ch] = {r_hi};
    txt << "  planetesimals ("
        << (c == 0 ? "direct coagulation" : "streaming instability") << "): " << m
        << " M_earth";
    if (!std::isnan(r_lo)) txt << " between " << r_lo << " and " << r_hi << " au";
    txt << "\n";
  }
  std::vector<double>& t_first = values[kFirstFormation];
  t_first.resize(n);
  for (int i = 0; i < n; ++i) t_first[i] = t_first_[i] / kYr;
  const auto mons = sim_.pebble_monitors();
  const auto mass = sim_.pebble_mass(y);
  for (std::size_t k = 0; k < mons.size(); ++k) {
    const std::string key = summary_pebble_key(mons[k]);
    if (key.empty()) continue;
    values[key] = {mass[k] / kMearth};
    txt << "  pebbles through " << mons[k].name << " (" << mons[k].r_au
        << " au): " << mass[k] / kMearth << " M_earth\n";
  }
  values["formed_threshold"] = {threshold_.empty() ? 0.0 : threshold_[0]};
  values["m_dust_final"] = {sim_.dust_mass_on_grid(y) / kMearth};
  values[kTopBinMax] = {top_bin_.fraction};
  values["budget_error"] = {sim_.budget_error(y)};
  for (const OutputField& f : summary_fields(sim_))
    out_.write_static("summary", f.name, values.at(f.name), f.units, f.description);
  txt << "  dust left on the grid: " << sim_.dust_mass_on_grid(y) / kMearth
      << " M_earth\n";
  if (top_bin_.fraction > kTopBinWarning)
    txt << "WARNING: the mass grid's top bin (" << sim_.top_bin_mass()
        << " g, model.m_max_g = " << sim_.config().real("model.m_max_g") << ") held "
        << top_bin_.fraction << " of the dust of the cell at " << top_bin_.r_au
        << " au at " << top_bin_.t_yr << " yr (snapshots/top_bin_fraction; more than "
        << kTopBinWarning
        << "): products beyond it do not stick, so the largest aggregates are missing "
           "and pile up there; raise model.m_max_g to resolve them\n";
  out_.flush();
  return txt.str();
}

}  // namespace panoptic
