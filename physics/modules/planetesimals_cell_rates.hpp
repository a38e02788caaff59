#pragma once
//! The conversion rates of one cell (spec §7), as a template on the scalar type T and
//! the gas type G: included by physics/modules/planetesimals.cpp (G = double) and by
//! physics/modules/evolving_gas_ad.cpp (G = AD, the Jacobian on evolving gas), which are
//! kept apart so that the static-gas code keeps its inlining
//! (physics/modules/evolving_gas_ad.hpp).
#include <cmath>
#include <type_traits>

#include "physics/modules/planetesimals.hpp"
#include "physics/planetesimal_criteria.hpp"

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
    coag = physics::coagulation_conversion(sigma, st, dlnm_dt, g.omega_k,
                                           opt_.tau_pl_omega, opt_.st_pl, opt_.width_dex);
  }
  if (opt_.si == StreamingInstability::kNone) return;
  // Sigma_d may dip below zero inside a Newton iteration where the dust is converted
  // away; the triggers take the log of Sigma_d, so they see a positive part.
  const T sigma_pos = physics::positive_part<T>(sigma, codec_.eps_sigma);
  if (opt_.si == StreamingInstability::kZcrit) {
    si = physics::si_conversion_zcrit(sigma, sigma_pos, st, g, opt_.zeta, opt_.st_si_min,
                                      opt_.width_dex);
    return;
  }
  const T trigger =
      physics::si_midplane_trigger(sigma_pos, st, g, opt_.eps_crit, opt_.width_dex);
  if (opt_.si == StreamingInstability::kD16)
    si = physics::si_conversion_d16(sigma, st, trigger, g.omega_k, opt_.zeta,
                                    opt_.st_si_min, opt_.width_dex);
  else
    si = physics::si_conversion_s18(sigma, st, trigger, g.omega_k, opt_.zeta);
}

}  // namespace panoptic
