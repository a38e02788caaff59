// The key tables of what leaves the dust: [planetesimals], [pebbles].
#include "src/scene/key_builders.hpp"
#include "src/scene/key_tables.hpp"

namespace panoptic::scene_detail {

// [planetesimals] spec §7 (needs growth.enabled; each channel owns a Sigma_pl)
std::vector<KeySpec> planetesimals_keys() {
  return {
      when({growth_on()},
           flag("planetesimals.coagulation", "false",
                "direct coagulation: dust with St >= St_pl that still grows becomes "
                "planetesimals (spec §7.1)")),
      when({growth_on(), is("planetesimals.coagulation", {"true"})},
           positive("planetesimals.St_pl", "10.0", "",
                    "St threshold of direct coagulation")),
      when({growth_on(), is("planetesimals.coagulation", {"true"})},
           // >= 1: no conversion faster than the dynamical time (a far faster one stalls
           // CVODE: t + h = t)
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
           // <= 1 (each): no conversion faster than the dynamical time (a far faster one
           // stalls CVODE: t + h = t)
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
  };
}

// [pebbles] spec §8
std::vector<KeySpec> pebbles_keys() {
  return {
      real_list("pebbles.radii_au", "au",
                "radii strictly inside the grid where the pebble flux is recorded (the "
                "nearest face); empty = the snow line, 1, 3, 10, 30 au (those inside the "
                "grid); the flux through r_in is always recorded",
                0.0),
      integer("pebbles.samples_per_snapshot", "10",
              "pebble-flux samples (/timeseries) per snapshot interval", 1, 1e5),
  };
}

}  // namespace panoptic::scene_detail
