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
  return {
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
      // settles into ever thinner layers: a run slows by orders of magnitude for each
      // decade of alpha below that, and CVODE fails at t = 0 far below it.
      real("disk.alpha", literal(gas_defaults::kAlpha), "",
           "Shakura-Sunyaev alpha, D_g = alpha c_s H (§1.5); below 1e-8 molecular "
           "viscosity would dominate",
           1e-8, false, 1.0, false),
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
