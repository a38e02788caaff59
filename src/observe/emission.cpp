#include "src/observe/emission.hpp"

#include <cmath>
#include <complex>

#include "physics/mie.hpp"
#include "physics/optical_constants.hpp"
#include "src/core/units.hpp"

namespace panoptic {

double planck_nu(double nu, double T) {
  using namespace units;
  const double x = kPlanck * nu / (kBoltzmann * T);
  return 2.0 * kPlanck * nu * nu * nu / (kLightSpeed * kLightSpeed) / std::expm1(x);
}

double slab_intensity_jy_arcsec2(double nu, double T, double tau, double mu) {
  using namespace units;
  const double b = planck_nu(nu, T) / kJansky / (kArcsecPerRad * kArcsecPerRad);
  return b * -std::expm1(-tau / mu);
}

CellEmission cell_emission(const std::vector<double>& lambda_mm, double incl_deg,
                           const RunSnapshot& s, const OpticalMaterials& mat,
                           const CellParticles& p) {
  using cplx = std::complex<double>;
  const std::size_t nl = lambda_mm.size(), n = s.r_c_au.size();
  CellEmission e;
  e.n_cells = n;
  e.mu = std::cos(incl_deg * units::kPi / 180.0);
  e.nu.resize(nl);
  e.kappa_abs.resize(nl * n);
  e.tau.resize(nl * n);
  e.intensity.resize(nl * n);
  e.b_nu.resize(nl * n);
  for (std::size_t l = 0; l < nl; ++l) {
    const double lambda_cm = lambda_mm[l] * 0.1;
    e.nu[l] = units::kLightSpeed / lambda_cm;
    const cplx m_sil = mat.sil.at(lambda_mm[l]), m_out = mat.outer_index(lambda_mm[l]);
    for (std::size_t i = 0; i < n; ++i) {
      const cplx m = physics::porous_index(p.inner[i] ? m_sil : m_out, p.phi[i]);
      const std::size_t k = l * n + i;
      e.kappa_abs[k] = physics::kappa_abs(m, p.a_cm[i], p.rho[i], lambda_cm);
      e.tau[k] = s.sigma_d[i] * e.kappa_abs[k];
      e.intensity[k] = slab_intensity_jy_arcsec2(e.nu[l], s.T[i], e.tau[k], e.mu);
      e.b_nu[k] = slab_intensity_jy_arcsec2(e.nu[l], s.T[i], 1e300, 1.0);
    }
  }
  return e;
}

}  // namespace panoptic
