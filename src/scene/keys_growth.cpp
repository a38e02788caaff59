// The key tables of the growth model: [growth], [porosity], [erosion],
// [fragmentation], [bouncing], [material].
#include "src/scene/key_builders.hpp"
#include "src/scene/key_tables.hpp"

namespace panoptic::scene_detail {

// [growth] spec §3, §4.1: the mass of the mass-dominating particle (variable Q_m)
std::vector<KeySpec> growth_keys() {
  return {
      flag("growth.enabled", "false",
           "grow the mass-dominating particle (spec §4.1); off: St is prescribed by "
           "transport.St"),
      when({growth_on()},
           // <= 100: a calibration factor, not a model; larger factors make the run
           // stiff beyond use, and far larger ones fail at t = 0
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
  };
}

// [porosity] spec §4.2-§4.4 (variable Q_phi; off: phi = 1)
std::vector<KeySpec> porosity_keys() {
  return {
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
      when({growth_on(), is("porosity.enabled", {"true"}), distribution()},
           choice("porosity.bins", "evolved", {"evolved", "track"},
                  "a size distribution's filling factors: evolved, a volume moment "
                  "per bin (Okuzumi et al. 2009, spec §15.1); or track, the single-size "
                  "law's phi(m) at each cell's gas (§4.2-§4.4), at the compact mode's "
                  "cost: close to evolved with the compaction floors on, not without "
                  "them (tests/bench/results/porosity_track.md)")),
  };
}

// [erosion] spec §5.1-§5.2
std::vector<KeySpec> erosion_keys() {
  return {
      when({growth_on()},
           choice("erosion.model", "none", {"none", "halt", "balance"},
                  "erosion by small projectiles: halt (E1) or rate balance (E2), the "
                  "single-size closures of spec §5.2; with model.kind = "
                  "\"distribution\" either applies the Krijt et al. (2015) rule itself "
                  "to the pairs of bins, m_proj/m_target < 1/10 (spec §5.1, §15.2)")),
      when({growth_on(), erosion({"halt", "balance"})},
           positive("erosion.v_eros_m_s", "40.0", "m s^-1",
                    "erosion threshold speed (§5.1)")),
      when({growth_on(), erosion({"halt", "balance"})},
           // >= 1e-3: a sharper switch is a step CVODE's Newton iteration cannot cross
           real("erosion.width", "0.01", "",
                "width w of the smooth erosion switch S(dv/v_eros) (spec §5.2 says "
                "0.05: with fast growth that lets particles overshoot the stall by "
                "20-40% in St); the same switch per pair of bins in the distribution",
                1e-3, false)),
      when({growth_on(), erosion({"balance"}), single_size()},
           real("erosion.f_s", "0.1", "",
                "balance: mass fraction of small projectiles (§5.2)", 0.0, false, 1.0,
                true)),
      // read by balance (single size) and by the distribution's pairs (either model)
      when({growth_on(), erosion({"halt", "balance"}),
            either(distribution(), {erosion({"balance"})})},
           real("erosion.eps_eros", "1.0", "",
                "mass eroded per projectile mass: balance (§5.2), and every model in the "
                "distribution (§15.2: < 10 there)",
                0.0, false)),
      when(
          {growth_on(), erosion({"halt", "balance"}), single_size()},
          real("erosion.St_small", "0.0", "",
               "Stokes number of the small projectiles; 0 = a monomer (§3)", 0.0, false)),
  };
}

// [fragmentation] spec §5.3
std::vector<KeySpec> fragmentation_keys() {
  return {
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
  };
}

// [bouncing] spec §5.3
std::vector<KeySpec> bouncing_keys() {
  return {
      when({growth_on()},
           flag("bouncing.enabled", "false",
                "no sticking of compact aggregates (§5.3 as written: at every speed and "
                "mass, not a usable bouncing barrier; see tests/README.md, What works)")),
      when({growth_on(), is("bouncing.enabled", {"true"})},
           real("bouncing.phi_bounce", "0.3", "",
                "filling factor above which aggregates bounce", 0.0, true, 1.0, false)),
  };
}

// [material] spec §0: monomer constants per species
std::vector<KeySpec> material_keys() {
  return {
      when({growth_on()},
           // 1 nm - 100 um: interstellar grains span ~5 nm - 1 um; radii far outside
           // fail at t = 0
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
  };
}

}  // namespace panoptic::scene_detail
