// The key tables of the star and the gas disk: [star], [disk], [gas]. The defaults of
// the gas come from disk/gas_defaults.hpp, the one statement of them.
#include "disk/gas_defaults.hpp"
#include "src/scene/key_builders.hpp"
#include "src/scene/key_tables.hpp"

namespace panoptic::scene_detail {

// [star] spec §1.1
std::vector<KeySpec> star_keys() {
  return {
      // Bounds on the physical keys: what a disk around a star can be (brown dwarfs to
      // massive stars, cold to hot, up to a self-gravitating disk), so that a typo (an
      // exponent off by decades) is refused by name instead of failing in the solver.
      real("star.mass_msun", "1.0", "M_sun", "stellar mass", 0.01, false, 100.0, false),
      real("star.luminosity_lsun", "1.0", "L_sun", "stellar luminosity (scales T, §1.3)",
           1e-4, false, 1e7, false),
  };
}

// [disk] spec §1.2-§1.7
std::vector<KeySpec> disk_keys() {
  const UsedWhen smooth_model = one_of("disk.model", {"powerlaw", "lbp"});
  const UsedWhen sigma_bump = one_of("disk.sigma_bump", {"gaussian"});
  const UsedWhen alpha_bump = one_of("disk.alpha_profile", {"gaussian"});
  return {
      choice("disk.model", "powerlaw", {"powerlaw", "lbp", "table"},
             "gas surface density: powerlaw = MMSN-like (§1.2 A), lbp = Lynden-Bell & "
             "Pringle similarity profile (§1.2 B), table = Sigma_g(r) and T(r) from the "
             "CSV file disk.table_file"),
      when({disk_model("powerlaw")},
           choice("disk.sigma_norm", "sigma_1au", {"sigma_1au", "mass"},
                  "powerlaw: what sets the level of Sigma_g: sigma_1au = disk.sigma_1au, "
                  "mass = disk.m_gas_msun between grid.r_in_au and grid.r_out_au")),
      when({disk_model("powerlaw"), one_of("disk.sigma_norm", {"sigma_1au"})},
           real("disk.sigma_1au", "1700.0", "g cm^-2",
                "powerlaw: gas surface density at 1 au (MMSN 1700)", 0.0, true, 1e6,
                false)),
      when({disk_model("powerlaw"), one_of("disk.sigma_norm", {"mass"})},
           real("disk.m_gas_msun", "0.01", "M_sun",
                "powerlaw with sigma_norm = \"mass\": gas mass between grid.r_in_au and "
                "grid.r_out_au (not to infinity, unlike the lbp disk.m_disk_msun: for "
                "p <= 2 that diverges)",
                0.0, true, 10.0, false)),
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
      when({disk_model("table")},
           text("disk.table_file",
                "table: CSV file (relative to the scene file that sets it; from --set, "
                "to the "
                "current directory) with the header "
                "r_au,sigma_g_gcm2,T_K and one row per radius, covering the grid; "
                "Sigma_g and T are interpolated as power laws between rows")),
      when({smooth_model},
           choice("disk.sigma_bump", "none", {"none", "gaussian"},
                  "powerlaw, lbp: a Gaussian bump on Sigma_g, Sigma_g [1 + A exp(-(r - "
                  "r0)^2 / (2 w^2))] (a pressure maximum traps dust)")),
      when({smooth_model, sigma_bump},
           real("disk.sigma_bump_amplitude", "1.0", "",
                "A of the Sigma_g bump (> 0 a bump, between -1 and 0 a gap)", -1.0, true,
                1e3, false)),
      when({smooth_model, sigma_bump}, positive("disk.sigma_bump_r_au", "10.0", "au",
                                                "centre r0 of the Sigma_g bump")),
      when({smooth_model, sigma_bump},
           positive("disk.sigma_bump_width_au", "1.0", "au",
                    "width w of the Sigma_g bump (standard deviation)")),
      when({smooth_model},
           real("disk.T_1au", literal(gas_defaults::kT1au), "K",
                "temperature at 1 au for L_* = L_sun (§1.3)", 1.0, false, 1e4, false)),
      when({smooth_model}, real("disk.q", literal(gas_defaults::kQ), "",
                                "T ∝ r^-q (§1.3)", -2.0, false, 3.0, false)),
      when({smooth_model}, real("disk.T_floor", literal(gas_defaults::kTFloor), "K",
                                "temperature floor (§1.3)", 0.0, false)),
      real("disk.mu", literal(gas_defaults::kMu), "",
           "mean molecular weight (§1.1; 0.5 for ionised hydrogen, no gas is heavier "
           "than 100)",
           0.5, false, 100.0, false),
      choice("disk.alpha_profile", "constant", {"constant", "gaussian", "table"},
             "alpha(r): constant = disk.alpha; gaussian = disk.alpha [1 + A exp(-(r - "
             "r0)^2 / (2 w^2))]; table = from disk.alpha_file. The one alpha of "
             "diffusion, relative velocities, dust scale heights and viscosity (§1.5)"),
      // >= 1e-8: weaker "turbulence" is below the gas's molecular viscosity, which the
      // model leaves out (alpha_mol = nu_mol / (c_s H) = 2 mu m_H / (sigma_mol Sigma_g),
      // spec §1.5-1.6: 2.3e-12 at 1 au, 1.2e-8 at 300 au in the MMSN, so the turbulent
      // Reynolds number of Ormel & Cuzzi's velocities falls to ~1 there), and the dust
      // settles into ever thinner layers: a run slows by orders of magnitude for each
      // decade of alpha below that, and CVODE fails at t = 0 far below it. The same
      // bounds hold for every value of an alpha profile (src/model/scene_validation.cpp).
      when({one_of("disk.alpha_profile", {"constant", "gaussian"})},
           real("disk.alpha", literal(gas_defaults::kAlpha), "",
                "Shakura-Sunyaev alpha, D_g = alpha c_s H (§1.5); below 1e-8 molecular "
                "viscosity would dominate",
                1e-8, false, 1.0, false)),
      when({alpha_bump},
           real("disk.alpha_bump_amplitude", "-0.9", "",
                "A of the alpha profile (> 0 a bump, between -1 and 0 a dip)", -1.0, true,
                1e4, false)),
      when({alpha_bump}, positive("disk.alpha_bump_r_au", "10.0", "au",
                                  "centre r0 of the alpha bump or dip")),
      when({alpha_bump},
           positive("disk.alpha_bump_width_au", "1.0", "au",
                    "width w of the alpha bump or dip (standard deviation)")),
      when({one_of("disk.alpha_profile", {"table"})},
           text("disk.alpha_file",
                "alpha_profile = \"table\": CSV file (relative to the scene file that "
                "sets it; from --set, to "
                "the current directory) "
                "with the header r_au,alpha, covering the grid; log-log interpolated")),
      positive("disk.sigma_mol", literal(gas_defaults::kSigmaMol), "cm^2",
               "molecular cross section (§1.6)"),
      positive("disk.T_sub", literal(gas_defaults::kTSub), "K",
               "water-ice sublimation temperature (§1.7)"),
  };
}

// [gas] spec §1.2, §6.1
std::vector<KeySpec> gas_keys() {
  return {
      flag(
          "gas.evolve", "false",
          "evolve Sigma_g by viscous diffusion (nu = alpha c_s H); the gas velocity then "
          "enters the dust drift"),
      when(
          {is("gas.evolve", {"true"})},
          choice("gas.inner_bc", "free_flow", {"free_flow", "zero_torque"},
                 "inner boundary of the evolving gas: free_flow = accretes through r_in "
                 "as if the disk went on; zero_torque = nu Sigma_g r^(1/2) = 0 at r_in")),
  };
}

}  // namespace panoptic::scene_detail
