#include "src/observe/particles.hpp"

#include <algorithm>
#include <cstddef>

namespace panoptic {

CellParticles cell_particles(const RunSnapshot& s, const OpticalMaterials& mat,
                             bool snowline, const ObserveArgs& a) {
  const std::size_t n = s.r_c_au.size();
  const bool has_size = !s.a.empty();
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
  p.a_cm.resize(n);
  p.phi.resize(n);
  p.rho.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double rho_solid = p.inner[i] ? mat.rho_sil : mat.outer_density();
    const bool compact = a.a_cm_given || !has_size;
    p.a_cm[i] = a.a_cm_given ? a.a_cm : s.a[i];
    p.rho[i] = compact ? rho_solid : s.rho_int[i];
    p.phi[i] = compact ? 1.0 : std::min(1.0, s.rho_int[i] / rho_solid);
  }
  return p;
}

}  // namespace panoptic
