#pragma once
//! Erosion by small projectiles (spec §5.1-§5.2; Krijt et al. 2015): the factor it
//! applies to the coagulation growth rate of the mass-dominating particle, for the
//! models halt (E1: growth stops where the speed against small projectiles reaches
//! v_eros) and balance (E2: a rate balance with an implicit reservoir of small
//! projectiles). Templates on T and the gas's G (rules: physics/particle.hpp).
#include <cmath>

#include "disk/local_gas.hpp"
#include "physics/drag.hpp"
#include "physics/growth_options.hpp"
#include "physics/particle.hpp"
#include "physics/relative_velocity.hpp"
#include "physics/smooth_switches.hpp"

namespace panoptic::physics {

//! Stokes number of the small projectiles (spec §3, "velocity against small
//! projectiles"): fixed (erosion.St_small), or that of a compact monomer (the default).
//! (G: the gas's type, LocalGasT; AD where Sigma_g is differentiated.)
template <class G>
G small_projectile_st(const GrowthOptions& o, const Species& sp,
                      const LocalGasT<G>& gas) {
  if (o.st_small > 0.0) return G(o.st_small);
  return stokes_number(G(sp.m0), G(1.0), sp.rho0, gas, o.drag);
}

//! Factor of the coagulation growth rate under erosion (o.erosion halt or balance; call
//! only with one of them): the particle (Stokes number St, mass m [g], dust scale height
//! h_d [cm]) collides with its partner at dv [cm s^-1]; `frag` is the fragmentation
//! factor of those similar-size collisions (1 without fragmentation). Sets dv_ls, the
//! speed against small projectiles [cm s^-1] [-].
template <class T, class G>
T erosion_factor(const T& St, const T& m, const T& dv, const T& h_d, const T& frag,
                 const LocalGasT<G>& gas, const Species& sp, const GrowthOptions& o,
                 T& dv_ls) {
  using std::sqrt;
  const G st_s = small_projectile_st(o, sp, gas);
  dv_ls = dv_small_projectile(St, m, st_s, sp.m0, gas, o.turbulence);  // spec §3
  // spec §5.2: S(x) = 1/2 [1 - tanh((x - 1)/w)], x = dv_ls / v_eros
  const T s = tanh_step<T>((1.0 - dv_ls / o.v_eros) / o.w_eros);
  if (o.erosion == ErosionModel::kHalt) {  // E1: growth halts where dv_ls = v_eros
    if (!o.fragmentation || !sp.fragments) return s * frag;  // frag = 1
    // Erosion halts growth, not the fragmentation of similar-size collisions (spec §5.2
    // with §5.3 composed literally, S frag, would also stop the loss above v_frag: the
    // particle would freeze instead of fragmenting): S acts on the smooth positive part
    // of frag only (band 1e-3, as the filling factor's growth test; a halted particle
    // near frag = 0 loses up to 5e-4 of its coagulation rate through the band).
    const T gain = positive_part<T>(frag, 1e-3);
    return s * gain + (frag - gain);
  }
  // E2: rate balance with an implicit reservoir of small projectiles
  // dm = (1 - f_s) dm_coag + f_s 2 sqrt(pi) a^2 dv_ls Sigma_d / h_bar [1 - (1+e)(1-S)]
  const G h_s = dust_scale_height(st_s, gas);
  const T h_bar = sqrt(h_d * h_d + h_s * h_s) / sqrt(2.0);
  const T factor = (1.0 - o.f_s) * frag + o.f_s / o.f_grow * (dv_ls / dv) *
                                              (h_d / h_bar) *
                                              (1.0 - (1.0 + o.eps_eros) * (1.0 - s));
  return factor;
}

}  // namespace panoptic::physics
