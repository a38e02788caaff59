#pragma once
//! The pair speeds of a cell's bins (spec §3) from terms computed once per bin: the
//! distribution mode evaluates dv_ij for all N^2 pairs at every right-hand side, and
//! most of the work of physics/relative_velocity.hpp's dv_total is per partner (drift,
//! settling, OC07's St^2/(St + St_eta) and 1/(1 + St): PartnerSpeedTerms) or per pair
//! of fixed masses (Brownian motion). PairSpeedEvaluator keeps those and evaluates
//! dv_total's formula, dv2_pair_of, on them, so that its dv_ij equals
//! dv_total(St_i, St_j, m_i, m_j) bit for bit (tests/unit/physics/
//! test_coagulation_pair_speeds.cpp checks it pair by pair): the distribution mode's
//! results do not depend on which of the two computed them.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>
#include <vector>

#include "disk/local_gas.hpp"
#include "physics/relative_velocity.hpp"
#include "physics/smooth_switches.hpp"

namespace panoptic::physics::coagulation {

//! The terms of spec §3's pair speed that depend on one partner only, with OC07's
//! regime weights at St_hi = this partner's St.
struct BinSpeedTerms : PartnerSpeedTerms<double> {
  //! the regime weights of dv2_turbulent at St_hi = St: log_step(St; St_eta) and
  //! log_step(St; 1) (spec §3.5) [-]
  Oc07Weights<double> weights_at_st{};
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
    vg2_ = oc07_vg2(gas, model_);
    st_eta_ = oc07_st_eta(gas);
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
    BinSpeedTerms b{partner_speed_terms(st, gas_, st_eta_)};
    b.weights_at_st = weights_at_st_hi()(st, b, b);
    return b;
  }

  //! dv_total(p.st, q.st, m_i, m_j, gas, turbulence) [cm s^-1]: p the terms of the first
  //! partner (mass bin i), q those of the second (bin j).
  double dv(const BinSpeedTerms& p, const BinSpeedTerms& q, int i, int j) const {
    const double brownian = brownian_[static_cast<std::size_t>(i) * n_ + j];
    // The weights at St_hi: for partners more than 2.8x apart in St, soft_max's
    // correction hi (1 + r^32/32) rounds to hi, so St_hi is one partner's St exactly and
    // its weights are that partner's (most pairs; log_step costs a log and an exp in
    // its +-1.3 dex band around the switch)
    const auto weights = [this](double s_hi, const BinSpeedTerms& a,
                                const BinSpeedTerms& b) {
      if (s_hi == a.st) return a.weights_at_st;
      if (s_hi == b.st) return b.weights_at_st;
      return weights_at_st_hi()(s_hi, a, b);
    };
    return std::sqrt(dv2_pair_of(p, q, brownian, vg2_, model_.y_a, weights));  // §3.6
  }

 private:
  Oc07WeightsAtStHi<double> weights_at_st_hi() const {
    return {st_eta_, model_.blend_half_width_dex};
  }

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
