#pragma once
//! Relative velocities of two dust particles at the midplane (spec §3): Brownian motion,
//! radial and azimuthal drift, vertical settling and turbulence, combined in quadrature;
//! for the single-size pair (St, eps St) and for a target against small projectiles
//! (erosion). Sources: Brownian speed of the reduced mass (kinetic theory, as in
//! Okuzumi et al. 2012 and Birnstiel et al. 2010); drift velocities of Nakagawa, Sekiya &
//! Hayashi (1986) / Weidenschilling (1977); settling speed as in Okuzumi et al. (2012);
//! turbulence: closed forms of Ormel & Cuzzi (2007, OC07) eqs. 27-29 with V_g^2 = alpha
//! c_s^2, St_eta = Re^-1/2, y_a = 1.6.
//!
//! Every function is a template on the scalar type T (double or Eigen::AutoDiffScalar);
//! see physics/particle.hpp for the rules. The components are returned *squared* (dv2_*):
//! a squared difference is smooth where the difference changes sign, while |v1 - v2| is
//! not. The dv_* speeds are for reports only.
#include <cmath>

#include "disk/local_gas.hpp"
#include "physics/particle.hpp"
#include "physics/smooth_switches.hpp"
#include "src/core/units.hpp"

namespace panoptic::physics {

//! Size ratio eps = St2/St1 of the single-size pair (spec §3) [-].
inline constexpr double kPairSizeRatio = 0.5;
//! OC07 y_a = t_12*/t_1 [-].
inline constexpr double kOc07Ya = 1.6;
//! p of the soft (St_hi, St_lo) ordering in dv2_turbulent [-].
inline constexpr double kOrderPower = 32.0;

//! Parameters of the turbulent term (spec §3.5, §10.1).
struct TurbulenceModel {
  double vg2_factor = 1.0;  //!< V_g^2 = vg2_factor alpha c_s^2 (OC07: 1; alt. 1.5)
  double y_a = kOc07Ya;     //!< OC07 y_a [-]
  double blend_half_width_dex = 0.1;  //!< 5%-95% half width of the regime blends [dex]
};

//! OC07 intermediate-regime coefficient (spec §3.5; Ormel & Cuzzi 2007, eq. 28):
//!   beta(eps) = 2 y_a - (1 + eps) + (2 / (1 + eps)) [1/(1 + y_a) + eps^3/(y_a + eps)],
//! eps = St2/St1 <= 1. beta(1) = 1.969, beta(0.5) = 2.292, beta(0) = 2.969 [-].
template <class T>
T beta_oc07(const T& eps, double y_a = kOc07Ya) {
  const T e3 = eps * eps * eps;
  const T bracket = 1.0 / (1.0 + y_a) + e3 / (y_a + eps);
  return 2.0 * y_a - (1.0 + eps) + 2.0 / (1.0 + eps) * bracket;
}

// ---------------------------------------------------------------------------------------------
// Single-particle velocities relative to the local Keplerian frame
// ---------------------------------------------------------------------------------------------

//! Radial drift v_r = (-2 St eta v_K + v_r,gas) / (1 + St^2) (spec §3.2, §6.1; Nakagawa,
//! Sekiya & Hayashi 1986; Takeuchi & Lin 2002) [cm s^-1].
template <class T, class G>
T v_radial_drift(const T& St, const LocalGasT<G>& gas) {
  const T denom = 1.0 + St * St;
  return (-2.0 * gas.headwind() * St + gas.v_r_gas) / denom;
}

//! Azimuthal velocity relative to Keplerian, v_phi - v_K = -eta v_K / (1 + St^2)
//! (spec §3.3; Nakagawa, Sekiya & Hayashi 1986) [cm s^-1].
template <class T, class G>
T v_azimuthal_offset(const T& St, const LocalGasT<G>& gas) {
  const T denom = 1.0 + St * St;
  return -gas.headwind() / denom;
}

//! Settling speed at z = h_d, v_z = h_d Omega St / (1 + St) (spec §3.4; Okuzumi et al.
//! 2012, the St/(1+St) form caps it at the free-fall-like h_d Omega for St >> 1) [cm
//! s^-1].
template <class T, class G>
T v_settling(const T& St, const LocalGasT<G>& gas) {
  const T h_d = dust_scale_height(St, gas);
  return h_d * gas.omega_k * St / (1.0 + St);
}

// ---------------------------------------------------------------------------------------------
// Squared relative-velocity components of a pair [cm^2 s^-2]
// ---------------------------------------------------------------------------------------------

//! Brownian motion, dv_B^2 = 8 k_B T (m1 + m2) / (pi m1 m2) (spec §3.1) [cm^2 s^-2];
//! m1, m2 [g].
template <class T, class G>
T dv2_brownian(const T& m1, const T& m2, const LocalGasT<G>& gas) {
  const double kt = units::kBoltzmann * gas.temperature;
  return 8.0 * kt * (m1 + m2) / (units::kPi * m1 * m2);
}

//! Radial drift, (v_r,1 - v_r,2)^2 (spec §3.2) [cm^2 s^-2].
template <class T, class G>
T dv2_radial(const T& St1, const T& St2, const LocalGasT<G>& gas) {
  const T d = v_radial_drift(St1, gas) - v_radial_drift(St2, gas);
  return d * d;
}

//! Azimuthal drift, (eta v_K [1/(1 + St1^2) - 1/(1 + St2^2)])^2 (spec §3.3) [cm^2 s^-2].
template <class T, class G>
T dv2_azimuthal(const T& St1, const T& St2, const LocalGasT<G>& gas) {
  const T d = v_azimuthal_offset(St1, gas) - v_azimuthal_offset(St2, gas);
  return d * d;
}

//! Vertical settling, (v_z,1 - v_z,2)^2, each at its own z = h_d (spec §3.4) [cm^2 s^-2].
template <class T, class G>
T dv2_vertical(const T& St1, const T& St2, const LocalGasT<G>& gas) {
  const T d = v_settling(St1, gas) - v_settling(St2, gas);
  return d * d;
}

//! The terms of a pair's speed (spec §3.2-§3.5) that depend on one partner only. A
//! pair's speed is dv2_pair_of() of its partners' terms: dv_total builds the two, the
//! size distribution builds them once per mass bin for its N^2 pairs
//! (physics/coagulation/pair_speed_evaluator.hpp), so both evaluate one formula.
template <class T>
struct PartnerSpeedTerms {
  using Scalar = T;
  T st;     //!< Stokes number [-]
  T v_r;    //!< radial drift velocity (spec §3.2) [cm s^-1]
  T v_phi;  //!< azimuthal offset from Keplerian (spec §3.3) [cm s^-1]
  T v_z;    //!< settling speed at z = h_d (spec §3.4) [cm s^-1]
  T g;      //!< St^2 / (St + St_eta) of OC07 eq. 27 (spec §3.5) [-]
  T heavy;  //!< 1 / (1 + St) of OC07 eq. 29 (spec §3.5) [-]
};

//! OC07's St_eta = t_eta/t_L = Re^-1/2 (spec §3.5) [-].
template <class G>
G oc07_st_eta(const LocalGasT<G>& gas) {
  using std::sqrt;
  return 1.0 / sqrt(gas.reynolds());
}

//! OC07's normalisation V_g^2 = f alpha c_s^2 (spec §3.5, §10.1) [cm^2 s^-2].
template <class G>
double oc07_vg2(const LocalGasT<G>& gas, const TurbulenceModel& model) {
  return model.vg2_factor * gas.alpha * gas.c_s * gas.c_s;
}

//! The terms of the partner of Stokes number St in the gas `gas` whose OC07 St_eta is
//! st_eta (oc07_st_eta).
template <class T, class G>
PartnerSpeedTerms<T> partner_speed_terms(const T& St, const LocalGasT<G>& gas,
                                         const G& st_eta) {
  const T v_r = v_radial_drift(St, gas);
  const T v_phi = v_azimuthal_offset(St, gas);
  const T v_z = v_settling(St, gas);
  const T g = St * St / (St + st_eta);
  const T heavy = 1.0 / (1.0 + St);
  return {St, v_r, v_phi, v_z, g, heavy};
}

//! OC07's regime weights at St_hi (spec §3.5) [-].
template <class T>
struct Oc07Weights {
  T w_eta;  //!< log_step(St_hi; St_eta, w)
  T w_one;  //!< log_step(St_hi; 1, w)
};

//! The regime weights computed at St_hi; the weights of dv2_turbulent_of.
template <class G>
struct Oc07WeightsAtStHi {
  G st_eta;               //!< OC07's St_eta (oc07_st_eta) [-]
  double half_width_dex;  //!< TurbulenceModel::blend_half_width_dex [dex]
  template <class T, class P>
  Oc07Weights<T> operator()(const T& s_hi, const P& /*p*/, const P& /*q*/) const {
    const T w_eta = log_step(s_hi, st_eta, half_width_dex);
    const T w_one = log_step(s_hi, 1.0, half_width_dex);
    return {w_eta, w_one};
  }
};

//! Turbulence, Ormel & Cuzzi (2007) closed forms (spec §3.5) [cm^2 s^-2].
//! With St1 >= St2, eps = St2/St1, St_eta = Re^-1/2, V_g^2 = f alpha c_s^2:
//!   tight,  OC07 eq. 27:
//!     A_t = (St1-St2)/(St1+St2) [St1^2/(St1+St_eta) - St2^2/(St2+St_eta)]
//!   intermediate, OC07 eq. 28:  A_i = beta(eps) St1
//!   heavy,  OC07 eq. 29:        A_h = 1/(1 + St1) + 1/(1 + St2)
//! blended smoothly in ln St1 (spec §3.5: logistic over +-0.1 dex at each boundary):
//!   dv_t^2 = V_g^2 [(1 - s_eta) A_t + s_eta ((1 - s_1) A_i + s_1 A_h)],
//!   s_eta = log_step(St1; St_eta, w),  s_1 = log_step(St1; 1, w),  w = 0.1 dex,
//! so the weights sum to 1 exactly. The regimes do not match at their boundaries
//! (at St1 = St_eta, A_i/A_t ~ 20 for eps = 0.5; at St1 = 1, A_i/A_h = 2.0), so the
//! blend is steep but C-infinity; at a boundary it gives the mean of the two dv_t^2.
//!
//! Ordering: A_t and A_h are symmetric in (St1, St2) and take the arguments as given.
//! A_i and the weights need the larger St. A hard swap would put a kink into dv_ls
//! where a target crosses its projectile's St (dv_ls enters the growth rate of erosion
//! option E2, spec §5.2), so the order is smooth:
//!   St_hi = soft_max(St1, St2, 32),  eps = soft_min(St1, St2, 32) / St_hi.
//! For St2/St1 <= 0.8 this equals the hard order to < 1e-4 (1e-11 for the eps = 0.5
//! pair); for equal sizes it raises St_hi by 2^(1/32) = 1.022 and gives eps = 0.958.
//! Evaluated from the partners' terms p, q (PartnerSpeedTerms, or a type derived from
//! it); vg2 = oc07_vg2; weights(St_hi, p, q) returns the Oc07Weights at St_hi
//! (Oc07WeightsAtStHi, or the same values found another way).
template <class P, class Weights>
typename P::Scalar dv2_turbulent_of(const P& p, const P& q, double vg2, double y_a,
                                    const Weights& weights) {
  using T = typename P::Scalar;
  const T tight = (p.st - q.st) / (p.st + q.st) * (p.g - q.g);
  const T s_hi = soft_max(p.st, q.st, kOrderPower);
  const T s_lo = p.st * q.st / s_hi;  // soft_min(St1, St2) with its soft_max
  const T eps = s_lo / s_hi;
  const T inter = beta_oc07(eps, y_a) * s_hi;
  const T heavy = p.heavy + q.heavy;
  const Oc07Weights<T> w = weights(s_hi, p, q);
  const T upper = (1.0 - w.w_one) * inter + w.w_one * heavy;
  return vg2 * ((1.0 - w.w_eta) * tight + w.w_eta * upper);
}

//! Total dv^2 of a pair (spec §3.6) from its partners' terms p, q and its Brownian term
//! dv2_brownian (spec §3.1): the sum of the five squared components [cm^2 s^-2];
//! vg2, y_a and weights as in dv2_turbulent_of.
template <class P, class Weights>
typename P::Scalar dv2_pair_of(const P& p, const P& q, const typename P::Scalar& brownian,
                               double vg2, double y_a, const Weights& weights) {
  using T = typename P::Scalar;
  const T d_r = p.v_r - q.v_r;
  const T d_phi = p.v_phi - q.v_phi;
  const T d_z = p.v_z - q.v_z;
  const T radial = d_r * d_r;
  const T azimuthal = d_phi * d_phi;
  const T vertical = d_z * d_z;
  const T turbulent = dv2_turbulent_of(p, q, vg2, y_a, weights);
  return brownian + radial + azimuthal + vertical + turbulent;
}

//! Turbulence of the pair (St1, St2), dv2_turbulent_of above [cm^2 s^-2].
template <class T, class G>
T dv2_turbulent(const T& St1, const T& St2, const LocalGasT<G>& gas,
                const TurbulenceModel& model = {}) {
  const G st_eta = oc07_st_eta(gas);
  const PartnerSpeedTerms<T> p = partner_speed_terms(St1, gas, st_eta);
  const PartnerSpeedTerms<T> q = partner_speed_terms(St2, gas, st_eta);
  return dv2_turbulent_of(p, q, oc07_vg2(gas, model), model.y_a,
                          Oc07WeightsAtStHi<G>{st_eta, model.blend_half_width_dex});
}

//! The five squared components of a pair [cm^2 s^-2] and their quadrature sum.
template <class T>
struct RelativeVelocity2 {
  T brownian;
  T radial;
  T azimuthal;
  T vertical;
  T turbulent;
  //! Total dv^2 = sum of the components (spec §3.6) [cm^2 s^-2].
  T total() const { return brownian + radial + azimuthal + vertical + turbulent; }
};

//! All components for particles (St1, m1) and (St2, m2) [cm^2 s^-2].
template <class T, class G>
RelativeVelocity2<T> relative_velocity2(const T& St1, const T& St2, const T& m1,
                                        const T& m2, const LocalGasT<G>& gas,
                                        const TurbulenceModel& model = {}) {
  return {dv2_brownian(m1, m2, gas), dv2_radial(St1, St2, gas),
          dv2_azimuthal(St1, St2, gas), dv2_vertical(St1, St2, gas),
          dv2_turbulent(St1, St2, gas, model)};
}

//! Total relative speed dv = sqrt(dv_B^2 + dv_r^2 + dv_phi^2 + dv_z^2 + dv_t^2) (spec
//! §3.6) [cm s^-1]. Smooth: the Brownian term keeps the radicand positive.
template <class T, class G>
T dv_total(const T& St1, const T& St2, const T& m1, const T& m2, const LocalGasT<G>& gas,
           const TurbulenceModel& model = {}) {
  using std::sqrt;
  const G st_eta = oc07_st_eta(gas);
  const PartnerSpeedTerms<T> p = partner_speed_terms(St1, gas, st_eta);
  const PartnerSpeedTerms<T> q = partner_speed_terms(St2, gas, st_eta);
  const T brownian = dv2_brownian(m1, m2, gas);
  const T dv2 = dv2_pair_of(p, q, brownian, oc07_vg2(gas, model), model.y_a,
                            Oc07WeightsAtStHi<G>{st_eta, model.blend_half_width_dex});
  return sqrt(dv2);
}

//! Single-size collision speed dv(St, eps St) of the mass-dominating particle (St, m)
//! with its partner of the same filling factor (spec §3 pair convention; Sato, Okuzumi &
//! Ida 2016): St2 = eps St and, with Epstein scaling St ~ a, m2 = eps^3 m (used only by
//! the Brownian term, which matters only for Epstein-sized grains) [cm s^-1].
template <class T, class G>
T dv_pair(const T& St, const T& m, const LocalGasT<G>& gas, double eps = kPairSizeRatio,
          const TurbulenceModel& model = {}) {
  const T st2 = eps * St;
  const T m2 = (eps * eps * eps) * m;
  return dv_total(St, st2, m, m2, gas, model);
}

//! Speed dv_ls of the target (St, m) against small projectiles of Stokes number st_s and
//! mass m_s (spec §3, erosion; default projectile a monomer, or St_s = 1e-4) [cm s^-1].
template <class T, class S, class G>
T dv_small_projectile(const T& St, const T& m, const S& st_s, double m_s,
                      const LocalGasT<G>& gas, const TurbulenceModel& model = {}) {
  return dv_total(St, T(st_s), m, T(m_s), gas, model);
}

// ---------------------------------------------------------------------------------------------
// Component speeds, for reports and diagnostics (not smooth where the difference
// vanishes)
// ---------------------------------------------------------------------------------------------

//! Brownian speed [cm s^-1].
template <class T, class G>
T dv_brownian(const T& m1, const T& m2, const LocalGasT<G>& gas) {
  using std::sqrt;
  return sqrt(dv2_brownian(m1, m2, gas));
}
//! |v_r,1 - v_r,2| [cm s^-1].
template <class T, class G>
T dv_radial(const T& St1, const T& St2, const LocalGasT<G>& gas) {
  using std::abs;
  return abs(v_radial_drift(St1, gas) - v_radial_drift(St2, gas));
}
//! |v_phi,1 - v_phi,2| [cm s^-1].
template <class T, class G>
T dv_azimuthal(const T& St1, const T& St2, const LocalGasT<G>& gas) {
  using std::abs;
  return abs(v_azimuthal_offset(St1, gas) - v_azimuthal_offset(St2, gas));
}
//! |v_z,1 - v_z,2| [cm s^-1].
template <class T, class G>
T dv_vertical(const T& St1, const T& St2, const LocalGasT<G>& gas) {
  using std::abs;
  return abs(v_settling(St1, gas) - v_settling(St2, gas));
}
//! Turbulent speed [cm s^-1].
template <class T, class G>
T dv_turbulent(const T& St1, const T& St2, const LocalGasT<G>& gas,
               const TurbulenceModel& model = {}) {
  using std::sqrt;
  return sqrt(dv2_turbulent(St1, St2, gas, model));
}

}  // namespace panoptic::physics
