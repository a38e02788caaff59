#pragma once
//! The filling factor of a sticking product and the compaction floor of each bin in the
//! size-distribution mode (spec §15.3). A bin's porosity is u_k = psi_k / sigma_k, the
//! mass-weighted mean of 1/phi (physics/coagulation/smoluchowski.hpp); an aggregate of
//! mass m and specific volume u has the volume measure W = m u = rho0 V [g].
//!
//! Product of a pair (target i the larger mass, projectile j), at impact energy
//! E = (1/2) mu dv^2 with the reduced mass mu = m_i m_j / (m_i + m_j) (spec §15.3):
//! * hit-and-stick (E << 3 b E_roll): the volume rule of Okuzumi, Tanaka & Sakagami
//!   (2009) used by Okuzumi et al. (2012) for unequal masses, as it is usually cited
//!   [R-O12: written from the citation, not checked against the paper's text]:
//!     V_p = V_1 + V_2 + V_void,  V_void = min(0.99 - 1.03 ln(2/(V_1/V_2 + 1)), 6.94)
//!     V_2,
//!   with V_1 >= V_2. Equal volumes give V_p = 2.99 V_1, the s_hs = 1 - log2(2.99) =
//!   -0.580 of spec §4.3 [V: Pamdeas constant]. The min is a soft-min (p = 8; 2e-8
//!   relative at equal volumes) so that the right-hand side stays smooth.
//! * collisional compression (E >> 3 b E_roll): a reconstruction [C], not Okuzumi et
//!   al.'s (2012) compression formula (after Suyama et al. 2012), whose text we could not
//!   read: the product's ln phi is the mass-weighted mean of its partners' plus the
//!   equilibrium slope s_c of spec §4.3 times ln(m_p / m_i),
//!     ln phi_p = (m_i ln phi_i + m_j ln phi_j)/m_p + s_c ln(1 + m_j/m_i),
//!   s_c = -1/8 (Epstein, St < 1), 0 (Stokes, St < 1), -1/5 (St >= 1) of the target. Its
//!   equal-mass limit is the single-size law d ln phi/d ln m = s_c by construction, and
//!   a small projectile changes the target's phi by O(m_j/m_i).
//! The two are blended in ln u by the logistic in ln(E / 3 b E_roll) over 0.1 dex, as
//! the single-size model switches its slopes (physics/compaction.hpp).
#include <cmath>

#include "disk/local_gas.hpp"
#include "physics/drag.hpp"
#include "physics/smooth_switches.hpp"

