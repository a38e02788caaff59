#pragma once
//! Drag on the mass-dominating particle (spec §2): its Stokes number, Epstein, and the
//! smooth Epstein-Stokes-Reynolds law solved by Newton's method in ln St; the
//! particle-gas speed and the particle Reynolds number it needs. Sources: Epstein
//! (1924) and Stokes drag; Weidenschilling (1977) C_D(Re_p); the smooth form of
//! DiscEvolution (Booth et al., porous_dust.py); Nakagawa, Sekiya & Hayashi (1986) for
//! the particle-gas speed. Templates on T and the gas's G (rules: physics/particle.hpp).
#include <cmath>
#include <numbers>

#include "disk/local_gas.hpp"
#include "physics/particle.hpp"
#include "physics/smooth_switches.hpp"
#include "src/core/autodiff.hpp"

namespace panoptic::physics {

//! Newton steps on ln St in stokes_number() (5 reach round-off) [-].
inline constexpr int kDragIterations = 6;
//! Re_p below which f_Re = (1 + Re_p^(0.4 p) + (0.01833 Re_p)^p)^(1/p) is 1 to round-off:
//! Re_p^3.2 < 1e-16 [-].
inline constexpr double kReNegligible = 1e-5;
//! ln kReNegligible.
inline constexpr double kLnReNegligible = -11.512925464970229;
//! C_D = 0.44 written as 24/Re_p times (this constant * Re_p) (Weidenschilling 1977) [-].
inline constexpr double kCdNewton = 0.44 / 24.0;

//! Drag law of spec §9 (`drag.law`).
enum class DragLaw {
  kEpstein,   //!< Epstein drag at every size
  kStokesRe,  //!< smooth Epstein-Stokes-Reynolds law (default)
};

// ---------------------------------------------------------------------------------------------
// Drag (spec §2)
// ---------------------------------------------------------------------------------------------

//! Epstein Stokes number St = t_s Omega_K with t_s = rho_int a / (rho_g v_th) (spec §2;
//! Epstein 1924). At the midplane this equals pi rho_int a / (2 Sigma_g) [-].
template <class T, class G>
T stokes_epstein(const T& a, const T& rho_int, const LocalGasT<G>& gas) {
  return rho_int * a * (gas.omega_k / (gas.rho_g * gas.v_th));
}

//! x = 4 a / (9 lambda): Stokes/Epstein stopping-time ratio at Re_p < 1 (spec §2) [-].
//! t_Stokes = 2 rho_int a^2 / (9 nu_mol rho_g) = x t_Epstein when nu_mol = v_th lambda
//! / 2.
template <class T, class G>
T knudsen_ratio(const T& a, const LocalGasT<G>& gas) {
  return 4.0 * a / (9.0 * gas.mfp);
}

//! Laminar particle-gas speed dv_pg = eta v_K St sqrt(4 + St^2) / (1 + St^2) (spec §2;
//! Nakagawa, Sekiya & Hayashi 1986 radial and azimuthal drift combined) [cm s^-1].
template <class T, class G>
T gas_drift_speed(const T& St, const LocalGasT<G>& gas) {
  using std::sqrt;
  const T st2 = St * St;
  const T shape = St * sqrt(4.0 + st2) / (1.0 + st2);
  // the speed, |eta| v_K: where the pressure rises outward (eta < 0, the inner side of a
  // pressure maximum, or a surface density rising with r) the particle drifts outward
  // as fast, and the drag laws and the gas-compaction floor take logs of this speed
  return std::abs(gas.headwind()) * shape;
}

//! Log-slope of gas_drift_speed(): d ln(dv_pg) / d ln St =
//! 1 + St^2/(4 + St^2) - 2 St^2/(1 + St^2), in [-0.115, 1] [-].
template <class T>
T gas_drift_speed_log_slope(const T& St) {
  const T st2 = St * St;
  return 1.0 + st2 / (4.0 + st2) - 2.0 * st2 / (1.0 + st2);
}

//! Particle Reynolds number Re_p = 2 a dv_pg / nu_mol (spec §2) [-].
template <class T, class G>
T particle_reynolds(const T& a, const T& dv_pg, const LocalGasT<G>& gas) {
  return 2.0 * a * dv_pg / gas.nu_mol;
}

//! Smooth C_D(Re_p) correction f_Re of spec §2, with p = kSoftMaxPower:
//!   f_Re = (1 + Re_p^(0.4 p) + (0.01833 Re_p)^p)^(1/p)
//!        ~ max(1, Re_p^0.4, 0.01833 Re_p).
//! The three branches are Weidenschilling's (1977) C_D = 24/Re_p, 24 Re_p^-0.6, 0.44
//! written as t_s = t_Stokes / f_Re. Written with Re_p^(0.4 p) = Re_p^3.2 (not
//! (Re_p^0.4)^p) so that Re_p = 0 (no headwind) has a finite derivative [-].
template <class T>
T reynolds_correction(const T& re_p) {
  using std::pow;
  const double p = kSoftMaxPower;
  const T fp = 1.0 + pow(re_p, 0.4 * p) + power_p<T>(kCdNewton * re_p, p);
  return root_p<T>(fp, p);
}

//! d ln f_Re / d ln Re_p = (0.4 Re_p^(0.4p) + (0.01833 Re_p)^p) / f_Re^p [-].
template <class T>
T reynolds_correction_log_slope(const T& re_p) {
  using std::pow;
  const double p = kSoftMaxPower;
  const T b = pow(re_p, 0.4 * p);
  const T c = power_p<T>(kCdNewton * re_p, p);
  return (0.4 * b + c) / (1.0 + b + c);
}

//! Drag-regime factor g = St / St_Epstein of spec §2 (DiscEvolution form, smoothed):
//!   g(x, Re_p) = soft_max(1, x / f_Re(Re_p)) = (1 + (x/f_Re)^p)^(1/p),  p = 8.
//! Limits: g -> 1 (Epstein) for x << 1; g -> x (Stokes, Re_p < 1), x Re_p^-0.4, or
//! x / (0.01833 Re_p) (C_D = 0.44) for x >> f_Re. The hard max() of DiscEvolution
//! (`where(x < 1, 1, x/f)`) has a kink at every regime boundary, which stalls CVODE's
//! Newton iteration (spec §6.4); the p-norm is C-infinity, within 1% of the hard law once
//! the two competing branches differ by more than 35%, and at most 9% (2^(1/8)) above it
//! exactly at a boundary, well inside the uncertainty of the drag law there [-].
template <class T>
T drag_regime_factor(const T& x, const T& re_p) {
  const T f = reynolds_correction(re_p);
  const T y = x / f;
  return soft_max(T(1.0), y);
}

//! Stokes number of an aggregate of mass m [g] and filling factor phi [-] made of
//! monomers of density rho0 [g cm^-3], spec §2 [-].
//!
//! kEpstein: St = St_Ep. kStokesRe: St = St_Ep g(x, Re_p(St)), implicit because
//! Re_p = 2 a dv_pg(St) / nu_mol. Plain fixed-point (Picard) iteration St <- St_Ep g(...)
//! does not converge where C_D = 0.44 and St < 1: there St_Ep g ~ 1/dv_pg ~ 1/St, a map
//! with slope -1 in ln St that oscillates forever (5 Picard steps leave 1-2% errors at
//! 1-5 au and up to a factor e^4 for fluffy km bodies at 0.3 au). We therefore iterate
//! the Newton map of
//!   G(u) = u - ln(St_Ep g(x, Re_p(e^u))),  u = ln St,
//!   u <- u - G(u) / G'(u),   G' = 1 - (dln g/dln f)(dln f/dln Re)(dln dv_pg/dln St),
//! with analytic slopes (G' lies in [0.88, 2], so the step is always well defined),
//! starting from the smaller of the Re_p = 0 law u0 = ln(St_Ep soft_max(1, x)) and the
//! hard-branch solution (below). A bounded number of steps keeps the result a
//! deterministic function of (m, phi), smooth to round-off, whose AutoDiff derivative
//! converges to the implicit-function derivative (the Newton map is flat at its fixed
//! point). The fiducial run needs at most four steps per call; 6 leave a margin.
//! stokes_number_of_radius() is the same law for a known radius a = radius(m, phi, rho0)
//! (the growth model's St cache keeps a for the rates; the same bits).
template <class T, class G>
T stokes_number_of_radius(const T& a, const T& phi, double rho0, const LocalGasT<G>& gas,
                          DragLaw law = DragLaw::kStokesRe,
                          int iterations = kDragIterations) {
  using std::exp;
  using std::log;
  using std::pow;
  const T rho_int = internal_density(phi, rho0);
  const T st_ep = stokes_epstein(a, rho_int, gas);  // spec §2; Epstein (1924)
  if (law == DragLaw::kEpstein) return st_ep;

  const double p = kSoftMaxPower;
  const T x = knudsen_ratio(a, gas);
  // A grain inside the Epstein regime (x < 0.01: ln g < x^8/8 = 1.25e-17 for any Re_p,
  // since f_Re >= 1, below half an ulp of 1) has St = St_Ep to round-off: the Newton
  // solve would return exp(ln St_Ep).
  if (value_of(x) < 1e-2) return st_ep;
  const T ln_st_ep = log(st_ep);
  // g = soft_max(1, x / f_Re) = (1 + y^p)^(1/p) with y^p = x^p / f_Re^p, so ln g =
  // log1p(x^p / f_Re^p) / p: no p-th root, no soft_max (drag_regime_factor() is the same
  // function; x < 3e38 in any disk, so x^p is finite).
  const T xp = power_p<T>(x, p);
  T u = ln_st_ep + log1p_nonneg(xp) / p;  // the Re_p = 0 law
  // Re_p = K shape(St) with K = 2 a eta v_K / nu_mol and shape = St sqrt(4 + St^2) / (1 +
  // St^2) <= min(2 St, 1.12) (gas_drift_speed).
  const T ln_k = log(2.0 * a * (std::abs(gas.headwind()) / gas.nu_mol));  // |eta| v_K
  // Re_p < kReNegligible at the Re_p = 0 law (bounded with shape <= 2 St) makes f_Re^p =
  // 1 + Re_p^3.2 + ... equal to 1 to round-off: that law solves G(u) = 0, and St is its
  // value without a Newton step (no pow; most grains before the drift barrier).
  if (value_of(ln_k) + std::numbers::ln2 + value_of(u) < kLnReNegligible) return exp(u);
  // First guess where Re_p matters: the hard-max law f_Re = max(1, Re_p^0.4, 0.01833
  // Re_p) with shape = min(2 St, 1), solved in closed form on each branch (St
  // f_i(Re_p(St)) = St_Ep x rises with St, so the solution is the least of the branch
  // solutions, and each branch's is the larger of its small- and large-St solutions);
  // never above the Re_p = 0 law. On the fiducial run it lies within 0.17 in ln St of
  // the smooth law's root (the p-norm corners and the shape), where the Re_p = 0 law is
  // up to 3.1 off, which saves the Newton solve below more than one step per call.
  {
    const T ln_sx = ln_st_ep + log(x);  // f_Re = 1 (Stokes)
    const double ln2 = std::numbers::ln2;
    const T b_small = (ln_sx - 0.4 * (ln_k + ln2)) / 1.4;  // f_Re = Re_p^0.4
    const T b_large = ln_sx - 0.4 * ln_k;
    const T c_small = 0.5 * (ln_sx - std::log(2.0 * kCdNewton) - ln_k);  // 0.01833 Re_p
    const T c_large = ln_sx - std::log(kCdNewton) - ln_k;
    const T& b = value_of(b_small) > value_of(b_large) ? b_small : b_large;
    const T& c = value_of(c_small) > value_of(c_large) ? c_small : c_large;
    const T& bc = value_of(b) < value_of(c) ? b : c;
    const T& guess = value_of(bc) > value_of(ln_st_ep) ? bc : ln_st_ep;
    if (value_of(guess) < value_of(u)) u = guess;
  }
  for (int it = 0; it < iterations; ++it) {
    const T st = exp(u);
    const T dv = gas_drift_speed(st, gas);
    const T re_p = particle_reynolds(a, dv, gas);
    // f_Re and its log-slope share Re_p^(0.4 p) and (0.01833 Re_p)^p: computed once
    // (the same expressions as reynolds_correction() and its _log_slope()).
    const T b = pow(re_p, 0.4 * p);
    const T c = power_p<T>(kCdNewton * re_p, p);
    const T fp = 1.0 + b + c;              // f_Re^p
    const T yp = xp / fp;                  // (x / f_Re)^p
    const T dlng_dlnf = -yp / (1.0 + yp);  // d ln g / d ln f for g = (1 + (x/f)^p)^(1/p)
    const T dlnf_dlnre = (0.4 * b + c) / fp;
    const T slope = dlng_dlnf * dlnf_dlnre * gas_drift_speed_log_slope(st);
    const T residual = u - ln_st_ep - log1p_nonneg(yp) / p;  // G(u)
    u = u - residual / (1.0 - slope);
    // Once |G| < 1e-8 this Newton step leaves an error ~|G''/2G'| G^2 < 1e-16 in u
    // (quadratic convergence; over 0.05-300 au, 1e-15 < m < 1e23 g, 1e-6 < phi < 1 the
    // result differs from one converged to |G| < 1e-14 by < 2e-15 (1 + |u|)), and the AD
    // derivative is converged to ~|G| (the Newton map is flat at its fixed point), so
    // stop. The test is on the value, so double and AD stop at the same step and agree
    // bit for bit.
    if (std::abs(value_of(residual)) < 1e-8) break;
  }
  return exp(u);
}

//! Stokes number of an aggregate of mass m [g] and filling factor phi (above).
template <class T, class G>
T stokes_number(const T& m, const T& phi, double rho0, const LocalGasT<G>& gas,
                DragLaw law = DragLaw::kStokesRe, int iterations = kDragIterations) {
  return stokes_number_of_radius(radius(m, phi, rho0), phi, rho0, gas, law, iterations);
}

}  // namespace panoptic::physics
