#pragma once
//! The filling factor of each mass bin of a cell in the size distribution's track mode
//! (porosity.bins = "track"): the single-size model's porosity law (spec §4.2-§4.4)
//! followed along the mass axis at the cell's gas, instead of a volume moment per bin
//! (spec §15.1, "evolved").
//!
//! The premise is that of the single-size porosity models (Okuzumi et al. 2012, Krijt et
//! al. 2016): the aggregates that carry the mass grow by collisions with partners of
//! similar size, so that their filling factor is a function of their mass, set by the
//! law d ln phi / d ln m = s of spec §4.3 (hit-and-stick s_hs below the compression
//! threshold E_imp = 3 b E_roll, the compression slope of the drag regime above it) with
//! the single size's collision speed dv(St, eps St) (spec §3) and raised to the
//! compaction floors (spec §4.3; the single size relaxes up to them on a time much
//! shorter than its growth, spec §4.4). Taking the track at the cell's own gas is ours
//! [C]: it neglects that aggregates drifted in from where the gas differed and that a
//! bin holds aggregates of different histories. The evolved mode carries both, and
//! `tests/bench/results/porosity_track.md` measures how far the track's answers are
//! from it. What the track buys: its phi_k depend on the gas only, so a cell's
//! coefficients are built once per gas refresh and the state holds no psi_k, as in the
//! compact mode.
#include <algorithm>
#include <cmath>
#include <span>

#include "disk/local_gas.hpp"
#include "physics/compaction.hpp"
#include "physics/drag.hpp"
#include "physics/growth_options.hpp"
#include "physics/particle.hpp"
#include "physics/relative_velocity.hpp"

namespace panoptic::physics::coagulation {

//! Largest step in ln m of the track's integration (midpoint rule) [-]: the slope's
//! switches are logistic steps 0.1 dex (0.23 in ln) wide (compaction.hpp).
inline constexpr double kTrackStepLnM = 0.05;

//! d ln phi / d ln m of the single-size law (compaction.hpp, compression_slope) for an
//! aggregate of mass m [g] and filling factor e^ln_phi in the gas `gas` [-].
inline double track_slope(double m, double ln_phi, const Species& sp, const LocalGas& gas,
                          const GrowthOptions& o) {
  const double phi = std::exp(ln_phi);
  const double a = radius(m, phi, sp.rho0);                                 // spec §2
  const double st = stokes_number_of_radius(a, phi, sp.rho0, gas, o.drag);  // spec §2
  const double dv = dv_pair(st, m, gas, o.eps, o.turbulence);               // spec §3
  return compression_slope(m, dv, a, st, gas, sp, o);                       // spec §4.3
}

//! ln phi raised to the compaction floor of its mass (spec §4.3), where a floor is on.
inline double raised_to_floor(double m, double ln_phi, const Species& sp,
                              const LocalGas& gas, const GrowthOptions& o) {
  if (!o.gas_compaction && !o.self_gravity) return ln_phi;
  const double st = stokes_number(m, std::exp(ln_phi), sp.rho0, gas, o.drag);
  return std::max(ln_phi, ln_compaction_floor(m, st, gas, sp, o));
}

//! The track's filling factor of every bin of the ascending masses m [g], into phi [-]:
//! 1 at and below m_start [g] (compact grains; 0: the monomer mass sp.m0), then the law
//! above integrated in ln m from (m_start, 1) by the midpoint rule in steps of at most
//! max_step in ln m, raised to the floor after each step. A track from compact grains
//! larger than monomers is that of their sticking products, which the volume rule of
//! spec §15.3 makes as fluffy relative to the grains as monomers' relative to monomers.
inline void track_filling_factors(std::span<const double> m, const Species& sp,
                                  const LocalGas& gas, const GrowthOptions& o,
                                  std::span<double> phi, double m_start = 0.0,
                                  double max_step = kTrackStepLnM) {
  double ln_m = std::log(std::max(m_start, sp.m0)), ln_phi = 0.0;
  for (std::size_t k = 0; k < m.size(); ++k) {
    const double ln_mk = std::log(m[k]);
    if (ln_mk > ln_m) {
      const int n_steps = static_cast<int>(std::ceil((ln_mk - ln_m) / max_step));
      const double h = (ln_mk - ln_m) / n_steps;
      for (int s = 0; s < n_steps; ++s) {
        const double half =
            ln_phi + 0.5 * h * track_slope(std::exp(ln_m), ln_phi, sp, gas, o);
        ln_phi += h * track_slope(std::exp(ln_m + 0.5 * h), half, sp, gas, o);
        ln_m = s + 1 == n_steps ? ln_mk : ln_m + h;
        ln_phi = raised_to_floor(std::exp(ln_m), ln_phi, sp, gas, o);
      }
    }
    phi[k] = std::exp(ln_phi);
  }
}

}  // namespace panoptic::physics::coagulation