namespace panoptic::physics::coagulation {

//! The porosity u = <1/phi>_m [-] of a bin holding sigma and psi [g cm^-2], with its
//! derivatives by sigma and psi [cm^2 g^-1] (zero where a bound holds).
struct BinPorosity {
  double u = 1.0;
  double dlnu_dsigma = 0.0;
  double dlnu_dpsi = 0.0;
  double phi() const { return 1.0 / u; }
};

//! The distribution mode's empty-bin scale e of bin_porosity() is the absolute
//! tolerance of a bin's mass (solver.atol_sigma times the run's dust scale;
//! SizeDistributionOptions::empty_bin_fraction): u is then resolved where the bin's mass
//! is. A bin at e has u halfway between 1 and psi/sigma, as its mass is uncertain by
//! ~100 %; a bin at 100 e has psi/sigma to 1 %, as its mass to ~1 %. An e below the
//! tolerance takes at face value the porosity of bins whose mass CVODE does not resolve,
//! whose psi (u sigma) is then held u times tighter than their sigma: on the porous
//! DustPy disk at e = 1e-2 atol one such bin (sigma_k ~ 4e-2 atol, u ~ 2 600) set 808 of
//! 999 steps (tests/bench/results/porous_cost.md, "The empty-bin scale").
//! This is e, and the bins' absolute tolerance, by default in a porous distribution, in
//! units of the run's dust scale [-] (atol_sigma_from_config, src/model).
inline constexpr double kPorousEmptyBinFraction = 1e-10;

//! An empty-bin scale e below any surface density of a test's state [g cm^-2]: (psi +
//! e)/(sigma + e) is psi/sigma to the last bit, and 1 for an empty bin.
inline constexpr double kTinyEmptyScale = 1e-300;

//! The one filling-factor rule of the distribution mode (spec §15.1): u = psi/sigma of a
//! bin that holds mass, written
//!   u = max(1, (|psi| + e) / (|sigma| + e)),
//! with e [g cm^-2] the empty-bin scale (the distribution mode's: above).
//! u sets a bin's kernel, the voids of its sticking products and its floor; the volume
//! its collisions move is its own psi in proportion to their mass, whatever u
//! (smoluchowski.hpp). The rule:
//! * Continuous in (sigma, psi) everywhere and bounded by the data: a nearly empty bin
//!   whose sigma or psi crosses 0 (round-off and integration error make such bins
//!   slightly negative, sigma has no >= 0 constraint) does not jump between psi/sigma
//!   and 1, and u does not diverge as sigma -> 0 with psi != 0. A bin whose sigma and psi
//!   are both negative (a negative copy of a bin) keeps its u; one whose psi has the
//!   wrong sign has u = |psi|/sigma >= 1, so that the voids e^d - 1 of its products
//!   scale a positive volume (a signed u, linear in psi, let a negative psi feed itself
//!   through them: psi -> -1e22 in a few years on the porous MMSN scene).
//! * Where sigma and psi are well above e, u = psi/sigma to e/sigma; an empty bin
//!   (|sigma|, |psi| << e) is compact, phi = 1, and enters only through the rate of its
//!   first collisions, as before.
//! * u >= 1, i.e. phi <= 1: u is the mass-weighted mean of 1/phi over aggregates that
//!   each have phi <= 1, so a value below 1 is round-off (psi and sigma of a nearly empty
//!   bin that differ in their last bits), not porosity.
//! The derivatives are one-sided at the kinks (|x| at 0, the max at u = 1), where they
//! are taken as 0.
inline BinPorosity bin_porosity(double sigma, double psi, double e) {
  const double s = std::abs(sigma), p = std::abs(psi);
  const double u = (p + e) / (s + e);
  if (!(u > 1.0)) return {};
  const double ds = sigma > 0.0 ? -1.0 : sigma < 0.0 ? 1.0 : 0.0;
  const double dp = psi > 0.0 ? 1.0 : psi < 0.0 ? -1.0 : 0.0;
  return {u, ds / (s + e), dp / (p + e)};
}

//! Okuzumi et al.'s (2012) cap on V_void / V_2 [-].
inline constexpr double kVoidCap = 6.94;

//! The specific volume u of the fluffiest aggregate of mass m [g] made of monomers of
//! mass m0 [g] [-]: the equal-mass hit-and-stick track of the volume rule below, V_p =
//! 2.99 V_1 per doubling, u = (m/m0)^(log2(2.99) - 1) = (m/m0)^0.580 (spec §4.3's s_hs;
//! the BCCA-like growth of Okuzumi, Tanaka & Sakagami 2009, fractal dimension ~1.9), and
//! 1 at or below m0. Fragments landing in a bin of mass m take their parents' u capped
//! at this value [C: ours, amending spec §15.3's "fragments take the filling factor of
//! their parent"]: a piece of N monomers cut from an aggregate is at most as fluffy as
//! the fluffiest aggregate of N monomers (a fractal's sub-volumes are denser than the
//! whole, phi(r) ∝ r^(D - 3)), while the uncapped rule put fragments of u ~ 5e4 into the
//! monomer bin (tests/bench/results/porous_cost.md).
inline double fragment_u_ceiling(double m, double m0) {
  static const double slope = std::log2(2.99) - 1.0;
  return m > m0 ? std::pow(m / m0, slope) : 1.0;
}

//! The terms of a pair's product rules that depend on its masses only (target m_i,
//! projectile m_j [g]): a mass grid's pairs keep them from call to call.
struct PairMasses {
  double m_i = 0.0, m_j = 0.0;  //!< [g]
  double ln1p_ratio = 0.0;      //!< ln(1 + m_j/m_i) = ln(m_p/m_i) [-]
  double frac_j = 0.0;          //!< m_j / m_p [-]
  double half_mu = 0.0;         //!< mu/2 = m_i m_j / (2 (m_i + m_j)) [g]
};

inline PairMasses pair_masses(double m_i, double m_j) {
  return {m_i, m_j, std::log1p(m_j / m_i), m_j / (m_i + m_j),
          0.5 * (m_i * m_j / (m_i + m_j))};
}

//! ln(u_p / u_i) of hit-and-stick: V_p = V_1 + V_2 + V_void (above) [-]; u = <1/phi>
//! [-]. Written without cancelling terms: log1p((W_j + W_void)/W_i) - log1p(m_j/m_i).
inline double ln_u_ratio_hit_and_stick(const PairMasses& pm, double u_i, double u_j) {
  const double w_i = pm.m_i * u_i, w_j = pm.m_j * u_j;
  const double w_big = w_i > w_j ? w_i : w_j;
  const double w_small = w_i > w_j ? w_j : w_i;
  const double f =
      soft_min(0.99 + 1.03 * std::log(0.5 * (w_big / w_small + 1.0)), kVoidCap);
  return std::log1p((w_j + f * w_small) / w_i) - pm.ln1p_ratio;
}

//! ln_u_ratio_hit_and_stick of masses m_i, m_j [g].
inline double ln_u_ratio_hit_and_stick(double m_i, double u_i, double m_j, double u_j) {
  return ln_u_ratio_hit_and_stick(pair_masses(m_i, m_j), u_i, u_j);
}

//! ln(u_p / u_i) of collisional compression (the reconstruction above) [-];
//! s_c: slope d ln phi / d ln m [-].
inline double ln_u_ratio_compression(const PairMasses& pm, double u_i, double u_j,
                                     double s_c) {
  return pm.frac_j * std::log(u_j / u_i) - s_c * pm.ln1p_ratio;
}

//! Equilibrium compression slope of spec §4.3 for the target (radius a [cm], St):
//! -1/8 (Epstein drag, St < 1), 0 (Stokes drag, St < 1), -1/5 (St >= 1), blended by the
//! logistic steps of physics/compaction.hpp (x = 4a/(9 lambda) about 1 and St about 1,
//! 0.1 dex) [-].
inline double compression_slope_of_target(double a, double St, const LocalGas& gas,
                                          DragLaw law) {
  const double w_stokes =
      law == DragLaw::kEpstein ? 0.0 : log_step(knudsen_ratio(a, gas), 1.0, 0.1);
  const double w_heavy = log_step(St, 1.0, 0.1);
  return (1.0 - w_heavy) * ((1.0 - w_stokes) * (-0.125)) + w_heavy * (-0.2);
}

//! ln(u_p / u_i) of a sticking pair at impact energy e_imp [erg] against the threshold
//! 3 b E_roll [erg]: hit-and-stick and compression blended (above) [-]. Flattened
//! (log_step and soft_min inlined; the libm calls stay calls): cell_coefficients calls it
//! for N^2/2 pairs, and GCC otherwise keeps log_step out of line there when the unit has
//! more callers of it (8 % more instructions per porous rebuild under callgrind,
//! tests/bench/results/porous_cost.md). Inlining moves no bit: the build targets
//! x86-64 without FMA, so nothing is contracted.
[[gnu::flatten]] inline double product_ln_u_ratio(const PairMasses& pm, double u_i,
                                                  double u_j, double e_imp,
                                                  double e_threshold, double s_c) {
  const double w = log_step(e_imp, e_threshold, 0.1);
  if (w == 1.0) return ln_u_ratio_compression(pm, u_i, u_j, s_c);
  const double hs = ln_u_ratio_hit_and_stick(pm, u_i, u_j);
  if (w == 0.0) return hs;
  return (1.0 - w) * hs + w * ln_u_ratio_compression(pm, u_i, u_j, s_c);
}

//! product_ln_u_ratio of masses m_i, m_j [g].
inline double product_ln_u_ratio(double m_i, double u_i, double m_j, double u_j,
                                 double e_imp, double e_threshold, double s_c) {
  return product_ln_u_ratio(pair_masses(m_i, m_j), u_i, u_j, e_imp, e_threshold, s_c);
}

//! Impact energy of a pair, E = (1/2) mu dv^2, mu = m_i m_j / (m_i + m_j) (spec §15.3)
//! [erg].
inline double impact_energy(const PairMasses& pm, double dv) {
  return pm.half_mu * dv * dv;
}

//! impact_energy of masses m_i, m_j [g].
inline double impact_energy(double m_i, double m_j, double dv) {
  return impact_energy(pair_masses(m_i, m_j), dv);
}

}  // namespace panoptic::physics::coagulation
