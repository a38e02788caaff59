#pragma once
//! Local growth and filling-factor rates of the mass-dominating particle of one cell: the
//! semi-analytical porous coagulation model (spec §4, §5; Krijt et al. 2016 built on
//! Okuzumi et al. 2012, Kataoka et al. 2013, Krijt et al. 2015). Pure functions,
//! templated on the scalar type so that the cell Jacobian is exact
//! (src/core/autodiff.hpp). This file combines the processes, each in its own file:
//!
//!   dm/dt = f_grow 2 sqrt(pi) a^2 dv Sigma_d / h_d  (spec §4.1; dv:
//!   relative_velocity.hpp)
//!           x [erosion (erosion.hpp), fragmentation, bouncing (fragmentation.hpp)]
//!   d ln phi/dt = s (d ln m/dt)_+  +  softplus_100(ln phi_floor - ln phi) / t_relax
//!           (s, phi_floor = max(phi_gas, phi_grav), t_relax: compaction.hpp, §4.2-§4.4)
#include <cmath>

#include "disk/local_gas.hpp"
#include "physics/compaction.hpp"
#include "physics/drag.hpp"
#include "physics/erosion.hpp"
#include "physics/fragmentation.hpp"
#include "physics/growth_options.hpp"
#include "physics/particle.hpp"
#include "physics/relative_velocity.hpp"
#include "src/core/autodiff.hpp"
#include "src/core/units.hpp"

namespace panoptic::physics {

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
  const T frag =
      o.fragmentation && sp.fragments ? fragmentation_factor(r.dv, sp.v_frag) : T(1.0);
  T factor = frag;
  r.dv_ls = T(0.0);
  if (o.eroding())  // spec §5.1-§5.2
    factor = erosion_factor(r.St, m, r.dv, r.h_d, frag, gas, sp, o, r.dv_ls);
  if (o.bouncing)  // spec §5.3: compact aggregates bounce (p_stick -> 0 above phi_bounce)
    factor = factor * bouncing_factor(phi, o.phi_bounce);
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
  const T slope = compression_slope(m, r.dv, r.a, r.St, gas, sp, o);  // spec §4.2-§4.3
  // growth only (spec §4.3: applied while dm/dt > 0)
  // The positive part is taken of the factor dm/dm_coag, so its smooth band scales with
  // the rate (an absolute band would be a hard max at real rates, with a kink where
  // fragmentation or erosion turns growth into loss).
  const T growth = dm_coag / m * positive_part<T>(factor, 1e-3);
  r.dlnphi_dt = slope * growth;

  if (o.gas_compaction || o.self_gravity) {  // spec §4.3-§4.4
    const T ln_floor = ln_compaction_floor(m, r.St, gas, sp, o);
    r.dlnphi_dt += floor_relaxation_rate(ln_floor, phi, growth, gas);
  }
  return r;
}

}  // namespace panoptic::physics
