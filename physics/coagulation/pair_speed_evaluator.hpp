#pragma once
//! The pair speeds of a cell's bins (spec §3) from terms computed once per bin: the
//! distribution mode evaluates dv_ij for all N^2 pairs at every right-hand side, and
//! most of the work of physics/relative_velocity.hpp's dv_total is per partner (drift,
//! settling, OC07's St^2/(St + St_eta) and 1/(1 + St)) or per pair of fixed masses
//! (Brownian motion). PairSpeedEvaluator keeps those and evaluates dv_total's formula
//! with the same operations in the same order, so that its dv_ij equals
//! dv_total(St_i, St_j, m_i, m_j) bit for bit (tests/unit/physics/
//! test_coagulation_pair_speeds.cpp checks it pair by pair): the distribution mode's
//! results do not depend on which of the two computed them.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>
#include <vector>

#include "disk/local_gas.hpp"
#include "physics/particle.hpp"
#include "physics/relative_velocity.hpp"
#include "physics/smooth_switches.hpp"

namespace panoptic::physics::coagulation {

//! The terms of spec §3's pair speed that depend on one partner only.
struct BinSpeedTerms {
  double st = 0.0;     //!< Stokes number [-]
  double v_r = 0.0;    //!< radial drift velocity (spec §3.2) [cm s^-1]
  double v_phi = 0.0;  //!< azimuthal offset from Keplerian (spec §3.3) [cm s^-1]
  double v_z = 0.0;    //!< settling speed at z = h_d (spec §3.4) [cm s^-1]
  double g = 0.0;      //!< St^2 / (St + St_eta) of OC07 eq. 27 (spec §3.5) [-]
  double heavy = 0.0;  //!< 1 / (1 + St) of OC07 eq. 29 (spec §3.5) [-]
  //! the regime weights of dv2_turbulent at St_hi = St: log_step(St; St_eta) and
  //! log_step(St; 1) (spec §3.5) [-]
  double w_eta = 0.0, w_one = 0.0;
};

//! dv_total of the pairs of a cell's mass bins from per-bin terms (see the file's note).
class PairSpeedEvaluator {
 public:
  //! Takes the cell's gas and turbulence model; the Brownian term of every pair of the
  //! masses m (N bins) is rebuilt when the gas temperature or the masses change.
  void set_gas(const LocalGas& gas, std::span<const double> m,
               const TurbulenceModel& turbulence) {
    gas_ = gas;
    model_ = turbulence;
    // dv2_turbulent's OC07 normalisation and St_eta, with its operations
    vg2_ = model_.vg2_factor * gas.alpha * gas.c_s * gas.c_s;
    st_eta_ = 1.0 / std::sqrt(gas.reynolds());
    const int n = static_cast<int>(m.size());
    if (gas.temperature == temperature_ && std::ranges::equal(m, m_)) return;
    n_ = n;
    temperature_ = gas.temperature;
    m_.assign(m.begin(), m.end());
    brownian_.resize(static_cast<std::size_t>(n) * n);
    // both orders: dv2_brownian(m1, m2) and (m2, m1) may differ in the last bit
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        brownian_[static_cast<std::size_t>(i) * n + j] = dv2_brownian(m[i], m[j], gas);
  }

  //! The per-bin terms at Stokes number st (the gas of set_gas).
  BinSpeedTerms bin_terms(double st) const {
    BinSpeedTerms b;
    b.st = st;
    b.v_r = v_radial_drift(st, gas_);
    b.v_phi = v_azimuthal_offset(st, gas_);
    b.v_z = v_settling(st, gas_);
    b.g = st * st / (st + st_eta_);
    b.heavy = 1.0 / (1.0 + st);
    b.w_eta = log_step(st, st_eta_, model_.blend_half_width_dex);
    b.w_one = log_step(st, 1.0, model_.blend_half_width_dex);
    return b;
  }

  //! dv_total(p.st, q.st, m_i, m_j, gas, turbulence) [cm s^-1]: p the terms of the first
  //! partner (mass bin i), q those of the second (bin j).
  double dv(const BinSpeedTerms& p, const BinSpeedTerms& q, int i, int j) const {
    const double brownian = brownian_[static_cast<std::size_t>(i) * n_ + j];
    const double d_r = p.v_r - q.v_r, d_phi = p.v_phi - q.v_phi, d_z = p.v_z - q.v_z;
    const double radial = d_r * d_r, azimuthal = d_phi * d_phi, vertical = d_z * d_z;
    // dv2_turbulent (spec §3.5): soft_min = St1 St2 / soft_max, so one soft_max serves
    const double tight = (p.st - q.st) / (p.st + q.st) * (p.g - q.g);
    const double s_hi = soft_max(p.st, q.st, kOrderPower);
    const double s_lo = p.st * q.st / s_hi;
    const double eps = s_lo / s_hi;
    const double inter = beta_oc07(eps, model_.y_a) * s_hi;
    const double heavy = p.heavy + q.heavy;
    // The weights at St_hi: for partners more than 2.8x apart in St, soft_max's
    // correction hi (1 + r^32/32) rounds to hi, so St_hi is one partner's St exactly and
    // its weights are that partner's (most pairs; log_step costs a log and an exp in
    // its +-1.3 dex band around the switch)
    const BinSpeedTerms* top = s_hi == p.st ? &p : s_hi == q.st ? &q : nullptr;
    const double w_eta = top != nullptr
                             ? top->w_eta
                             : log_step(s_hi, st_eta_, model_.blend_half_width_dex);
    const double w_one =
        top != nullptr ? top->w_one : log_step(s_hi, 1.0, model_.blend_half_width_dex);
    const double upper = (1.0 - w_one) * inter + w_one * heavy;
    const double turbulent = vg2_ * ((1.0 - w_eta) * tight + w_eta * upper);
    return std::sqrt(brownian + radial + azimuthal + vertical + turbulent);  // spec §3.6
  }

 private:
  LocalGas gas_;
  TurbulenceModel model_;
  double vg2_ = 0.0, st_eta_ = 0.0;
  // what the Brownian table was built for
  int n_ = 0;
  double temperature_ = -1.0;
  std::vector<double> m_;
  std::vector<double> brownian_;  //!< dv2_brownian(m_i, m_j) at [i * N + j]
};

}  // namespace panoptic::physics::coagulation
