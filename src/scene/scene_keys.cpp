// The scene schema: every key a scene may hold, its type, default, unit, meaning and
// allowed range. params/reference.toml is generated from this list (`panoptic reference`)
// and a unit test keeps the two identical. Physics defaults cite physics-spec sections.
//
// NEW_PROCESS: add the keys of a new process here, in a table of its own.
#include <charconv>
#include <cmath>

#include "disk/gas_defaults.hpp"
#include "src/scene/config.hpp"
#include "src/scene/toml_literal.hpp"

namespace panoptic {
namespace {

// A default as the schema writes it: below 0.01 with an exponent ("1e-3", as the
// reference lists small numbers), else as a TOML float ("280.0").
std::string literal(double x) {
  if (x == 0.0 || std::abs(x) >= 0.01) return toml_real(x);
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x, std::chars_format::scientific);
  std::string s(buf, r.ptr);
  if (const size_t e = s.find("e-0"); e != std::string::npos) s.erase(e + 2, 1);  // e-03
  return s;
}

KeySpec real(std::string key, std::string def, std::string unit, std::string doc,
             std::optional<double> min = std::nullopt, bool min_excl = false,
             std::optional<double> max = std::nullopt, bool max_excl = false) {
  KeySpec k;
  k.key = std::move(key);
  k.type = KeyType::kReal;
  k.default_toml = std::move(def);
  k.unit = std::move(unit);
  k.doc = std::move(doc);
  k.min = min;
  k.min_exclusive = min_excl;
  k.max = max;
  k.max_exclusive = max_excl;
  return k;
}

KeySpec positive(std::string key, std::string def, std::string unit, std::string doc) {
  return real(std::move(key), std::move(def), std::move(unit), std::move(doc), 0.0, true);
}

KeySpec integer(std::string key, std::string def, std::string doc, double min,
                double max) {
  KeySpec k;
  k.key = std::move(key);
  k.type = KeyType::kInt;
  k.default_toml = std::move(def);
  k.doc = std::move(doc);
  k.min = min;
  k.max = max;
  return k;
}

KeySpec flag(std::string key, std::string def, std::string doc) {
  KeySpec k;
  k.key = std::move(key);
  k.type = KeyType::kBool;
  k.default_toml = std::move(def);
  k.doc = std::move(doc);
  return k;
}

KeySpec choice(std::string key, std::string def, std::vector<std::string> choices,
               std::string doc) {
  KeySpec k;
  k.key = std::move(key);
  k.type = KeyType::kString;
  k.default_toml = "\"" + def + "\"";
  k.doc = std::move(doc);
  k.choices = std::move(choices);
  return k;
}

KeySpec text(std::string key, std::string doc) {
  KeySpec k;
  k.key = std::move(key);
  k.type = KeyType::kString;
  k.default_toml = "\"\"";
  k.doc = std::move(doc);
  return k;
}

KeySpec real_list(std::string key, std::string unit, std::string doc,
                  std::optional<double> min = std::nullopt) {
  KeySpec k;
  k.key = std::move(key);
  k.type = KeyType::kRealList;
  k.default_toml = "[]";
  k.unit = std::move(unit);
  k.doc = std::move(doc);
  k.min = min;
  return k;
}

KeySpec real_table(std::string key, std::string def, std::string unit, std::string doc,
                   double min) {
  KeySpec k = real_list(std::move(key), std::move(unit), std::move(doc), min);
  k.default_toml = std::move(def);
  k.min_exclusive = true;
  return k;
}

// When a run reads a key (KeySpec::used_when), taken from the code that reads it
// (src/model/simulation.cpp, disk/gas_disk.cpp, physics/growth_rates.hpp and the
// processes it combines, physics/modules/planetesimals_cell_rates.hpp,
// src/observe/observe.cpp). Values are TOML literals.
UsedWhen is(std::string key, std::vector<std::string> values) {
  return UsedWhen{std::move(key), std::move(values)};
}
//! A string switch (a choice) holding one of `names`.
UsedWhen one_of(std::string key, std::vector<std::string> names) {
  for (std::string& n : names) n = toml_string(n);  // as Config writes the value
  return is(std::move(key), std::move(names));
}
UsedWhen growth_on() { return is("growth.enabled", {"true"}); }
UsedWhen disk_model(const std::string& m) { return one_of("disk.model", {m}); }
UsedWhen dust_init(const std::string& i) { return one_of("dust.init", {i}); }
UsedWhen erosion(std::vector<std::string> models) {
  return one_of("erosion.model", std::move(models));
}
UsedWhen si(std::vector<std::string> models) {
  return one_of("planetesimals.si", std::move(models));
}

KeySpec when(std::vector<UsedWhen> conditions, KeySpec k) {
  k.used_when = std::move(conditions);
  return k;
}

std::vector<KeySpec> make_keys() {
  return {
      // [meta]: documentation only.
      text("meta.description", "what this scene is for"),
      text("meta.reference", "the paper or test this scene reproduces"),

      // [star] spec §1.1
      // Bounds on the physical keys: what a disk around a star can be (brown dwarfs to
      // massive stars, cold to hot, up to a self-gravitating disk), so that a typo (an
      // exponent off by decades) is refused by name instead of failing in the solver.
      real("star.mass_msun", "1.0", "M_sun", "stellar mass", 0.01, false, 100.0, false),
      real("star.luminosity_lsun", "1.0", "L_sun", "stellar luminosity (scales T, §1.3)",
           1e-4, false, 1e7, false),

      // [disk] spec §1.2-§1.7
      choice("disk.model", "powerlaw", {"powerlaw", "lbp"},
             "gas surface density: powerlaw = MMSN-like (§1.2 A), lbp = Lynden-Bell & "
             "Pringle similarity profile (§1.2 B)"),
      when({disk_model("powerlaw")},
           real("disk.sigma_1au", "1700.0", "g cm^-2",
                "powerlaw: gas surface density at 1 au (MMSN 1700)", 0.0, true, 1e6,
                false)),
      when({disk_model("powerlaw")}, real("disk.p", "1.5", "", "powerlaw: Sigma_g ∝ r^-p",
                                          -5.0, false, 5.0, false)),
      when({disk_model("lbp")},
           real("disk.m_disk_msun", "0.05", "M_sun", "lbp: total gas mass of the disk",
                0.0, true, 10.0, false)),
      when({disk_model("lbp")},
           positive("disk.r_c_au", "60.0", "au", "lbp: characteristic radius r_c")),
      when({disk_model("lbp")},
           real("disk.gamma", "1.0", "",
                "lbp: exponent gamma of the initial profile Sigma ∝ (r/r_c)^-gamma "
                "exp(-(r/r_c)^(2 - gamma)) (§1.2, the similarity solution for nu ∝ "
                "r^gamma; an evolving gas uses nu = alpha c_s H ∝ r^(3/2 - q) whatever "
                "gamma is)",
                -2.0, false, 2.0, true)),
      real("disk.T_1au", literal(gas_defaults::kT1au), "K",
           "temperature at 1 au for L_* = L_sun (§1.3)", 1.0, false, 1e4, false),
      real("disk.q", literal(gas_defaults::kQ), "", "T ∝ r^-q (§1.3)", -2.0, false, 3.0,
           false),
      real("disk.T_floor", literal(gas_defaults::kTFloor), "K",
           "temperature floor (§1.3)", 0.0, false),
      real("disk.mu", literal(gas_defaults::kMu), "",
           "mean molecular weight (§1.1; 0.5 for ionised hydrogen, no gas is heavier "
           "than 100)",
           0.5, false, 100.0, false),
      // >= 1e-8: weaker "turbulence" is below the gas's molecular viscosity, which the
      // model leaves out (alpha_mol = nu_mol / (c_s H) = 2 mu m_H / (sigma_mol Sigma_g),
      // spec §1.5-1.6: 2.3e-12 at 1 au, 1.2e-8 at 300 au in the MMSN, so the turbulent
      // Reynolds number of Ormel & Cuzzi's velocities falls to ~1 there), and the dust
      // settles into ever thinner layers: the fiducial scene to 1 Myr took 185 s at
      // 1e-7, 39 s at 1e-8 and did not finish in 20 min at 1e-10; at 1e-50 it did not
      // reach 100 yr in 5 min, and at 1e-70 CVODE failed at t = 0.
      real("disk.alpha", literal(gas_defaults::kAlpha), "",
           "Shakura-Sunyaev alpha, D_g = alpha c_s H (§1.5); below 1e-8 molecular "
           "viscosity would dominate",
           1e-8, false, 1.0, false),
      positive("disk.sigma_mol", literal(gas_defaults::kSigmaMol), "cm^2",
               "molecular cross section (§1.6)"),
      positive("disk.T_sub", literal(gas_defaults::kTSub), "K",
               "water-ice sublimation temperature (§1.7)"),

      // [gas] spec §1.2, §6.1
      flag(
          "gas.evolve", "false",
          "evolve Sigma_g by viscous diffusion (nu = alpha c_s H); the gas velocity then "
          "enters the dust drift"),
      when(
          {is("gas.evolve", {"true"})},
          choice("gas.inner_bc", "free_flow", {"free_flow", "zero_torque"},
                 "inner boundary of the evolving gas: free_flow = accretes through r_in "
                 "as if the disk went on; zero_torque = nu Sigma_g r^(1/2) = 0 at r_in")),

      // [dust] initial condition, spec §6.4
      when({dust_init("dust_to_gas")},
           real("dust.dust_to_gas", "0.01", "",
                "initial Sigma_d / Sigma_g outside the snow line (§1.7 Z_out; inside it "
                "(1 - snowline.f_ice) times this)",
                0.0, true, 1.0, false)),
      choice(
          "dust.init", "dust_to_gas", {"dust_to_gas", "gaussian_ring"},
          "initial Sigma_d: dust_to_gas = dust_to_gas * Sigma_g; gaussian_ring = a thin "
          "ring diffused to Gaussian width ring_width_au (the exact diffusing-ring "
          "profile, ~Gaussian for width << radius) on a floor of sigma_floor_rel * "
          "Sigma_g"),
      when({dust_init("gaussian_ring")},
           positive("dust.ring_r_au", "30.0", "au", "gaussian_ring: ring centre")),
      when({dust_init("gaussian_ring")},
           positive("dust.ring_width_au", "2.0", "au",
                    "gaussian_ring: Gaussian width (standard deviation)")),
      when({dust_init("gaussian_ring")},
           positive("dust.ring_sigma", "1.0", "g cm^-2", "gaussian_ring: peak Sigma_d")),
      when({dust_init("gaussian_ring")}, real("dust.sigma_floor_rel", "1e-30", "",
                                              "gaussian_ring: Sigma_d / Sigma_g outside "
                                              "the ring (§6.4; not a floor during "
                                              "the run: m and phi of a nearly empty cell "
                                              "are decoded through a floor set by "
                                              "solver.atol_sigma)",
                                              0.0, false, 1e-3, false)),

      // [transport] spec §6.1, §6.3
      flag("transport.drift", "true", "radial drift (advection by v_r, §6.1)"),
      flag("transport.diffusion", "true",
           "turbulent diffusion of Sigma_d/Sigma_g (§6.1)"),
      when({is("growth.enabled", {"false"})},
           positive(
               "transport.St", "0.03", "",
               "prescribed Stokes number at 1 au with growth off (growth.enabled = true "
               "ignores it)")),
      when({is("growth.enabled", {"false"})},
           real("transport.St_slope", "0.0", "",
                "prescribed St ∝ r^St_slope (growth off)", -5.0, false, 5.0, false)),
      when(
          {is("transport.drift", {"true"})},
          choice(
              "transport.advection", "upwind", {"upwind", "van_leer"},
              "advection scheme of the drift: first-order upwind, or second-order upwind "
              "with a van Leer-limited reconstruction of r Sigma (MUSCL; widens the "
              "Jacobian stencil to 4 cells per face)")),

      // [growth] spec §3, §4.1: the mass of the mass-dominating particle (variable Q_m)
      flag("growth.enabled", "false",
           "grow the mass-dominating particle (spec §4.1); off: St is prescribed by "
           "transport.St"),
      when({growth_on()},
           // <= 100: a calibration factor, not a model; 1e3 took 138 000 steps to 1e4
           // yr on the fiducial scene, 1e30 failed at t = 0
           real("growth.f_grow", "1.0", "",
                "multiplier of the coagulation rate (spec §4.1; with erosion.model = "
                "\"balance\" of its similar-size term only)",
                0.0, true, 100.0, false)),
      when({growth_on()}, real("growth.eps", "0.5", "",
                               "size ratio of the collision partner, St2 = eps St (§3)",
                               0.0, true, 1.0, true)),
      when({growth_on()},
           choice(
               "growth.drag_law", "stokes_re", {"stokes_re", "epstein"},
               "drag: Epstein joined smoothly to Stokes and Reynolds-dependent drag, or "
               "Epstein only (spec §2)")),
      when({growth_on()},
           positive(
               "growth.vg2_factor", "1.0", "",
               "V_g^2 = vg2_factor alpha c_s^2 in the turbulent relative velocity (spec "
               "§3, item 5: 1, the Ormel & Cuzzi 2007 normalisation; alt. 1.5)")),
      when({growth_on()}, real("growth.St_max", "1e4", "",
                               "soft cap of St (m stops growing there; planetesimals "
                               "are converted by the planetesimal channels)",
                               1.0, false)),

      // [porosity] spec §4.2-§4.4 (variable Q_phi; off: phi = 1)
      when({growth_on()}, flag("porosity.enabled", "false",
                               "evolve the filling factor phi (spec §4.3)")),
      when({growth_on(), is("porosity.enabled", {"true"})},
           real("porosity.s_hs", "-0.58", "",
                "hit-and-stick slope d ln phi/d ln m (§4.3)", -1.0, false, 0.0, false)),
      when({growth_on(), is("porosity.enabled", {"true"})},
           positive("porosity.b", "0.15", "",
                    "compression threshold E_imp = 3 b E_roll (§4.2)")),
      when({growth_on(), is("porosity.enabled", {"true"})},
           real("porosity.phi_max", "0.5", "",
                "largest filling factor compaction raises phi to: the cap of the gas and "
                "self-gravity floors (§4.3-§4.4); monomers start at phi = 1, which "
                "hit-and-stick lowers, so phi <= 1 is what holds throughout",
                0.0, true, 1.0, false)),
      when({growth_on(), is("porosity.enabled", {"true"})},
           flag("porosity.gas_compaction", "true",
                "static compression by gas drag (§4.3)")),
      when({growth_on(), is("porosity.enabled", {"true"})},
           flag("porosity.self_gravity", "true",
                "static compression by self-gravity (§4.3)")),

      // [erosion] spec §5.1-§5.2
      when({growth_on()},
           choice("erosion.model", "none", {"none", "halt", "balance"},
                  "erosion by small projectiles: halt (E1) or rate balance (E2)")),
      when({growth_on(), erosion({"halt", "balance"})},
           positive("erosion.v_eros_m_s", "40.0", "m s^-1",
                    "erosion threshold speed (§5.1)")),
      when({growth_on(), erosion({"halt", "balance"})},
           // >= 1e-3: a sharper switch is a step CVODE's Newton iteration cannot cross
           // (erosion_40 with 1e-30 did not reach 1e3 yr in 40 s; 1e-3: 1e4 yr in 7 s)
           real("erosion.width", "0.01", "",
                "width w of the smooth erosion switch (spec §5.2 says 0.05: with fast "
                "growth that lets particles overshoot the stall by 20-40% in St)",
                1e-3, false)),
      when({growth_on(), erosion({"balance"})},
           real("erosion.f_s", "0.1", "",
                "balance: mass fraction of small projectiles (§5.2)", 0.0, false, 1.0,
                true)),
      when({growth_on(), erosion({"balance"})},
           real("erosion.eps_eros", "1.0", "",
                "balance: mass eroded per projectile mass (§5.2)", 0.0, false)),
      when(
          {growth_on(), erosion({"halt", "balance"})},
          real("erosion.St_small", "0.0", "",
               "Stokes number of the small projectiles; 0 = a monomer (§3)", 0.0, false)),

      // [fragmentation], [bouncing] spec §5.3
      when({growth_on()},
           flag("fragmentation.enabled", "false", "similar-size fragmentation (§5.3)")),
      when({growth_on(), is("fragmentation.enabled", {"true"})},
           choice("fragmentation.species", "both", {"both", "silicate", "ice"},
                  "which monomer species fragment: both, or only silicate (inside the "
                  "snow line; spec §11 #17, with porous ice unfragmented, §5.3) or only "
                  "ice")),
      when({growth_on(), is("fragmentation.enabled", {"true"}),
            one_of("fragmentation.species", {"both", "ice"})},
           positive("fragmentation.v_frag_ice_m_s", "60.0", "m s^-1",
                    "ice fragmentation speed")),
      when({growth_on(), is("fragmentation.enabled", {"true"}),
            one_of("fragmentation.species", {"both", "silicate"})},
           positive("fragmentation.v_frag_sil_m_s", "5.0", "m s^-1",
                    "silicate fragmentation speed")),
      when({growth_on()},
           flag("bouncing.enabled", "false",
                "no sticking of compact aggregates (§5.3 as written: at every speed and "
                "mass, not a usable bouncing barrier; see README)")),
      when({growth_on(), is("bouncing.enabled", {"true"})},
           real("bouncing.phi_bounce", "0.3", "",
                "filling factor above which aggregates bounce", 0.0, true, 1.0, false)),

      // [snowline] spec §1.7, §6.3
      flag("snowline.enabled", "true",
           "ice outside r_snow, silicate inside; drifting ice loses f_ice of its mass "
           "there"),
      real("snowline.f_ice", "0.5", "", "ice mass fraction of the icy solids (§1.7)", 0.0,
           false, 1.0, true),

      // [material] spec §0: monomer constants per species
      when({growth_on()},
           // 1 nm - 100 um: interstellar grains span ~5 nm - 1 um; 1e-30 and 1e30
           // failed at t = 0
           real("material.a0_um", "0.1", "micron", "monomer radius (both species)", 1e-3,
                false, 100.0, false)),
      when({growth_on()}, positive("material.xi_crit_angstrom", "8.0", "angstrom",
                                   "critical rolling displacement")),
      when({growth_on()}, positive("material.z0_nm", "0.4", "nm",
                                   "equilibrium atomic spacing (Tabor parameter)")),
      when({growth_on()},
           positive(
               "material.rolling_radius_factor", "1.0", "",
               "R_r = factor * a0 in E_roll = 6 pi^2 gamma R_r xi_crit (§0: 1 or 0.5)")),
      when({growth_on()}, real("material.ice_rho0", "1.4", "g cm^-3",
                               "ice monomer density (no solid is denser than 25)", 0.0,
                               true, 25.0, false)),
      when({growth_on()},
           real("material.ice_gamma", "100.0", "erg cm^-2",
                "ice surface energy per surface gamma (E_roll; JKR uses w = 2 gamma; "
                "metals have 1e3 - 3e3)",
                0.0, true, 1e4, false)),
      when({growth_on()},
           real("material.ice_youngs_gpa", "7.0", "GPa",
                "ice Young's modulus (diamond: 1220)", 0.0, true, 1e4, false)),
      when({growth_on()}, real("material.ice_poisson", "0.25", "", "ice Poisson ratio",
                               0.0, false, 0.5, true)),
      real("material.sil_rho0", "3.0", "g cm^-3",
           "silicate monomer density (no solid is denser than 25)", 0.0, true, 25.0,
           false),
      when({growth_on()},
           real("material.sil_gamma", "25.0", "erg cm^-2",
                "silicate surface energy per surface gamma (§0; metals have 1e3 - 3e3)",
                0.0, true, 1e4, false)),
      when({growth_on()},
           real("material.sil_youngs_gpa", "54.0", "GPa",
                "silicate Young's modulus (diamond: 1220)", 0.0, true, 1e4, false)),
      when({growth_on()}, real("material.sil_poisson", "0.17", "",
                               "silicate Poisson ratio", 0.0, false, 0.5, true)),

      // [planetesimals] spec §7 (needs growth.enabled; each channel owns a Sigma_pl)
      when({growth_on()},
           flag("planetesimals.coagulation", "false",
                "direct coagulation: dust with St >= St_pl that still grows becomes "
                "planetesimals (spec §7.1)")),
      when({growth_on(), is("planetesimals.coagulation", {"true"})},
           positive("planetesimals.St_pl", "10.0", "",
                    "St threshold of direct coagulation")),
      when({growth_on(), is("planetesimals.coagulation", {"true"})},
           // >= 1: no conversion faster than the dynamical time (1e-30 stalled CVODE,
           // t + h = t, at 200 yr)
           real("planetesimals.tau_pl_omega", "10.0", "",
                "conversion time of direct coagulation in units of 1/Omega_K", 1.0,
                false)),
      choice(
          "planetesimals.si", "none", {"none", "d16", "s18", "zcrit"},
          "streaming instability: d16 = Drazkowska et al. 2016 (zeta Sigma_d Omega for "
          "St >= 0.01), s18 = Schoonenberg et al. 2018 (zeta Sigma_d St Omega), both "
          "when the midplane rho_d/rho_g >= eps_crit; zcrit = zeta Sigma_d Omega for "
          "St >= 0.01 when Sigma_d/Sigma_g >= Z_crit(St) of Lim et al. 2025 (revised "
          "Li & Youdin 2021 fit, Pi = 0.05) (spec §7.2)"),
      when({si({"d16"})},
           // <= 1 (each): no conversion faster than the dynamical time (zeta_d16 = 1e30
           // stalled CVODE, t + h = t, at 200 yr)
           real("planetesimals.zeta_d16", "0.01", "", "d16 efficiency", 0.0, true, 1.0,
                false)),
      when({si({"s18"})}, real("planetesimals.zeta_s18", "0.1", "", "s18 efficiency", 0.0,
                               true, 1.0, false)),
      when({si({"zcrit"})}, real("planetesimals.zeta_zcrit", "0.01", "",
                                 "zcrit efficiency", 0.0, true, 1.0, false)),
      when({si({"d16", "zcrit"})},
           positive("planetesimals.St_si_min", "0.01", "",
                    "d16 and zcrit: smallest St that takes part")),
      when({si({"d16", "s18"})},
           positive("planetesimals.eps_crit", "1.0", "",
                    "d16 and s18: midplane rho_d/rho_g that triggers SI (zcrit compares "
                    "Sigma_d/Sigma_g with Z_crit(St) instead)")),

      // [pebbles] spec §8
      real_list("pebbles.radii_au", "au",
                "radii strictly inside the grid where the pebble flux is recorded (the "
                "nearest face); empty = the snow line, 1, 3, 10, 30 au (those inside the "
                "grid); the flux through r_in is always recorded",
                0.0),
      integer("pebbles.samples_per_snapshot", "10",
              "pebble-flux samples (/timeseries) per snapshot interval", 1, 1e5),

      // [grid] spec §10.2
      // at most 1e5 cells: ~1 GB of memory (8.5 GB at 1e6, measured), and ~150 times
      // the finest grid of the work-precision study
      integer("grid.n_cells", "250", "number of radial cells (spacing: grid.stretch)", 4,
              1e5),
      positive("grid.r_in_au", "1.0", "au", "inner edge (open: outflow, booked)"),
      positive("grid.r_out_au", "300.0", "au", "outer edge (closed: zero flux)"),
      real("grid.stretch", "0.0", "",
           "cell spacing d ln r ∝ r^stretch: 0 log-spaced, > 0 finer in the inner disk",
           -2.0, true, 2.0, true),

      // [solver] CVODE BDF + KLU
      real("solver.rtol", "1e-6", "", "CVODE relative tolerance", 1e-14, false, 0.1,
           false),
      real("solver.atol_sigma", "1e-8", "",
           "absolute tolerance of Sigma_d and Sigma_g, relative to the initial maximum "
           "of Sigma (so it scales with the scene); 10x it is also the Sigma_d below "
           "which a cell's m and phi are decoded towards a monomer's",
           1e-30, false, 1.0, false),
      integer("solver.max_steps", "2000000", "limit on the total number of CVODE steps",
              1, 1e12),
      real("solver.max_dt_yr", "0.0", "yr",
           "largest CVODE step (0 = unlimited; else >= 1e-6 yr)", 0.0, false),
      real(
          "solver.newton_coef", "0.03", "",
          "CVODE's nonlinear convergence coefficient (CVodeSetNonlinConvCoef): Newton "
          "stops when its correction is below this fraction of the local error "
          "tolerance; 0.03 rather than CVODE's 0.1: less Newton error in the local error "
          "estimate, fewer failed steps (tests/bench/results/performance_log.md)",
          0.0, true, 1.0, false),
      integer("solver.steps_per_jacobian", "10",
              "k: a Newton-matrix factorisation at least every k steps and a fresh "
              "Jacobian at the first one k or more steps after the last "
              "(CVodeSetLSetupFrequency, CVodeSetJacEvalFrequency; CVODE's own are 20 "
              "and 51): a Jacobian of at most 2k - 1 steps keeps Newton converging where "
              "a cell crosses one of the model's smooth switches, fewer failed "
              "iterations and steps (README, Performance); 0: CVODE's own",
              0, 1e6),

      // [solver] (continued) and [checkpoint]: restart, README "Restart"
      flag("solver.reinit_at_snapshots", "true",
           "reinitialise CVODE at every snapshot time, so that a run restarted from a "
           "checkpoint is bit-for-bit identical to one never stopped; with gas.evolve "
           "the particle laws' eta and gas velocity are also set from the gas there "
           "(false: once, at the start)"),
      real("checkpoint.every_wall_s", "1800.0", "s",
           "checkpoint at the first snapshot after this much wall time since the last "
           "one (0 = off); one is always written at the end and when stopped",
           0.0, false),
      integer("checkpoint.every_snapshots", "0",
              "checkpoint at every k-th snapshot (0 = off)", 0, 1e6),

      // [output]
      // 1e12 yr: far beyond any disk's life, and t_end in seconds stays finite (1e308 yr
      // was inf s: the run wrote its output and failed in CVODE, exit 3)
      real("output.t_end_yr", "1e6", "yr", "end of the run", 1e-6, false, 1e12, false),
      when({is("output.times_yr", {"[]"})},
           real("output.t_first_yr", "100.0", "yr",
                "first snapshot after t = 0 (log-spaced snapshots from here to t_end)",
                1e-6)),
      when({is("output.times_yr", {"[]"})},
           integer("output.n_snapshots", "41",
                   "log-spaced snapshots after t = 0 (t_first..t_end)", 1, 1e6)),
      real_list("output.times_yr", "yr",
                "explicit snapshot times, each <= t_end_yr, strictly increasing, at "
                "least 1e-9 (relative) apart; replaces the log spacing when not empty",
                1e-6),
      text("output.file", "output file (default: out/<scene name>.h5; -o overrides)"),

      // [observe] `panoptic observe` (README "Synthetic observations"): optical
      // constants m = n + i k per species, tabulated against wavelength (n linear, k
      // log-linear in ln lambda between the rows; no extrapolation).
      choice("observe.outer_species", "mix", {"mix", "ice", "sil"},
             "solids outside the snow line (inside: sil): mix = water ice + silicate "
             "with the ice mass fraction snowline.f_ice, ice = pure water ice"),
      when(
          {one_of("observe.outer_species", {"mix"})},
          choice("observe.mix_rule", "bruggeman", {"bruggeman", "maxwell_garnett"},
                 "effective-medium rule of the mix (maxwell_garnett: silicate inclusions "
                 "in an ice matrix)")),
      when({one_of("observe.outer_species", {"mix", "ice"})},
           positive("observe.water_ice_rho", "0.92", "g cm^-3",
                    "density of water ice, for the volume fractions of the mix (with "
                    "material.sil_rho0)")),
      real_table("observe.ice_lambda_mm",
                 "[0.3, 0.5, 1.3, 5.0, 19.0, 39.0, 61.0, 86.0, 110.0]", "mm",
                 "water ice: wavelengths of the table (Warren & Brandt 2008, JGR 113, "
                 "D14220: rows of their table, at 266 K)",
                 0.0),
      real_table(
          "observe.ice_n",
          "[1.7989, 1.7908, 1.7868, 1.7861, 1.7861, 1.7861, 1.7861, 1.7861, 1.7861]", "",
          "water ice: real part n", 0.0),
      real_table("observe.ice_k",
                 "[2.549e-2, 1.405e-2, 5.173e-3, 1.337e-3, 3.574e-4, 1.839e-4, 1.294e-4, "
                 "1.058e-4, 9.675e-5]",
                 "", "water ice: imaginary part k", 0.0),
      real_table("observe.sil_lambda_mm",
                 "[0.29999, 0.49994, 0.70008, 0.99987, 1.2398, 1.4999, 2.0001, 2.4797, "
                 "2.9999, 3.9995, 4.9994, 6.1992, 7.0008, 8.9974, 9.9987, 12.398, "
                 "14.999, 20.001, 29.999, 49.994, 99.987]",
                 "mm",
                 "silicate: wavelengths of the table (Draine 2003, ApJ 598, 1026, "
                 "astrosilicate; rows of his callindex.out_silD03)",
                 0.0),
      real_table("observe.sil_n",
                 "[3.416, 3.405, 3.403, 3.406, 3.409, 3.412, 3.416, 3.418, 3.421, 3.424, "
                 "3.426, 3.428, 3.429, 3.431, 3.432, 3.433, 3.434, 3.434, 3.435, 3.435, "
                 "3.435]",
                 "", "silicate: real part n", 0.0),
      real_table("observe.sil_k",
                 "[0.1551, 0.08922, 0.06918, 0.05573, 0.04893, 0.04361, 0.03665, "
                 "0.03219, 0.02870, 0.02413, 0.02109, 0.01853, 0.01722, 0.01480, "
                 "0.01384, 0.01120, 0.009254, 0.006939, 0.004626, 0.002775, 0.001388]",
                 "", "silicate: imaginary part k", 0.0),
  };
}

}  // namespace

const std::vector<KeySpec>& scene_keys() {
  static const std::vector<KeySpec> keys = make_keys();
  return keys;
}

}  // namespace panoptic
