// The opacity of a size distribution in `panoptic observe` (src/observe/particles,
// emission): a one-bin distribution is seen exactly as the single-size particle of the
// same mass, filling factor and species; two bins give the mass-weighted mean of the
// two opacities, computed here from the laws themselves (physics/mie, optical_constants);
// a bin below zero (solver noise in a drained cell) weighs nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstddef>
#include <vector>

#include "physics/optical_constants.hpp"
#include "physics/particle.hpp"
#include "src/observe/emission.hpp"
#include "src/observe/materials.hpp"
#include "src/observe/particles.hpp"
#include "src/observe/run_snapshot.hpp"
#include "src/scene/config.hpp"

namespace {

using namespace panoptic;

const std::vector<double> kLambdaMm{0.87, 1.3, 3.0, 9.0};

//! The default scene's materials and monomer densities.
struct Scene {
  Config cfg = load_scene_text("[output]\nt_end_yr = 1e5\n", "scene.toml");
  OpticalMaterials mat = optical_materials(cfg);
  MonomerDensities rho0{cfg.real("material.ice_rho0"), cfg.real("material.sil_rho0")};
  //! Monomer density of cell i of snapshot() (cell 0 inside the snow line).
  double rho0_of(std::size_t i) const { return i == 0 ? rho0.sil : rho0.ice; }
};

//! Two cells, at 1 au (silicate, inside the snow line at 2 au) and 5 au (outer species).
RunSnapshot snapshot() {
  RunSnapshot s;
  s.r_c_au = {1.0, 5.0};
  s.r_f_au = {0.5, 2.5, 10.0};
  s.T = {150.0, 60.0};
  s.sigma_d = {3.0, 0.7};
  s.r_snow_au = 2.0;
  return s;
}

CellEmission seen(const Scene& sc, const RunSnapshot& s) {
  const CellParticles p = cell_particles(s, sc.mat, true, sc.rho0, ObserveArgs{});
  return cell_emission(kLambdaMm, 30.0, s, sc.mat, p);
}

//! The single-size snapshot of aggregates of mass m and filling factor phi per cell.
RunSnapshot single(const Scene& sc, double m, const std::vector<double>& phi) {
  RunSnapshot s = snapshot();
  for (std::size_t i = 0; i < 2; ++i) {
    s.a.push_back(physics::radius(m, phi[i], sc.rho0_of(i)));
    s.phi.push_back(phi[i]);
    s.rho_int.push_back(physics::internal_density(phi[i], sc.rho0_of(i)));
  }
  return s;
}

//! kappa_abs of one aggregate (mass m, filling factor phi) of cell i at lambda, from
//! the laws: Maxwell-Garnett with vacuum at the volume fraction of the optical solid.
double kappa_of(const Scene& sc, std::size_t i, double m, double phi, double lambda_mm) {
  const double rho_int = phi * sc.rho0_of(i);
  const double rho_solid = i == 0 ? sc.mat.rho_sil : sc.mat.outer_density();
  const std::complex<double> solid =
      i == 0 ? sc.mat.sil.at(lambda_mm) : sc.mat.outer_index(lambda_mm);
  return physics::kappa_abs(
      physics::porous_index(solid, std::min(1.0, rho_int / rho_solid)),
      physics::radius(m, phi, sc.rho0_of(i)), rho_int, lambda_mm * 0.1);
}

TEST(ObserveDistribution, OneBinIsTheSingleSizeParticleExactly) {
  const Scene sc;
  for (const double m : {1e-10, 1e-3, 1e2, 1e6})
    for (const bool compact : {true, false}) {
      const std::vector<double> phi =
          compact ? std::vector<double>{1.0, 1.0} : std::vector<double>{0.3, 2e-3};
      const RunSnapshot one = single(sc, m, phi);
      RunSnapshot dist = snapshot();
      dist.a = one.a;
      dist.m_bins = {m};
      dist.sigma_bins = dist.sigma_d;
      if (!compact) dist.phi_bins = phi;  // a compact run writes no phi_bins
      const CellEmission a = seen(sc, one), b = seen(sc, dist);
      for (std::size_t k = 0; k < a.kappa_abs.size(); ++k) {
        EXPECT_EQ(a.kappa_abs[k], b.kappa_abs[k]) << "m " << m << " entry " << k;
        EXPECT_EQ(a.tau[k], b.tau[k]) << "m " << m << " entry " << k;
        EXPECT_EQ(a.intensity[k], b.intensity[k]) << "m " << m << " entry " << k;
      }
      // the single-size path itself against the laws
      EXPECT_EQ(a.kappa_abs[1], kappa_of(sc, 1, m, phi[1], kLambdaMm[0]));
    }
}

TEST(ObserveDistribution, TwoBinsGiveTheMassWeightedMean) {
  const Scene sc;
  const std::vector<double> m{1e-6, 3e1};
  // per cell: sigma_k and phi_k of the two bins (cell by cell, as the run writes them)
  RunSnapshot s = snapshot();
  s.m_bins = m;
  s.sigma_bins = {2.4, 0.6, 0.1, 0.6};
  s.phi_bins = {0.8, 0.6, 1.0, 0.5};
  s.sigma_d = {2.4 + 0.6, 0.1 + 0.6};
  s.a = {0.0, 0.0};
  const CellEmission e = seen(sc, s);
  const std::size_t n = 2;
  for (std::size_t l = 0; l < kLambdaMm.size(); ++l)
    for (std::size_t i = 0; i < n; ++i) {
      const double k0 = kappa_of(sc, i, m[0], s.phi_bins[2 * i], kLambdaMm[l]);
      const double k1 = kappa_of(sc, i, m[1], s.phi_bins[2 * i + 1], kLambdaMm[l]);
      const double s0 = s.sigma_bins[2 * i], s1 = s.sigma_bins[2 * i + 1];
      const double tau = s0 * k0 + s1 * k1, kappa = tau / (s0 + s1);
      // the bins differ: a weighting other than by mass would show
      EXPECT_GT(std::abs(k0 - k1), 0.05 * std::max(k0, k1)) << l << " " << i;
      EXPECT_NEAR(e.kappa_abs[l * n + i], kappa, 1e-14 * kappa) << l << " " << i;
      EXPECT_NEAR(e.tau[l * n + i], tau, 1e-14 * tau) << l << " " << i;
    }
  // the particle written for each cell is its mass-dominating bin: bin 0 in cell 0,
  // bin 1 in cell 1
  const CellParticles p = cell_particles(s, sc.mat, true, sc.rho0, ObserveArgs{});
  EXPECT_EQ(p.a_cm[0], physics::radius(m[0], 0.8, sc.rho0.sil));
  EXPECT_EQ(p.a_cm[1], physics::radius(m[1], 0.5, sc.rho0.ice));
  EXPECT_EQ(p.rho[1], 0.5 * sc.rho0.ice);
}

TEST(ObserveDistribution, BinsBelowZeroWeighNothing) {
  const Scene sc;
  RunSnapshot s = snapshot();
  s.m_bins = {1e-4, 1e2};
  s.sigma_bins = {3.0, -1e-18, -1e-20, 0.7};  // cell 0: bin 0 only; cell 1: bin 1 only
  s.a = {0.0, 0.0};
  RunSnapshot one0 = single(sc, 1e-4, {1.0, 1.0}), one1 = single(sc, 1e2, {1.0, 1.0});
  const CellEmission e = seen(sc, s), e0 = seen(sc, one0), e1 = seen(sc, one1);
  for (std::size_t l = 0; l < kLambdaMm.size(); ++l) {
    EXPECT_EQ(e.kappa_abs[2 * l], e0.kappa_abs[2 * l]);
    EXPECT_EQ(e.kappa_abs[2 * l + 1], e1.kappa_abs[2 * l + 1]);
  }
}

}  // namespace
