#include "src/observe/emission.hpp"

#include <cmath>
#include <complex>
#include <map>
#include <tuple>

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

namespace {

//! The opacities of a size distribution's bins at one wavelength: each distinct
//! aggregate (species, radius, filling factor, density) computed once, as compact bins
//! are the same in every cell of a species.
template <class Kappa>
class DistinctOpacities {
 public:
  explicit DistinctOpacities(const Kappa& kappa) : kappa_(kappa) {}
  //! Sum_k (sigma_k / Sigma_d) kappa_k of a cell's bins [cm^2 g^-1].
  double mass_weighted(int inner, const std::vector<BinParticle>& bins) {
    double sum = 0.0;
    for (const BinParticle& b : bins) {
      const SeenParticle& q = b.particle;
      const auto key = std::tuple{inner, q.a_cm, q.phi, q.rho};
      auto it = known_.find(key);
      if (it == known_.end()) it = known_.emplace(key, kappa_(inner, q)).first;
      sum += b.mass_fraction * it->second;
    }
    return sum;
  }

 private:
  const Kappa& kappa_;
  std::map<std::tuple<int, double, double, double>, double> known_;
};

}  // namespace

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
    auto kappa = [&](int inner, const SeenParticle& q) {
      const cplx m = physics::porous_index(inner ? m_sil : m_out, q.phi);
      return physics::kappa_abs(m, q.a_cm, q.rho, lambda_cm);
    };
    DistinctOpacities bins(kappa);
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t k = l * n + i;
      e.kappa_abs[k] = p.bins.empty() ? kappa(p.inner[i], {p.a_cm[i], p.phi[i], p.rho[i]})
                                      : bins.mass_weighted(p.inner[i], p.bins[i]);
      e.tau[k] = s.sigma_d[i] * e.kappa_abs[k];
      e.intensity[k] = slab_intensity_jy_arcsec2(e.nu[l], s.T[i], e.tau[k], e.mu);
      e.b_nu[k] = slab_intensity_jy_arcsec2(e.nu[l], s.T[i], 1e300, 1.0);
    }
  }
  return e;
}

}  // namespace panoptic
