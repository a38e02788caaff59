#include "src/observe/particles.hpp"

#include <algorithm>
#include <cstddef>

#include "physics/particle.hpp"

namespace panoptic {
namespace {

//! The bins of cell i of a size-distribution snapshot (the run's aggregates: mass m_k,
//! filling factor phi_k of /snapshots/phi_bins or 1 when compact, monomer density
//! `rho0`; spec §2, §15.1) made of an optical solid of density `rho_solid`; the
//! mass-dominating bin (argmax sigma_k, the first of equals, as the run's) in `dominant`.
std::vector<BinParticle> distribution_bins(const RunSnapshot& s, std::size_t i,
                                           double rho0, double rho_solid,
                                           SeenParticle& dominant) {
  const std::size_t nb = s.m_bins.size();
  const double* sigma = &s.sigma_bins[i * nb];
  auto particle = [&](std::size_t k) {
    const double phi = s.phi_bins.empty() ? 1.0 : s.phi_bins[i * nb + k];
    return seen_particle(physics::radius(s.m_bins[k], phi, rho0),
                         physics::internal_density(phi, rho0), rho_solid);
  };
  dominant =
      particle(static_cast<std::size_t>(std::max_element(sigma, sigma + nb) - sigma));
  // A bin below zero (a drained bin within the solver's absolute tolerance) weighs
  // nothing: the mass fractions are of the bins holding dust.
  double total = 0.0;
  for (std::size_t k = 0; k < nb; ++k)
    if (sigma[k] > 0.0) total += sigma[k];
  std::vector<BinParticle> bins;
  for (std::size_t k = 0; k < nb; ++k)
    if (sigma[k] > 0.0) bins.push_back({sigma[k] / total, particle(k)});
  if (bins.empty()) bins.push_back({1.0, dominant});
  return bins;
}

}  // namespace

SeenParticle seen_particle(double a_cm, double rho_int, double rho_solid) {
  return {a_cm, std::min(1.0, rho_int / rho_solid), rho_int};
}

CellParticles cell_particles(const RunSnapshot& s, const OpticalMaterials& mat,
                             bool snowline, const MonomerDensities& rho0,
                             const ObserveArgs& a) {
  const std::size_t n = s.r_c_au.size();
  const bool has_size = !s.a.empty();
  const bool distribution = s.distribution() && !a.a_cm_given;
  CellParticles p;
  // r_snow_au is +inf for a disk warmer than T_sub everywhere (all silicate), 0 for one
  // colder everywhere; NaN (a run without a snow line) compares false
  p.inner.resize(n);
  for (std::size_t i = 0; i < n; ++i) p.inner[i] = snowline && s.r_c_au[i] < s.r_snow_au;
  // The particle's mass and size are the run's (rho_int = phi rho0 of its monomers); its
  // optical solid has the density of the material whose constants it gets (silicate,
  // water ice of observe.water_ice_rho, or their mix), so the volume fraction of that
  // solid, the filling factor of the mixing rule, is rho_int / rho_solid: the run's phi
  // when the densities agree (the default mix: 1.408 against material.ice_rho0 = 1.4).
  // A compact grain (--a-cm, or a run without sizes) is of the optical solid itself.
  // Each bin of a size distribution is such a particle.
  p.a_cm.resize(n);
  p.phi.resize(n);
  p.rho.resize(n);
  if (distribution) p.bins.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double rho_solid = p.inner[i] ? mat.rho_sil : mat.outer_density();
    SeenParticle seen;
    if (distribution)
      p.bins[i] =
          distribution_bins(s, i, p.inner[i] ? rho0.sil : rho0.ice, rho_solid, seen);
    else if (a.a_cm_given || !has_size)
      seen = seen_particle(a.a_cm_given ? a.a_cm : s.a[i], rho_solid, rho_solid);
    else
      seen = seen_particle(s.a[i], s.rho_int[i], rho_solid);
    p.a_cm[i] = seen.a_cm;
    p.phi[i] = seen.phi;
    p.rho[i] = seen.rho;
  }
  return p;
}

}  // namespace panoptic
