#include "src/model/initial_state.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "disk/gas_disk.hpp"
#include "physics/modules/dust_transport.hpp"
#include "physics/modules/porous_growth.hpp"
#include "physics/modules/size_distribution.hpp"
#include "src/core/error.hpp"
#include "src/core/units.hpp"
#include "src/model/simulation.hpp"

namespace panoptic {

using units::kAu;

namespace {

//! exp(-x) I_0(x), the exponentially scaled modified Bessel function (no overflow).
double i0e(double x) {
  if (x < 500.0) return std::cyl_bessel_i(0.0, x) * std::exp(-x);
  // Abramowitz & Stegun 9.7.1, three terms: relative error < 1e-9 for x >= 500.
  return (1.0 + 1.0 / (8.0 * x) + 9.0 / (128.0 * x * x)) /
         std::sqrt(2.0 * units::kPi * x);
}

//! A thin ring at r0 spread by diffusion until its Gaussian width is w, normalised to 1
//! at r0: the exact axisymmetric diffusing-ring solution
//! Sigma ∝ exp(-(r^2 + r0^2)/(4Dt)) I_0(r r0/(2Dt)) with 2Dt = w^2, so that
//! regression tests can compare with the analytic solution at all later times.
double diffused_ring(double r, double r0, double w) {
  const double x = (r - r0) / w;
  return std::exp(-0.5 * x * x) * i0e(r * r0 / (w * w)) / i0e(r0 * r0 / (w * w));
}

}  // namespace

InitialDust initial_dust(const Config& cfg, const Grid& grid, const GasDisk& disk,
                         std::span<const double> sigma_g, std::span<const char> inside,
                         double r_snow) {
  const int n = grid.n_cells();
  // Initial dust (spec §6.4: Sigma_d = Z Sigma_g, Z_in = (1 - f_ice) Z_out, spec §1.7),
  // or a test ring on the floor.
  const double z = cfg.real("dust.dust_to_gas"), floor = cfg.real("dust.sigma_floor_rel");
  const double f_ice = cfg.real("snowline.f_ice");
  InitialDust d;
  d.sigma_d.resize(n);
  for (int i = 0; i < n; ++i) {
    if (cfg.str("dust.init") == "gaussian_ring") {
      d.sigma_d[i] = cfg.real("dust.ring_sigma") *
                         diffused_ring(grid.r_c(i), cfg.real("dust.ring_r_au") * kAu,
                                       cfg.real("dust.ring_width_au") * kAu) +
                     floor * sigma_g[i];
    } else {
      d.sigma_d[i] = (inside[i] ? 1.0 - f_ice : 1.0) * z * sigma_g[i];
    }
    d.mass += d.sigma_d[i] * grid.area(i);
  }
  // The same dust integrated exactly (spec §1.7: Z_in inside r_snow, Z_out outside), to
  // show the cell-centre values' quadrature error (the run header).
  d.profile_mass = std::numeric_limits<double>::quiet_NaN();
  if (cfg.str("dust.init") == "dust_to_gas") {
    const double r1 = grid.r_f(0), r2 = grid.r_f(n);
    const bool snowline = cfg.flag("snowline.enabled");
    const double rs = snowline ? std::clamp(r_snow, r1, r2) : r1;  // r_snow may be +-inf
    d.profile_mass = z * ((1.0 - f_ice) * (rs > r1 ? disk.mass_between(r1, rs) : 0.0) +
                          (rs < r2 ? disk.mass_between(rs, r2) : 0.0));
  }
  return d;
}

std::vector<double> Simulation::initial_state() const {
  const auto& L = *layout_;
  std::vector<double> y(L.size(), 0.0);
  for (int i = 0; i < grid_.n_cells(); ++i) {
    if (distribution_)  // spread over the mass bins (spec §15.4)
      distribution_->initial_cell(
          i, sigma_d0_[i],
          std::span<double>(y).subspan(L.index(i, distribution_->bin_slot(0)),
                                       distribution_->cell_vars()));
    else
      y[L.index(i, transport_->sigma_slot())] = sigma_d0_[i];
    if (gas_.evolves()) y[L.index(i, gas_.slot)] = gas_.static_sigma[i];
    // monomers everywhere (spec §6.4): m = m0 of the cell's species, phi = 1
    if (growth_) y[L.index(i, codec_->qm_slot)] = sigma_d0_[i] * codec_->x_lo[i];
  }
  return y;
}

void Simulation::check_start_is_finite() const {
  // Keys inside their ranges can still combine into a disk or an initial state that is
  // not finite (dust.dust_to_gas = 1e308, star.luminosity_lsun = 1e308, an LBP r_c_au of
  // 1e-6 au...), which CVODE reported only as a failed first right-hand side, naming no
  // key. Said here, before any output is written, as bad input.
  const auto fail = [&](int cell, const std::string& what, double value) {
    std::ostringstream m;
    m << what << " = " << value << " at r = " << grid_.r_c(cell) / kAu << " au (cell "
      << cell
      << "): the scene's values, each inside its range, give a disk or an initial state "
         "that is not finite and positive there; bring the disk.*, star.*, dust.*, "
         "material.* and grid.* values nearer to physical ones (a grid reaching far "
         "beyond an LBP disk's r_c_au has no gas there; panoptic check prints the "
         "resolved scene)";
    // the likely culprits: values the scene set far from their defaults (1e308, 1e-300)
    std::string far;
    for (const KeySpec& spec : scene_keys()) {
      if (spec.type != KeyType::kReal || !cfg_.user_set(spec.key)) continue;
      const double v = cfg_.real(spec.key), d = default_real(spec.key);
      if (d != 0.0 && v != 0.0 && std::abs(std::log10(std::abs(v / d))) > 3.0)
        far += (far.empty() ? "" : ", ") + spec.key + " = " + num(v) + " (default " +
               spec.default_toml + ", " + cfg_.where(spec.key) + ")";
    }
    if (!far.empty()) m << "; set far from their defaults (over 1e3 x): " << far;
    throw ConfigError(m.str());
  };
  const auto bad = [](double v) { return !(std::isfinite(v) && v > 0.0); };
  for (int i = 0; i < grid_.n_cells(); ++i) {
    const double r = grid_.r_c(i);
    if (bad(gas_.static_sigma[i])) fail(i, "Sigma_g [g cm^-2]", gas_.static_sigma[i]);
    if (bad(disk_->temperature(r))) fail(i, "T [K]", disk_->temperature(r));
    if (!(std::isfinite(sigma_d0_[i]) && sigma_d0_[i] >= 0.0))
      fail(i, "initial Sigma_d [g cm^-2]", sigma_d0_[i]);
    if (cell_gas_) {
      const auto& g = cell_gas_->reference(i);
      for (const auto& [name, v] : {std::pair{"rho_g [g cm^-3]", g.rho_g},
                                    {"mean free path [cm]", g.mfp},
                                    {"nu_mol [cm^2 s^-1]", g.nu_mol},
                                    {"c_s [cm s^-1]", g.c_s},
                                    {"H_g [cm]", g.h_g}})
        if (bad(v)) fail(i, name, v);
      if (!std::isfinite(g.eta)) fail(i, "eta", g.eta);
    }
  }
  const auto y0 = initial_state();
  std::vector<double> f(y0.size());
  model_->rhs(0.0, y0, f);
  const auto& L = *layout_;
  for (long k = 0; k < L.size(); ++k)
    if (!std::isfinite(y0[k]) || !std::isfinite(f[k])) {
      const int cell = L.cell_of(k);
      const std::string what = (std::isfinite(y0[k]) ? "d/dt of " : "initial ") +
                               L.info_of(k).name + " [" + L.info_of(k).units +
                               (std::isfinite(y0[k]) ? " s^-1]" : "]");
      fail(cell < 0 ? 0 : cell, what, std::isfinite(y0[k]) ? f[k] : y0[k]);
    }
}

}  // namespace panoptic
