#pragma once
//! The conversion rates of one cell (spec §7), as a template on the scalar type T and
//! the gas type G: included by physics/modules/planetesimals.cpp (G = double) and by
//! physics/modules/evolving_gas_ad.cpp (G = AD, the Jacobian on evolving gas), which are
//! kept apart so that the static-gas code keeps its inlining
//! (physics/modules/evolving_gas_ad.hpp).
#include <cmath>
#include <type_traits>

#include "physics/modules/planetesimals.hpp"

namespace panoptic {

template <class T, class G>
void Planetesimals::cell_rates_with(int cell, const T* yc, const physics::LocalGasT<G>& g,
                                    T& coag, T& si) const {
  const T& sigma = yc[codec_.sigma_slot];
  const T st = stokes_.St(cell, yc);
  coag = T(0.0);
  si = T(0.0);
  if (opt_.coagulation) {
    // spec §7.1: St >= St_pl while the particle still grows
    T dlnm_dt;
    if (growth_module_) {
      if constexpr (std::is_same_v<T, double>) {
        dlnm_dt = growth_module_->cell_rates(cell, yc).dlnm_dt;
      } else {
        T unused;
        growth_module_->rates_ad(cell, yc, dlnm_dt, unused);
      }
    } else {
      dlnm_dt = physics::particle_rates(sigma, codec_.mass(cell, yc), codec_.phi(yc), st,
                                        g, species_[cell], growth_)
                    .dlnm_dt;
    }
    const double tau_pl = opt_.tau_pl_omega / g.omega_k;
    // dm/dt > 0, smoothly: on while the particle e-folds its mass within 1e9 / Omega (a
    // particle held by erosion or fragmentation grows far slower than that)
    const T growing = physics::tanh_step<T>(1e9 / g.omega_k * dlnm_dt);
    coag = sigma / tau_pl * physics::log_step(st, opt_.st_pl, opt_.width_dex) * growing;
  }
  if (opt_.si == StreamingInstability::kNone) return;
  // Sigma_d may dip below zero inside a Newton iteration where the dust is converted
  // away; the triggers take the log of Sigma_d, so they see a positive part.
  const T sigma_pos = physics::positive_part<T>(sigma, codec_.eps_sigma);
  if (opt_.si == StreamingInstability::kZcrit) {
    // spec §7.2 option: Z / Z_crit(St) >= 1 for St >= St_si_min (zcrit_lim25)
    const T z_ratio = sigma_pos / (g.sigma_g * zcrit_lim25(st));
    si = opt_.zeta * sigma * g.omega_k * physics::log_step(z_ratio, 1.0, opt_.width_dex) *
         physics::log_step(st, opt_.st_si_min, opt_.width_dex);
    return;
  }
  // spec §7.2: midplane rho_d/rho_g >= 1 (spec §2: rho_d = Sigma_d/(sqrt(2 pi) h_d))
  const T h_d = physics::dust_scale_height(st, g);
  const T eps_mid = physics::midplane_dust_to_gas(sigma_pos, h_d, g);
  const T trigger = physics::log_step(eps_mid, opt_.eps_crit, opt_.width_dex);
  if (opt_.si == StreamingInstability::kD16)  // Drazkowska et al. 2016
    si = opt_.zeta * sigma * g.omega_k * trigger *
         physics::log_step(st, opt_.st_si_min, opt_.width_dex);
  else  // Schoonenberg, Ormel & Krijt 2018
    si = opt_.zeta * sigma * st * g.omega_k * trigger;
}

}  // namespace panoptic
