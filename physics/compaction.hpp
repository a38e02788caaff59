#pragma once
//! Filling-factor evolution of a growing aggregate (spec §4.2-§4.4): the compression
//! slope d ln phi / d ln m of its collisions (hit-and-stick below the compression
//! threshold, Okuzumi et al. 2012; collisional compression above it, by drag regime),
//! and the static compaction floors it relaxes up to (gas pressure and self-gravity,
//! Kataoka et al. 2013b; phi_max). physics/growth_rates.hpp combines them into
//! d ln phi/dt. Templates on T and the gas's G (rules: physics/particle.hpp).
#include <cmath>

#include "disk/local_gas.hpp"
#include "physics/drag.hpp"
#include "physics/growth_options.hpp"
#include "physics/smooth_switches.hpp"
#include "src/core/units.hpp"

namespace panoptic::physics {

//! Longest floor-relaxation time t_relax / kRelaxFraction, in units of 1/Omega (spec §4.4
//! has 1).
//! The floor push softplus_100(ln floor - ln phi)/t_relax must stay small next to the
//! hit-and-stick decline |s_hs|/t_grow while phi is still above the floor; with the
//! spec's t_relax = 0.01 min(t_grow, 1/Omega) the push outruns growth by t_grow Omega
//! wherever growth is slow, and its tail lifts phi above the floor before phi reaches it
//! (at t_grow Omega = 1e4, phi cannot fall below 1.13 floor). With this cap the
//! fiducial planetesimal mass converges faster in the sharpness k than with the 1/Omega
//! cap (13.42 and 13.51 M_earth for k = 100 and 300, against 13.18 and 13.44), at fewer
//! steps (tests/bench/results/performance_log.md). The cap keeps the relaxation going
//! where growth stalls (erosion, fragmentation) on <= 1/Omega.
inline constexpr double kRelaxCapOmega = 100.0;

//! Floor-relaxation time in units of min(t_grow, kRelaxCapOmega/Omega) (spec §4.4 has
//! 0.01). On the floor phi settles where the push softplus_100(z)/t_relax balances
//! compression, |s| t_relax/t_grow = softplus_100(z): with 0.01 that is z < 0 (the push's
//! tail holds phi ~1% above the floor); with 0.03 it is z ~ 0 for the compression slopes
//! -1/8 and -1/5 (spec §4.3), and the push is 3x less stiff. Against the sharp limit
//! (k = 1000, 0.003) on the default grids: fiducial planetesimal mass off by 1.1% with
//! 0.01, 0.54% with 0.03 (0.45% with 0.1, but a floor rising with m^0.4 under
//! self-gravity then lags ~6% behind); erosion_40 by 0.22% / 0.04%; and fewer
//! right-hand sides (tests/bench/results/performance_log.md).
inline constexpr double kRelaxFraction = 0.03;

//! ln x for an x that is a constant of the run (a species' or an option's), remembered
//! for the last x seen at call site `Site`: particle_rates would otherwise take two such
//! logs per cell and call. One entry per site suffices: cells are visited in radial
//! order, so the species changes once per sweep (at the snow line). The same bits as
//! std::log(x).
template <int Site>
double log_of_constant(double x) {
  thread_local double last_x = -1.0, last_ln = 0.0;  // -1: no log taken yet
  if (x != last_x) {
    last_ln = std::log(x);
    last_x = x;
  }
  return last_ln;
}

//! Slope d ln phi / d ln m of collisions of the particle (mass m [g], radius a [cm],
//! Stokes number St) at speed dv [cm s^-1] (spec §4.2-§4.3): hit-and-stick (s_hs) below
//! the compression threshold E_imp = 3 b E_roll, and above it the compression slope of
//! its drag regime [-].
template <class T, class G>
T compression_slope(const T& m, const T& dv, const T& a, const T& St,
                    const LocalGasT<G>& gas, const Species& sp, const GrowthOptions& o) {
  // spec §4.2: E_imp = (1/2)(m/2) dv^2 against the threshold 3 b E_roll. The reduced
  // mass m/2 is that of an equal-mass collision (Okuzumi et al. 2012), as the spec
  // writes it, although dv is that of the eps = 0.5 pair, whose reduced mass m/9 would
  // give 4.5x less energy (compression would start at ~5x the mass).
  const T e_imp = 0.25 * m * dv * dv;
  const T w_comp = log_step(e_imp, 3.0 * o.b * sp.e_roll, 0.1);
  // spec §4.3 compression slopes: Epstein St < 1: -1/8; Stokes St < 1: 0; St >= 1: -1/5
  // (the Stokes-drag slope only where the drag law has a Stokes regime)
  const T w_stokes =
      o.drag == DragLaw::kEpstein ? T(0.0) : T(log_step(knudsen_ratio(a, gas), 1.0, 0.1));
  const T w_heavy = log_step(St, 1.0, 0.1);
  const T s_comp = (1.0 - w_heavy) * ((1.0 - w_stokes) * (-0.125)) + w_heavy * (-0.2);
  const T slope = (1.0 - w_comp) * o.s_hs + w_comp * s_comp;
  return slope;
}

//! ln of the static compaction floor of phi (spec §4.3, Kataoka et al. 2013b): where the
//! gas ram pressure (phi_gas) or self-gravity (phi_grav) equals the aggregate's
//! compressive strength P_c, softly the larger of the two that are on, and softly capped
//! at phi_max. Call only with o.gas_compaction or o.self_gravity [-].
template <class T, class G>
T ln_compaction_floor(const T& m, const T& St, const LocalGasT<G>& gas, const Species& sp,
                      const GrowthOptions& o) {
  using std::log;
  using units::kPi;
  // The floors are power laws of m, St and the gas: taken in logs (ln_soft_max,
  // ln_soft_min), they cost two logs instead of four pow() and two p-th roots.
  const T ln_nmono = log(m / sp.m0);
  T ln_floor = T(0.0);
  if (o.gas_compaction) {  // spec §4.3, Kataoka et al. 2013b: P_gas = P_c
    // phi_gas = (a0 m0 dv_pg Omega / (pi E_roll St))^(3/7) N^(1/7)
    const T dv_pg = gas_drift_speed(St, gas);
    ln_floor =
        (3.0 / 7.0) * log(sp.a0 * sp.m0 * dv_pg * gas.omega_k / (kPi * sp.e_roll * St)) +
        ln_nmono / 7.0;
  }
  if (o.self_gravity) {  // spec §4.3, Kataoka et al. 2013b: P_grav = P_c
    // phi_grav = (G m0^2 / (pi a0 E_roll))^(3/5) N^(2/5)
    const double ln_c =
        0.6 * log_of_constant<0>(units::kG * sp.m0 * sp.m0 / (kPi * sp.a0 * sp.e_roll));
    const T ln_grav = ln_c + 0.4 * ln_nmono;
    ln_floor = o.gas_compaction ? ln_soft_max(ln_floor, ln_grav) : ln_grav;
  }
  ln_floor = ln_soft_min(ln_floor, T(log_of_constant<1>(o.phi_max)));
  return ln_floor;
}

//! The push of phi up to its floor (spec §4.4): softplus_100(ln floor - ln phi) /
//! t_relax, with t_relax = kRelaxFraction min(t_grow, kRelaxCapOmega/Omega) and
//! t_grow = 1/growth, growth the positive part of d ln m/dt [s^-1].
template <class T, class G>
T floor_relaxation_rate(const T& ln_floor, const T& phi, const T& growth,
                        const LocalGasT<G>& gas) {
  using std::log;
  // spec §4.4: relax up to the floor on t_relax = kRelaxFraction min(t_grow, t_cap),
  // with t_cap = kRelaxCapOmega/Omega where the spec has 1/Omega (see kRelaxCapOmega).
  const T rate_grow = growth + 1e-30;
  const T t_grow = 1.0 / rate_grow;
  const T t_relax = kRelaxFraction * soft_min(t_grow, T(kRelaxCapOmega / gas.omega_k));
  // softplus sharpness 100: below the floor by z the push is e^(-100 z)-small, so phi
  // follows max(phi_dyn, floor) to a few per cent (k = 1 or 10 leaks: phi would sit
  // a factor ~2 above the floor wherever t_relax << t_grow).
  const T push = softplus<T>(ln_floor - log(phi), 100.0) / t_relax;
  return push;
}

}  // namespace panoptic::physics
