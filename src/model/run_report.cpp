#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "disk/gas_disk.hpp"
#include "physics/contact_mechanics.hpp"
#include "physics/modules/dust_transport.hpp"
#include "physics/modules/porous_growth.hpp"
#include "physics/modules/size_distribution.hpp"
#include "physics/stokes_model.hpp"
#include "src/core/error.hpp"
#include "src/core/units.hpp"
#include "src/core/worker_threads.hpp"
#include "src/model/scene_to_physics.hpp"
#include "src/model/simulation.hpp"

namespace panoptic {

using units::kAu;

namespace {

// The names of `count` variables as the header lists them, with a run of numbered names
// (a size distribution's sigma_0 ... sigma_198) written as its first and last: a
// distribution run's header would otherwise list hundreds of names.
template <class NameOf>
std::string variable_names(int count, NameOf name_of) {
  const auto split = [](const std::string& n) -> std::pair<std::string, long> {
    const auto us = n.rfind('_');
    if (us == std::string::npos || us + 1 == n.size() ||
        !std::all_of(n.begin() + us + 1, n.end(),
                     [](char c) { return c >= '0' && c <= '9'; }))
      return {n, -1};
    return {n.substr(0, us + 1), std::stol(n.substr(us + 1))};
  };
  std::ostringstream s;
  for (int k = 0; k < count;) {
    const std::string first = name_of(k);
    const auto [base, index] = split(first);
    int last = k;
    while (index >= 0 && last + 1 < count &&
           split(name_of(last + 1)) == std::pair{base, index + (last + 1 - k)})
      ++last;
    s << " " << first;
    if (last - k >= 2)
      s << " ... " << name_of(last);
    else if (last == k + 1)
      s << " " << name_of(last);
    k = last + 1;
  }
  return s.str();
}

// What the particles do, said in the header of every single-size run: the process
// switches default to off (params/README.md, Scenes), so a scene without [growth] runs
// transport alone at a prescribed St, and one with growth alone sticks compact
// particles at every speed; each off switch is named with its key.
std::string physics_choices(const Config& cfg) {
  if (cfg.str("model.kind") != "single_size") {
    // the distribution resolves the projectiles: the erosion model names a closure of
    // the single-size model, and either selects the rule itself on the pairs
    if (!cfg.flag("growth.enabled") || cfg.str("erosion.model") == "none") return "";
    return "erosion: the Krijt et al. (2015) rule on the pairs of bins with m_proj/"
           "m_target < 1/10: above erosion.v_eros_m_s = " +
           num(cfg.real("erosion.v_eros_m_s")) +
           " m/s the target loses eps_eros = " + num(cfg.real("erosion.eps_eros")) +
           " x m_proj, below it the projectile sticks (erosion.model = \"" +
           cfg.str("erosion.model") +
           "\" names a single-size closure, spec §5.2; the distribution applies the "
           "rule itself, spec §15.2)\n";
  }
  std::ostringstream s;
  if (!cfg.flag("growth.enabled")) {
    s << "growth: off (growth.enabled = false"
      << (cfg.user_set("growth.enabled") ? "" : ", the default")
      << "): no particle grows, St is prescribed: transport.St = "
      << cfg.real("transport.St") << " at 1 au";
    if (cfg.real("transport.St_slope") != 0.0)
      s << " times (r/au)^" << cfg.real("transport.St_slope");
    s << " (set growth.enabled = true to grow the particles from monomers)\n";
    return s.str();
  }
  s << "growth: on, ";
  if (cfg.flag("porosity.enabled"))
    s << "porous";
  else
    s << "compact (phi = 1; porous with porosity.enabled = true)";
  if (cfg.str("erosion.model") == "none" && !cfg.flag("fragmentation.enabled") &&
      !cfg.flag("bouncing.enabled"))
    s << "; particles stick at any speed (fragmentation.enabled = false, erosion.model = "
         "\"none\", bouncing.enabled = false)";
  if (!cfg.flag("planetesimals.coagulation") && cfg.str("planetesimals.si") == "none")
    s << "; no planetesimal channel (planetesimals.coagulation = false, planetesimals.si "
         "= \"none\")";
  s << "\n";
  return s.str();
}

// Direct coagulation converts a distribution's bins above St_pl (spec §15.4), but the
// mass grid ends at model.m_max_g (DustPy's 1e5 g by default), and products beyond it do
// not stick: where even its last bin is below St_pl, no bin converts, silently. A bin's
// largest St is its compact one (a lower phi lowers St in both drag regimes, spec §2),
// taken with the gas at the start; on the porosity track, the track's (bin_stokes).
std::string unreachable_st_pl_warning(const Config& cfg, const Grid& grid,
                                      const SizeDistribution* dist) {
  if (!dist || !cfg.flag("planetesimals.coagulation")) return "";
  const int top = dist->n_bins() - 1;
  double st_top = 0.0;
  int where = 0;
  for (int i = 0; i < grid.n_cells(); ++i)
    if (const double st = dist->bin_stokes(i, top, 1.0); st > st_top) {
      st_top = st;
      where = i;
    }
  const double st_pl = cfg.real("planetesimals.St_pl");
  if (st_top >= st_pl) return "";
  std::ostringstream s;
  s << "WARNING: no bin can reach planetesimals.St_pl = " << st_pl
    << ", so planetesimals.coagulation converts nothing: the mass grid ends at "
    << dist->mass_grid().m[static_cast<std::size_t>(top)]
    << " g (model.m_max_g = " << cfg.real("model.m_max_g") << "), whose "
    << (dist->porosity_track() ? "St on the porosity track" : "compact St")
    << " is at most " << st_top << " (at " << grid.r_c(where) / kAu
    << " au, the gas at the start); raise model.m_max_g (porous ice on the MMSN reaches "
       "St = 10 near 1e12 g)\n";
  return s.str();
}

// The porosity track without either compaction floor: measured far from the evolved bins
// (tests/bench/results/porosity_track.md), said, not refused.
std::string track_without_floors_warning(const Config& cfg,
                                         const SizeDistribution* dist) {
  if (!dist || !dist->porosity_track() || cfg.flag("porosity.gas_compaction") ||
      cfg.flag("porosity.self_gravity"))
    return "";
  return "WARNING: porosity.bins = \"track\" with both compaction floors off "
         "(porosity.gas_compaction, porosity.self_gravity): the single-size law's track "
         "then leaves aggregates of 1 g .. 1e10 g 100-1000x fluffier than the evolved "
         "bins, and on the porous MMSN no St >= 10 body forms where they form some "
         "(tests/bench/results/porosity_track.md); use porosity.bins = \"evolved\" or "
         "turn a floor on\n";
}

}  // namespace

std::string Simulation::summary() const {
  std::ostringstream s;
  const auto& L = *layout_;
  const int n = grid_.n_cells();
  s << "grid: " << n << " cells, " << grid_.r_f(0) / kAu << " - " << grid_.r_f(n) / kAu
    << " au (dr/r = ";
  if (grid_.stretch() == 0.0)
    s << std::expm1(grid_.dlnr(0)) << ")\n";
  else
    s << std::expm1(grid_.dlnr(0)) << " at r_in to " << std::expm1(grid_.dlnr(n - 1))
      << " at r_out, stretch " << grid_.stretch() << ")\n";
  s << "gas disk: " << disk_->name()
    << (gas_.evolves() ? ", viscously evolving" : ", static") << ", ";
  if (disk_->alpha_profile().kind != AlphaProfile::Kind::kConstant) {
    // the range of alpha(r) the cells see (disk.alpha_profile; spec §1.5)
    double lo = disk_->alpha(grid_.r_c(0)), hi = lo;
    for (int i = 1; i < n; ++i) {
      lo = std::min(lo, disk_->alpha(grid_.r_c(i)));
      hi = std::max(hi, disk_->alpha(grid_.r_c(i)));
    }
    s << "alpha(r) " << cfg_.str("disk.alpha_profile") << " from " << lo << " to " << hi
      << " on the grid, ";
  }
  {  // the profile's gas on the grid's span (spec §1.2; for LBP, its share of M_disk)
    const double m_gas = disk_->mass_between(grid_.r_f(0), grid_.r_f(n));
    s << m_gas / units::kMsun << " M_sun between r_in and r_out";
    if (cfg_.str("disk.model") == "lbp")
      s << " (" << 100.0 * m_gas / (cfg_.real("disk.m_disk_msun") * units::kMsun)
        << " % of disk.m_disk_msun)";
    s << "; ";
  }
  const double r_snow_au = disk_->r_snow() / kAu;
  if (!cfg_.flag("snowline.enabled"))
    s << "snow line off (icy solids everywhere)\n";
  else if (std::isinf(r_snow_au))
    s << "no snow line: warmer than disk.T_sub everywhere (all silicate)\n";
  else if (r_snow_au == 0.0)
    s << "no snow line: colder than disk.T_sub everywhere (all ice)\n";
  else {
    // where T = T_sub may lie off the grid (a warm disk with q > 0: 3.5e5 au was printed
    // as if it were a snow line of the run)
    s << "snow line at " << r_snow_au << " au";
    if (r_snow_au * kAu >= grid_.r_f(n))
      s << " (beyond the outer edge: all silicate on the grid)";
    else if (r_snow_au * kAu <= grid_.r_f(0))
      s << " (inside the inner edge: all ice on the grid)";
    s << "\n";
  }
  s << "state: " << L.size() << " variables; per cell:"
    << variable_names(L.n_cell_vars(), [&](int k) { return L.cell_var(k).name; })
    << "; global:"
    << variable_names(L.n_global_vars(), [&](int k) { return L.global_var(k).name; });
  s << "\nmodules:";
  for (const auto& m : model_->modules()) s << " " << m->name();
  s << "\n" << physics_choices(cfg_);
  s << "Jacobian: " << model_->pattern().nnz() << " structural non-zeros; ";
  if (cfg_.str("solver.method") == "implicit_euler")
    s << "linearly implicit Euler steps of cfl = " << cfg_.real("solver.cfl")
      << " times DustPy's rule, solved by block (solver.method)\n";
  else
    s << "Newton systems solved by " << linear_solver_name(linear_solver())
      << " (solver.linear" << (cfg_.str("solver.linear") == "auto" ? " = auto" : "")
      << ")\n";
  if (worker_threads() > 1)
    s << "worker threads: " << worker_threads()
      << " (--threads: they share the size distribution's cells; the results do not "
         "depend on their number)\n";
  s << "initial dust mass: " << dust_mass0_ / units::kMearth << " M_earth";
  // the cells' centre values against the profile's exact mass: second order in the width
  if (std::isfinite(profile_dust_mass_)) {
    const double excess = dust_mass0_ / profile_dust_mass_ - 1.0;
    std::ostringstream pct;
    pct << std::showpos << std::setprecision(2) << 100.0 * excess << " %";
    s << " (cell-centre values; the profile holds " << profile_dust_mass_ / units::kMearth
      << " on the grid's span: " << pct.str() << ")";
    if (std::abs(excess) > 0.01)
      s << "\nWARNING: the cells misstate the initial dust mass by " << pct.str()
        << " (cell-centre values of the profile); raise grid.n_cells";
  }
  s << "\n";
  // log-spaced snapshots between equal ends fall on one time (a quick run shortened
  // with output.t_end_yr = t_first_yr): said, not refused
  if (cfg_.reals("output.times_yr").empty() && cfg_.integer("output.n_snapshots") > 1 &&
      cfg_.real("output.t_first_yr") == cfg_.real("output.t_end_yr"))
    s << "WARNING: output.n_snapshots = " << cfg_.integer("output.n_snapshots")
      << " with output.t_first_yr = t_end_yr = " << cfg_.real("output.t_end_yr")
      << " yr: one snapshot after t = 0; lower t_first_yr for more\n";
  s << unreachable_st_pl_warning(cfg_, grid_, distribution_);
  s << track_without_floors_warning(cfg_, distribution_);
  if (growth_) {  // spec §0: the contact mechanics behind the collision parameters
    s << physics::contact_summary("ice", material_from_config(cfg_, "ice")) << "\n";
    s << physics::contact_summary("silicate", material_from_config(cfg_, "sil")) << "\n";
    // spec §5.3 has bouncing at every speed for phi >= phi_bounce, and monomers start at
    // phi = 1 (tests/README.md, "What works").
    if (cfg_.flag("bouncing.enabled"))
      s << "WARNING: bouncing.enabled: particles with phi >= bouncing.phi_bounce = "
        << cfg_.real("bouncing.phi_bounce")
        << " do not stick at any speed (spec §5.3 has no speed or mass threshold): "
        << (cfg_.flag("porosity.enabled")
                ? "the monomers (phi = 1) grow only once hit-and-stick has lowered phi "
                  "below it, and then never bounce"
                : "with porosity off nothing grows")
        << "\n";
    // refresh_local_gas runs where CVODE restarts (tests/README.md, "What works")
    if (gas_.evolves() && !cfg_.flag("solver.reinit_at_snapshots"))
      s << "WARNING: gas.evolve with solver.reinit_at_snapshots = false: the pressure "
           "gradient (eta) and gas velocity that the particle laws see are set once, at "
           "the start, and not from the evolving gas at every snapshot; set "
           "solver.reinit_at_snapshots = true to follow the gas\n";
  }
  return s.str();
}

std::string Simulation::describe_state(long index, std::span<const double> y) const {
  const auto& L = *layout_;
  const int i = L.cell_of(index);
  if (i < 0 || y.size() < static_cast<std::size_t>(L.size())) return "";
  const double* yc = &y[L.index(i, 0)];
  std::ostringstream s;
  s.precision(4);
  s << "r = " << grid_.r_c(i) / kAu << " au, Sigma_d = " << dust_->sigma_d(i, y)
    << " g cm^-2";
  if (gas_.evolves()) s << ", Sigma_g = " << gas_.sigma(i, yc) << " g cm^-2";
  if (growth_) s << ", m = " << codec_->mass(i, yc) << " g, phi = " << codec_->phi(yc);
  if (distribution_)
    s << ", mass-dominating bin " << distribution_->dominant_bin(i, y)
      << ", St = " << distribution_->dominant_st(y)[i];
  else
    s << ", St = " << stokes_->St(i, yc);
  return s.str();
}

}  // namespace panoptic
