#pragma once
//! Fragmentation and bouncing of similar-size collisions (spec §5.3): the factors they
//! apply to the coagulation growth rate of the mass-dominating particle. Templates on
//! the scalar type T (rules: physics/particle.hpp).
#include "physics/smooth_switches.hpp"

namespace panoptic::physics {

//! Similar-size collisions at dv [cm s^-1] turn growth into loss above v_frag [cm s^-1],
//! smoothly: 1 - 2 dv^2/(dv^2 + v_frag^2), -> -1 (loss at the growth rate) for
//! dv >> v_frag (spec §5.3) [-].
template <class T>
T fragmentation_factor(const T& dv, double v_frag) {
  const T dv2 = dv * dv;
  const T frag = 1.0 - 2.0 * dv2 / (dv2 + v_frag * v_frag);
  return frag;
}

//! Compact aggregates bounce: the sticking probability goes to 0 above phi_bounce,
//! logistic in ln phi over 0.05 dex (spec §5.3) [-].
template <class T>
T bouncing_factor(const T& phi, double phi_bounce) {
  const T p_stick = 1.0 - log_step(phi, phi_bounce, 0.05);
  return p_stick;
}

}  // namespace panoptic::physics
