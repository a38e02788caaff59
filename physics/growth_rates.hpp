#pragma once
//! Local growth and filling-factor rates of the mass-dominating particle of one cell: the
//! semi-analytical porous coagulation model (spec §4, §5; Krijt et al. 2016 built on
//! Okuzumi et al. 2012, Kataoka et al. 2013, Krijt et al. 2015). Pure functions,
//! templated on the scalar type so that the cell Jacobian is exact (src/autodiff.hpp).
//!
//!   dm/dt = f_grow 2 sqrt(pi) a^2 dv Sigma_d / h_d  x  [erosion, fragmentation,
//!   bouncing] d ln phi/dt = s(E_imp, drag regime, St) (d ln m/dt)_+  +  softplus_k(ln
//!   phi_floor -
//!                 ln phi) / t_relax,   phi_floor = max(phi_gas, phi_grav)  (spec §4.4)
#include <cmath>

#include "physics/local_gas.hpp"
#include "physics/particle.hpp"
#include "physics/relative_velocity.hpp"
#include "src/autodiff.hpp"
#include "src/units.hpp"

namespace panoptic::physics {

//! Monomer species of a cell (ice outside the snow line, silicate inside; spec §1.7).
struct Species {
  double a0 = 1e-5;     //!< monomer radius [cm]
  double rho0 = 1.4;    //!< monomer density [g cm^-3]
  double m0 = 0.0;      //!< monomer mass [g]
  double e_roll = 0.0;  //!< rolling energy [erg] (spec §0)
  double v_frag = 6e3;  //!< fragmentation speed [cm s^-1] (spec §5.3)
};

enum class ErosionModel { kNone, kHalt, kBalance };

//! Switches and parameters of the growth model (scene tables growth, porosity, erosion,
//! fragmentation, bouncing). Speeds cgs.
struct GrowthOptions {
  double f_grow = 1.0;  //!< growth-rate multiplier (spec §4.1)
  double eps = 0.5;     //!< partner size ratio (spec §3)
  DragLaw drag = DragLaw::kStokesRe;
  double st_max = 1e4;   //!< soft cap of St: growth switched off smoothly above
  bool porosity = true;  //!< evolve phi; off: phi = 1
  double s_hs = -0.58;   //!< hit-and-stick slope (spec §4.3)
  double b = 0.15;       //!< compression threshold factor (spec §4.2)
  double phi_max = 0.5;  //!< spec §4.3
  bool gas_compaction = true;
  bool self_gravity = true;
  ErosionModel erosion = ErosionModel::kNone;
  double v_eros = 4e3;    //!< [cm s^-1] (spec §5.1)
  double w_eros = 0.01;   //!< switch width (spec §5.2 has 0.05; see scene_keys.cpp)
  double f_s = 0.1;       //!< E2: small-projectile mass fraction
  double eps_eros = 1.0;  //!< E2: eroded mass per projectile mass
  double st_small = 0.0;  //!< projectile St; 0 = a monomer
  bool fragmentation = false;
  bool bouncing = false;
  double phi_bounce = 0.3;
  TurbulenceModel turbulence;  //!< V_g^2 normalisation and y_a of the turbulent dv (§3.5)
};

//! Longest floor-relaxation time t_relax / kRelaxFraction, in units of 1/Omega (spec §4.4
//! has 1).
//! The floor push softplus_100(ln floor - ln phi)/t_relax must stay small next to the
//! hit-and-stick decline |s_hs|/t_grow while phi is still above the floor; with the
//! spec's t_relax = 0.01 min(t_grow, 1/Omega) the push outruns growth by t_grow Omega
//! wherever growth is slow, and its tail lifts phi above the floor before phi reaches it
//! (at t_grow Omega = 1e4, phi cannot fall below 1.13 floor). Measured on fiducial
//! (issue 7): the planetesimal mass converges in the sharpness k as 12.05, 13.18, 13.44,
//! 13.51 M_earth for k = 30, 100, 300, 1000 with the 1/Omega cap, and as 13.42 (k = 100)
//! and 13.51 (k = 300) with this cap, at 19% fewer steps for k = 100. The cap keeps the
//! relaxation going where growth stalls (erosion, fragmentation) on <= 1/Omega.
inline constexpr double kRelaxCapOmega = 100.0;

//! Floor-relaxation time in units of min(t_grow, kRelaxCapOmega/Omega) (spec §4.4 has
//! 0.01). On the floor phi settles where the push softplus_100(z)/t_relax balances
//! compression, |s| t_relax/t_grow = softplus_100(z): with 0.01 that is z < 0 (the push's
//! tail holds phi ~1% above the floor); with 0.03 it is z ~ 0 for the compression slopes
//! -1/8 and -1/5 (spec §4.3), and the push is 3x less stiff. Measured against the sharp
//! limit (k = 1000, 0.003) on the default grids (issue 7): fiducial planetesimal mass
//! off by 1.1% with 0.01, 0.54% with 0.03 (0.45% with 0.1, but a floor rising with m^0.4
//! under self-gravity then lags ~6% behind); erosion_40 by 0.22% / 0.04%; 13.5% fewer
//! right-hand sides on fiducial, 3% on erosion_40.
inline constexpr double kRelaxFraction = 0.03;

//! Softplus with sharpness k: ln(1 + e^(k z))/k, = z for k z >> 1, -> 0 for k z << -1.
template <class T>
T softplus(const T& z, double k) {
  using std::exp;
  using std::log;
  const double kz = k * value_of(z);
  if (kz > 30.0) return z;
  // Far below the bend exp(k z) underflows, and libm's underflow path is slow (3% of the
  // fiducial run's time went to it): softplus < 1e-300 there, so it is 0.
  if (kz < -690.0) return T(0.0);
  return log(1.0 + exp(k * z)) / k;
}

//! Smooth positive part of x (scale-free: exact away from a band of width `delta`).
template <class T>
T positive_part(const T& x, double delta) {
  using std::sqrt;
  return 0.5 * (x + sqrt(x * x + delta * delta));
}

//! Everything the rates of one cell produce, also used for output.
template <class T>
struct ParticleRates {
  T a;          //!< particle radius [cm]
  T St;         //!< Stokes number
  T h_d;        //!< dust scale height [cm]
  T dv;         //!< collision speed with the partner at eps St [cm s^-1]
  T dv_ls;      //!< speed against small projectiles [cm s^-1] (erosion on)
  T dm_dt;      //!< [g s^-1]
  T dlnm_dt;    //!< [s^-1]
  T dlnphi_dt;  //!< [s^-1]
};

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

//! Stokes number of the small projectiles (spec §3, "velocity against small
//! projectiles"): fixed (erosion.St_small), or that of a compact monomer (the default).
//! (G: the gas's type, LocalGasT; AD where Sigma_g is differentiated.)
template <class G>
G small_projectile_st(const GrowthOptions& o, const Species& sp,
                      const LocalGasT<G>& gas) {
  if (o.st_small > 0.0) return G(o.st_small);
  return stokes_number(G(sp.m0), G(1.0), sp.rho0, gas, o.drag);
}

//! The rates of the mass-dominating particle (m [g], phi, Stokes number St from
//! stokes_number(), spec §2) in a cell with dust surface density sigma_d [g cm^-2].
//! `a_known`, if given, is radius(m, phi, sp.rho0), already computed by the caller.
template <class T, class G>
ParticleRates<T> particle_rates(const T& sigma_d, const T& m, const T& phi, const T& St,
                                const LocalGasT<G>& gas, const Species& sp,
                                const GrowthOptions& o, const T* a_known = nullptr) {
  using std::pow;
  using std::sqrt;
  using units::kPi;
  ParticleRates<T> r;
  r.a = a_known != nullptr ? *a_known : radius(m, phi, sp.rho0);  // spec §2
  r.St = St;
  r.h_d = dust_scale_height(r.St, gas);               // spec §2
  r.dv = dv_pair(r.St, m, gas, o.eps, o.turbulence);  // spec §3
  // spec §4.1 (Okuzumi et al. 2012 single-size form): sigma dv rho_d / sqrt(2) with the
  // vertical average over Gaussian layers of equal height.
  const T dm_coag = o.f_grow * 2.0 * sqrt(kPi) * r.a * r.a * r.dv * sigma_d / r.h_d;
  // Erosion, fragmentation, bouncing and the size cap multiply dm_coag by a factor that
  // does not depend on Sigma_d (both terms of E2 are proportional to it): dm = dm_coag
  // factor. Keeping the factor apart lets the filling factor test "dm/dt > 0" smoothly on
  // it (below) without dividing by a rate that vanishes with the dust.
  // spec §5.3: similar-size collisions turn growth into loss above v_frag, smoothly. The
  // factor multiplies the similar-size term only: under E2 the small-projectile term is
  // another kind of collision, and a product of the two signed terms would turn net
  // erosion plus fragmentation into growth.
  T frag = T(1.0);
  if (o.fragmentation) {
    const T dv2 = r.dv * r.dv;
    frag = 1.0 - 2.0 * dv2 / (dv2 + sp.v_frag * sp.v_frag);
  }
  T factor = frag;
  r.dv_ls = T(0.0);
  if (o.erosion != ErosionModel::kNone) {
    const G st_s = small_projectile_st(o, sp, gas);
    r.dv_ls = dv_small_projectile(r.St, m, st_s, sp.m0, gas, o.turbulence);  // spec §3
    // spec §5.2: S(x) = 1/2 [1 - tanh((x - 1)/w)], x = dv_ls / v_eros
    const T s = tanh_step<T>((1.0 - r.dv_ls / o.v_eros) / o.w_eros);
    if (o.erosion == ErosionModel::kHalt) {  // E1: growth halts where dv_ls = v_eros
      factor = s * frag;
    } else {  // E2: rate balance with an implicit reservoir of small projectiles
      // dm = (1 - f_s) dm_coag + f_s 2 sqrt(pi) a^2 dv_ls Sigma_d / h_bar [1 -
      // (1+e)(1-S)]
      const G h_s = dust_scale_height(st_s, gas);
      const T h_bar = sqrt(r.h_d * r.h_d + h_s * h_s) / sqrt(2.0);
      factor = (1.0 - o.f_s) * frag + o.f_s / o.f_grow * (r.dv_ls / r.dv) *
                                          (r.h_d / h_bar) *
                                          (1.0 - (1.0 + o.eps_eros) * (1.0 - s));
    }
  }
  if (o.bouncing)  // spec §5.3: compact aggregates bounce (p_stick -> 0 above phi_bounce)
    factor = factor * (1.0 - log_step(phi, o.phi_bounce, 0.05));
  // Soft cap of the size (growth.St_max, 1e4 by default; not in spec §4.1, a numerical
  // guard): far past St = 1 the particle is a planetesimal, which the planetesimal
  // channels (spec §7, from St >= 10) convert; without the cap a cell whose dust is not
  // yet converted would let m grow without bound (ln m in Q_m), with no effect on any
  // outcome. It leaves the rates below St = St_max/10 unchanged to < 1e-12.
  factor = factor * (1.0 - log_step(r.St, o.st_max, 0.1));
  const T dm = dm_coag * factor;
  r.dm_dt = dm;
  r.dlnm_dt = dm / m;

  r.dlnphi_dt = T(0.0);
  if (!o.porosity) return r;
  // spec §4.2: E_imp = (1/2)(m/2) dv^2 against the threshold 3 b E_roll
  const T e_imp = 0.25 * m * r.dv * r.dv;
  const T w_comp = log_step(e_imp, 3.0 * o.b * sp.e_roll, 0.1);
  // spec §4.3 compression slopes: Epstein St < 1: -1/8; Stokes St < 1: 0; St >= 1: -1/5
  // (the Stokes-drag slope only where the drag law has a Stokes regime)
  const T w_stokes = o.drag == DragLaw::kEpstein
                         ? T(0.0)
                         : T(log_step(knudsen_ratio(r.a, gas), 1.0, 0.1));
  const T w_heavy = log_step(r.St, 1.0, 0.1);
  const T s_comp = (1.0 - w_heavy) * ((1.0 - w_stokes) * (-0.125)) + w_heavy * (-0.2);
  const T slope = (1.0 - w_comp) * o.s_hs + w_comp * s_comp;
  // growth only (spec §4.3: applied while dm/dt > 0)
  // The positive part is taken of the factor dm/dm_coag, so its smooth band scales with
  // the rate (an absolute band would be a hard max at real rates, with a kink where
  // fragmentation or erosion turns growth into loss).
  const T growth = dm_coag / m * positive_part<T>(factor, 1e-3);
  r.dlnphi_dt = slope * growth;

  if (o.gas_compaction || o.self_gravity) {
    using std::log;
    // The floors are power laws of m, St and the gas: taken in logs (ln_soft_max,
    // ln_soft_min), they cost two logs instead of four pow() and two p-th roots.
    const T ln_nmono = log(m / sp.m0);
    T ln_floor = T(0.0);
    if (o.gas_compaction) {  // spec §4.3, Kataoka et al. 2013b: P_gas = P_c
      // phi_gas = (a0 m0 dv_pg Omega / (pi E_roll St))^(3/7) N^(1/7)
      const T dv_pg = gas_drift_speed(r.St, gas);
      ln_floor = (3.0 / 7.0) *
                     log(sp.a0 * sp.m0 * dv_pg * gas.omega_k / (kPi * sp.e_roll * r.St)) +
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
    // spec §4.4: relax up to the floor on t_relax = kRelaxFraction min(t_grow, t_cap),
    // with t_cap = kRelaxCapOmega/Omega where the spec has 1/Omega (see kRelaxCapOmega).
    const T rate_grow = growth + 1e-30;
    const T t_grow = 1.0 / rate_grow;
    const T t_relax = kRelaxFraction * soft_min(t_grow, T(kRelaxCapOmega / gas.omega_k));
    // softplus sharpness 100: below the floor by z the push is e^(-100 z)-small, so phi
    // follows max(phi_dyn, floor) to a few per cent (k = 1 or 10 leaks: phi would sit
    // a factor ~2 above the floor wherever t_relax << t_grow).
    r.dlnphi_dt += softplus<T>(ln_floor - log(phi), 100.0) / t_relax;
  }
  return r;
}

}  // namespace panoptic::physics
