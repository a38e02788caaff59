#include "src/model/scene_validation.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "physics/coagulation/smoluchowski.hpp"
#include "src/core/error.hpp"
#include "src/core/units.hpp"
#include "src/model/scene_to_physics.hpp"

namespace panoptic {
namespace {

// alpha(r) within the bounds of disk.alpha (src/scene/keys_gas.cpp says why) at every
// radius: the extreme of a Gaussian profile, every row of a table.
void validate_alpha_profile(const Config& cfg, const DiskParams& d) {
  constexpr double kMin = 1e-8, kMax = 1.0;
  const AlphaProfile& a = d.alpha;
  if (a.kind == AlphaProfile::Kind::kGaussian) {
    const double extreme = d.thermal.alpha * (1.0 + a.amplitude);
    if (extreme < kMin || extreme > kMax)
      cfg.fail("disk.alpha_bump_amplitude",
               "makes alpha = disk.alpha (1 + A) = " + num(extreme) +
                   " at the centre of the profile, outside [" + num(kMin) + ", " +
                   num(kMax) + "]; make the bump or dip shallower");
  } else if (a.kind == AlphaProfile::Kind::kTable) {
    for (std::size_t i = 0; i < a.table->values().size(); ++i) {
      const double v = a.table->values()[i];
      if (v < kMin || v > kMax)
        cfg.fail("disk.alpha_file",
                 "row " + std::to_string(i + 1) + " (r = " +
                     num(a.table->r()[i] / units::kAu) + " au) has alpha = " + num(v) +
                     ", outside [" + num(kMin) + ", " + num(kMax) +
                     "] (below 1e-8 molecular viscosity would dominate); fix the row");
    }
  }
}

// One snow line (spec §1.7): ice outside the innermost radius where T falls to T_sub, so
// a table's T may not rise above T_sub again further out on the grid (as disk.q < 0 is
// refused for the power law).
void validate_table_snow_line(const Config& cfg, const DiskParams& d) {
  const RadialTable& t = *d.profile.t_table;
  const double r_snow = t.first_fall_to(d.thermal.T_sub);
  const double r_out = cfg.real("grid.r_out_au") * units::kAu;
  for (std::size_t i = 0; i < t.r().size(); ++i)
    if (t.r()[i] > r_snow && t.r()[i] <= r_out && t.values()[i] > d.thermal.T_sub)
      cfg.fail("disk.table_file",
               "row " + std::to_string(i + 1) + " (r = " + num(t.r()[i] / units::kAu) +
                   " au) has T = " + num(t.values()[i]) +
                   " K, above disk.T_sub = " + num(d.thermal.T_sub) +
                   " K outside the snow line at " + num(r_snow / units::kAu) +
                   " au: the snow line of spec §1.7 needs T falling outward across "
                   "T_sub; fix the table or set snowline.enabled = false");
}

// The radial structure of the disk: its tables are read here (disk_params_from_config),
// so that `panoptic check` finds a bad file.
void validate_radial_structure(const Config& cfg) {
  const DiskParams d = disk_params_from_config(cfg);
  validate_alpha_profile(cfg, d);
  if (d.profile.kind == GasProfile::Kind::kTable && cfg.flag("snowline.enabled"))
    validate_table_snow_line(cfg, d);
}

}  // namespace

namespace {

// model.kind = "distribution" (spec §15): what of the single-size model it does not carry
// yet (issue 35), refused by name with the fix.
void validate_distribution(const Config& cfg) {
  if (cfg.str("model.kind") != "distribution") return;
  const std::string not_yet =
      " is not supported with model.kind = \"distribution\" yet (issue 35: the size "
      "distribution has no bouncing); ";
  // the critical metallicity Z_crit(St) is a law of one St (spec §7.2), with no per-bin
  // form (physics/modules/bin_planetesimals.hpp)
  if (cfg.str("planetesimals.si") == "zcrit")
    cfg.fail("planetesimals.si",
             "= \"zcrit\" is not supported with model.kind = \"distribution\" (its "
             "critical metallicity Z_crit(St) is a law of one Stokes number); use si = "
             "\"d16\" or \"s18\", which count the bins with St >= St_si_min");
  // erosion (any model): Krijt et al.'s rule on the pairs m_j/m_i < 1/ratio
  // (physics/coagulation/cell_coefficients.hpp), whose target keeps m_i - eps_eros m_j
  const double ratio = physics::coagulation::FragmentationModel{}.erosion_mass_ratio;
  if (cfg.flag("growth.enabled") && cfg.str("erosion.model") != "none" &&
      cfg.real("erosion.eps_eros") >= ratio)
    cfg.fail("erosion.eps_eros",
             "= " + num(cfg.real("erosion.eps_eros")) + " must be < " + num(ratio) +
                 " with model.kind = \"distribution\": the erosion rule acts on pairs "
                 "with m_proj/m_target < 1/" +
                 num(ratio) + ", and the target must keep mass; lower it");
  if (cfg.flag("bouncing.enabled"))
    // spec §5.3 as written (no sticking where phi >= phi_bounce, at every speed) would
    // stop the compact bins of the initial state (phi = 1) from ever sticking: per pair
    // it needs a speed threshold that the spec does not give
    cfg.fail("bouncing.enabled",
             "bouncing" + not_yet +
                 "spec §5.3's rule has no speed threshold, so per pair it would keep the "
                 "compact initial bins from ever sticking; set bouncing.enabled = false");
  const double m_min = cfg.real("model.m_min_g"), m_max = cfg.real("model.m_max_g");
  if (m_min > 0.0 && m_min >= m_max)
    cfg.fail("model.m_min_g", "= " + num(m_min) + " must be < model.m_max_g = " +
                                  num(m_max) + " [g]; lower it or raise m_max_g");
}

}  // namespace

void validate_scene(const Config& cfg) {
  const double r_in = cfg.real("grid.r_in_au"), r_out = cfg.real("grid.r_out_au");
  if (r_in >= r_out)
    cfg.fail("grid.r_in_au",
             "must be < grid.r_out_au = " + num(r_out) +
                 " [au]; make the inner edge smaller than the outer edge");
  if (r_out / r_in > 1e8)
    cfg.fail("grid.r_out_au", "r_out/r_in must be <= 1e8; narrow the radial domain");
  const double max_dt = cfg.real("solver.max_dt_yr");
  if (max_dt > 0.0 && max_dt < 1e-6)
    cfg.fail("solver.max_dt_yr",
             "must be 0 (unlimited) or >= 1e-6 [yr] (a step of 1e-320 yr is not one); "
             "raise it");
  // Output times: CVODE cannot step to a time closer to the last one than a few
  // round-offs (CV_TOO_CLOSE) nor start with a step of 1e-300 yr (CV_ILL_INPUT), so
  // they must lie >= kMinTime after t = 0 (the lower bound of output.t_end_yr,
  // t_first_yr and times_yr in the schema) and kMinGap (relative) apart.
  constexpr double kMinTime = 1e-6, kMinGap = 1e-9;
  const double t_end = cfg.real("output.t_end_yr");
  const auto& times = cfg.reals("output.times_yr");
  if (times.empty()) {  // log-spaced from t_first_yr (unused with a list of times)
    const double t_first = cfg.real("output.t_first_yr");
    if (t_first > t_end)
      cfg.fail("output.t_first_yr", "must be <= output.t_end_yr = " + num(t_end) +
                                        " [yr]; lower it or raise t_end_yr");
    const long m = cfg.integer("output.n_snapshots");
    if (m > 1 && t_first < t_end &&
        std::expm1(std::log(t_end / t_first) / double(m - 1)) < kMinGap)
      cfg.fail("output.n_snapshots", "puts snapshots less than " + num(kMinGap) +
                                         " (relative) apart between "
                                         "t_first_yr = " +
                                         num(t_first) + " and t_end_yr = " + num(t_end) +
                                         "; use fewer snapshots or a wider time span");
  }
  for (std::size_t i = 0; i < times.size(); ++i) {
    if (times[i] < kMinTime || times[i] > t_end)
      cfg.fail("output.times_yr", "every time must be in [" + num(kMinTime) +
                                      ", t_end_yr = " + num(t_end) +
                                      "] [yr]; remove or fix the entry " + num(times[i]));
    if (i > 0 && times[i] <= times[i - 1])
      cfg.fail("output.times_yr", "times must be strictly increasing; sort the list");
    const double next = i + 1 < times.size() ? times[i + 1] : t_end;
    if (next > times[i] && next - times[i] < kMinGap * next)
      cfg.fail("output.times_yr", "the times " + num(times[i]) + " and " + num(next) +
                                      " [yr] (or t_end_yr) are less than " +
                                      num(kMinGap) + " (relative) apart; merge them");
  }
  // /timeseries: RunDiagnostics lays out every sample time at the start, so their number
  // is bounded (1e6 snapshots of 1e5 samples each, both inside their ranges, asked for
  // 800 GB and ended in std::bad_alloc after the output file was created)
  {
    constexpr double kMaxSamples = 1e7;
    // the intervals of output_times(): to each listed time, and on to t_end
    const double intervals =
        times.empty() ? double(cfg.integer("output.n_snapshots"))
                      : double(times.size()) + (times.back() < t_end ? 1.0 : 0.0);
    const long per = cfg.integer("pebbles.samples_per_snapshot");
    if (intervals * double(per) > kMaxSamples)
      cfg.fail("pebbles.samples_per_snapshot",
               "with " + num(intervals) +
                   " snapshot intervals (output.n_snapshots or output.times_yr) makes " +
                   num(intervals * double(per)) + " /timeseries samples, more than " +
                   num(kMaxSamples) + "; lower pebbles.samples_per_snapshot to at most " +
                   std::to_string(std::max(1L, long(kMaxSamples / intervals))) +
                   " or use fewer snapshots");
  }
  if (cfg.flag("porosity.enabled") && !cfg.flag("growth.enabled"))
    cfg.fail(
        "porosity.enabled",
        "needs growth.enabled = true (the filling factor evolves as the particle grows); "
        "turn growth on or porosity off");
  for (const char* key : {"planetesimals.coagulation"})
    if (cfg.flag(key) && !cfg.flag("growth.enabled"))
      cfg.fail(key,
               "needs growth.enabled = true (conversion depends on the particles); "
               "turn growth on or this channel off");
  validate_radial_structure(cfg);
  if (cfg.str("model.kind") == "single_size" && cfg.flag("transport.drift") &&
      cfg.str("transport.face_stokes") == "upwind" &&
      cfg.str("transport.advection") == "van_leer")
    cfg.fail("transport.face_stokes",
             "splits the first-order drift flux by cell and has no van Leer form; set "
             "transport.advection = \"upwind\" or transport.face_stokes = \"mean\"");
  if (cfg.flag("snowline.enabled") && cfg.str("disk.model") != "table" &&
      cfg.real("disk.q") < 0.0)
    cfg.fail("disk.q",
             "< 0 makes the temperature rise outward, so ice would lie inside silicate; "
             "the snow line of spec §1.7 needs T falling outward: set disk.q >= 0 or "
             "snowline.enabled = false");
  const auto& radii_au = cfg.reals("pebbles.radii_au");
  for (std::size_t i = 0; i < radii_au.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (radii_au[i] == radii_au[j])
        cfg.fail("pebbles.radii_au", "lists " + num(radii_au[i]) +
                                         " [au] twice (one monitor each would record the "
                                         "same flux); remove one");
  for (double r : radii_au)
    if (!(r > cfg.real("grid.r_in_au") && r < cfg.real("grid.r_out_au")))
      cfg.fail("pebbles.radii_au",
               "every radius must lie strictly inside the grid, (r_in_au, r_out_au) = (" +
                   num(cfg.real("grid.r_in_au")) + ", " + num(cfg.real("grid.r_out_au")) +
                   ") [au]: the flux through r_in is always recorded, and none crosses "
                   "the closed outer edge; remove " +
                   num(r));
  // The optical-constant tables are read only by `panoptic observe`, but a table that
  // observe will refuse (lengths differ, wavelengths not increasing) is checked here, so
  // that `panoptic check` and a run find it and not an observe after the run.
  for (const std::string sp : {"ice", "sil"}) (void)optical_table_from_config(cfg, sp);
  validate_distribution(cfg);
  // DustPy's step rule (src/solver/implicit_euler_integrator.hpp) bounds the change of
  // surface densities only: the single-size model's m and phi (or q_m, q_V) have no
  // rule of it, and nothing would hold their steps
  if (cfg.str("solver.method") == "implicit_euler" &&
      cfg.str("model.kind") != "distribution")
    cfg.fail("solver.method",
             "needs model.kind = \"distribution\" (its step rule, "
             "DustPy's, covers surface densities only, not the single-size model's "
             "particle mass and filling factor), and model.kind is \"" +
                 cfg.str("model.kind") +
                 "\"; set solver.method = \"bdf\" or model.kind = \"distribution\"");
  if (cfg.str("dust.init") == "gaussian_ring") {
    const double r0 = cfg.real("dust.ring_r_au");
    if (r0 <= r_in || r0 >= r_out)
      cfg.fail("dust.ring_r_au", "the ring centre must lie inside the grid (" +
                                     num(r_in) + ", " + num(r_out) +
                                     ") [au]; move the ring or the grid edges");
  }
}

}  // namespace panoptic
