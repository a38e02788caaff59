#pragma once
//! Planetesimal formation laws (spec §7): the rates at which the dust of a cell turns
//! into planetesimals [g cm^-2 s^-1], by
//!   direct coagulation (§7.1): Sdot = Sigma_d / tau_pl W(St/St_pl) I(dm/dt > 0),
//!                              tau_pl = 10/Omega_K, St_pl = 10;
//!   streaming instability (§7.2), when the midplane rho_d/rho_g >= 1:
//!     d16 (Drazkowska et al. 2016): Sdot = zeta Sigma_d Omega_K for St >= 0.01,
//!     zeta = 0.01;
//!     s18 (Schoonenberg, Ormel & Krijt 2018): Sdot = zeta Sigma_d St Omega_K, zeta =
//!     0.1;
//!   streaming instability, critical-metallicity option (zcrit), when the column
//!   metallicity Z = Sigma_d/Sigma_g exceeds Z_crit(St) (zcrit_lim25) for St >= 0.01:
//!     Sdot = zeta Sigma_d Omega_K, zeta = 0.01.
//! Every threshold is a smooth step (log_step: logistic in ln x over +-width_dex) so
//! CVODE's Newton iteration sees no kink (spec §6.4). The grid module that applies them
//! to every cell and books Sigma_pl: physics/modules/planetesimals.hpp; to every mass
//! bin of the size distribution (spec §15.4): physics/modules/bin_planetesimals.hpp.
#include <cmath>

#include "disk/local_gas.hpp"
#include "physics/particle.hpp"
#include "physics/smooth_switches.hpp"

namespace panoptic::physics {

//! Critical column metallicity Z = Sigma_d/Sigma_g above which the streaming instability
//! clumps particles strongly enough to form planetesimals [-] (spec §7.2, option):
//!   log10 Z_crit = 0.10 (log10 St)^2 + 0.07 log10 St - 2.36,
//! Lim et al. 2025 (ApJ; arXiv:2410.17319) eq. 15, their revision for tau_s = St >= 0.01
//! of the Li & Youdin (2021, ApJ 919, 107) fit, for the pressure-gradient parameter
//! Pi = 0.05 and no external turbulence. The coefficients agree with three published
//! numbers: the fit's minimum, 0.43% at St = 0.45, is Li & Youdin's "critical
//! metallicity as low as 0.4% for the optimum particle sizes" (Pi = 0.05); at St = 0.01
//! it gives 0.79%, Lim et al.'s "strong clumping even at Z <~ 0.01 for tau_s = 0.01";
//! and a public implementation quotes the same three numbers as Lim et al. 2025 eq. 15.
//! Below St = 0.01 the fits do not apply (Li & Youdin: Z_crit rises sharply), so the
//! channel is switched off there (St_si_min).
template <class T>
T zcrit_lim25(const T& st) {
  using std::exp;
  using std::log;
  const double ln10 = std::log(10.0);
  const T x = log(st) / ln10;  // log10 St
  const T log10_z = 0.10 * x * x + 0.07 * x - 2.36;
  return exp(ln10 * log10_z);
}

//! The St part of direct coagulation (spec §7.1): Sigma_d / tau_pl W(St/St_pl), tau_pl =
//! tau_pl_omega / Omega_K. Linear in sigma_d.
template <class T>
T conversion_above_st_pl(const T& sigma_d, const T& st, double omega_k,
                         double tau_pl_omega, double st_pl, double width_dex) {
  const double tau_pl = tau_pl_omega / omega_k;
  return sigma_d / tau_pl * log_step(st, st_pl, width_dex);
}

//! Direct coagulation (spec §7.1): Sigma_d / tau_pl W(St/St_pl) I(dm/dt > 0), tau_pl =
//! tau_pl_omega / Omega_K. dm/dt > 0 smoothly: on while the particle e-folds its mass
//! within 1e9 / Omega_K (a particle held by erosion or fragmentation grows far slower
//! than that).
template <class T>
T coagulation_conversion(const T& sigma_d, const T& st, const T& dlnm_dt, double omega_k,
                         double tau_pl_omega, double st_pl, double width_dex) {
  const T growing = tanh_step<T>(1e9 / omega_k * dlnm_dt);
  const T above =
      conversion_above_st_pl(sigma_d, st, omega_k, tau_pl_omega, st_pl, width_dex);
  return above * growing;
}

//! The streaming instability's midplane trigger (spec §7.2): rho_d/rho_g >= eps_crit,
//! smoothly, with rho_d = Sigma_d/(sqrt(2 pi) h_d) (spec §2). sigma_d > 0.
template <class T, class G>
T si_midplane_trigger(const T& sigma_d, const T& st, const LocalGasT<G>& g,
                      double eps_crit, double width_dex) {
  const T h_d = dust_scale_height(st, g);
  const T eps_mid = midplane_dust_to_gas(sigma_d, h_d, g);
  return log_step(eps_mid, eps_crit, width_dex);
}

//! Streaming instability after Drazkowska et al. (2016) (spec §7.2): zeta Sigma_d
//! Omega_K while `trigger` (si_midplane_trigger) is on and St >= st_si_min.
template <class T>
T si_conversion_d16(const T& sigma_d, const T& st, const T& trigger, double omega_k,
                    double zeta, double st_si_min, double width_dex) {
  return zeta * sigma_d * omega_k * trigger * log_step(st, st_si_min, width_dex);
}

//! Streaming instability after Schoonenberg, Ormel & Krijt (2018) (spec §7.2): zeta
//! Sigma_d St Omega_K while `trigger` (si_midplane_trigger) is on.
template <class T>
T si_conversion_s18(const T& sigma_d, const T& st, const T& trigger, double omega_k,
                    double zeta) {
  return zeta * sigma_d * st * omega_k * trigger;
}

//! Streaming instability by the critical metallicity (spec §7.2 option): zeta Sigma_d
//! Omega_K while Z / Z_crit(St) >= 1 (zcrit_lim25) and St >= st_si_min. The column
//! metallicity takes `sigma_d_pos` (> 0, for its logarithm), the rate sigma_d.
template <class T, class G>
T si_conversion_zcrit(const T& sigma_d, const T& sigma_d_pos, const T& st,
                      const LocalGasT<G>& g, double zeta, double st_si_min,
                      double width_dex) {
  const T z_ratio = sigma_d_pos / (g.sigma_g * zcrit_lim25(st));
  return zeta * sigma_d * g.omega_k * log_step(z_ratio, 1.0, width_dex) *
         log_step(st, st_si_min, width_dex);
}

}  // namespace panoptic::physics
