#include "disk/gas_disk.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "disk/pressure_gradient.hpp"
#include "src/core/units.hpp"
#include "src/solver/grid.hpp"

namespace panoptic {

using units::kAu;
using units::kPi;

double GasDisk::temperature(double r) const {
  const double t = th_.T_1au * std::pow(star_.luminosity / units::kLsun, 0.25) *
                   std::pow(r / kAu, -th_.q);
  return std::max(t, th_.T_floor);
}

double GasDisk::c_s(double r) const {
  return std::sqrt(units::kBoltzmann * temperature(r) / (th_.mu * units::kMassH));
}

double GasDisk::v_th(double r) const { return std::sqrt(8.0 / kPi) * c_s(r); }

double GasDisk::omega_k(double r) const {
  return std::sqrt(units::kG * star_.mass / (r * r * r));
}

double GasDisk::v_k(double r) const { return omega_k(r) * r; }

double GasDisk::h_g(double r) const { return c_s(r) / omega_k(r); }

double GasDisk::nu(double r) const { return alpha(r) * c_s(r) * h_g(r); }

double GasDisk::rho_mid(double sigma_g, double r) const {
  return sigma_g / (std::sqrt(2.0 * kPi) * h_g(r));
}

double GasDisk::pressure(double sigma_g, double r) const {
  const double cs = c_s(r);
  return rho_mid(sigma_g, r) * cs * cs;
}

double GasDisk::mfp(double rho_g) const {
  return th_.mu * units::kMassH / (th_.sigma_mol * rho_g);
}

double GasDisk::r_snow() const {
  // T_1 L^(1/4) (r/au)^-q = T_sub  ->  r = au (T_1 L^(1/4) / T_sub)^(1/q)
  const double t1 = th_.T_1au * std::pow(star_.luminosity / units::kLsun, 0.25);
  const double inf = std::numeric_limits<double>::infinity();
  if (th_.T_floor > th_.T_sub) return inf;  // warmer than T_sub everywhere: no ice
  if (th_.q == 0.0) return t1 > th_.T_sub ? inf : 0.0;  // one temperature everywhere
  if (th_.q < 0.0) return std::numeric_limits<double>::quiet_NaN();  // ice inside
  return kAu * std::pow(t1 / th_.T_sub, 1.0 / th_.q);
}

double PowerLawDisk::sigma_g(double r) const {
  return sigma_1au_ * std::pow(r / kAu, -p_);
}

double Lbp74Disk::sigma_g(double r) const {
  const double x = r / r_c_;
  return (2.0 - gamma_) * m_disk_ / (2.0 * kPi * r_c_ * r_c_) * std::pow(x, -gamma_) *
         std::exp(-std::pow(x, 2.0 - gamma_));
}

// Both closed forms are written with expm1 of the annulus' log width (log1p of its exact
// width r2 - r1 over r1), so that a narrow annulus keeps full relative precision: no
// difference of two nearly equal powers.
double PowerLawDisk::mass_between(double r1, double r2) const {
  // 2 pi sigma_1au au^2 int x^(1-p) dx, x = r/au: [x^k/k], k = 2 - p ([ln x] at k = 0)
  const double k = 2.0 - p_, ln_ratio = std::log1p((r2 - r1) / r1);
  const double scale = 2.0 * kPi * sigma_1au_ * kAu * kAu;
  if (k == 0.0) return scale * ln_ratio;
  return scale * std::pow(r1 / kAu, k) * std::expm1(k * ln_ratio) / k;
}

double Lbp74Disk::mass_between(double r1, double r2) const {
  // spec §1.2 B: with u = (r/r_c)^(2-gamma), Sigma 2 pi r dr = M e^-u du, so the mass is
  // M (e^-u1 - e^-u2) = -M e^-u1 expm1(-(u2 - u1)); the total of r = 0..inf is M.
  const double k = 2.0 - gamma_;
  const double u1 = std::pow(r1 / r_c_, k);
  const double du = u1 * std::expm1(k * std::log1p((r2 - r1) / r1));
  return -m_disk_ * std::exp(-u1) * std::expm1(-du);
}

double PowerLawDisk::sigma_1au_for_mass(double m, double p, double r1, double r2) {
  return m / PowerLawDisk({}, {}, 1.0, p).mass_between(r1, r2);
}

double TableDisk::r_snow() const { return t_->first_fall_to(thermal().T_sub); }

BumpedDisk::BumpedDisk(std::unique_ptr<GasDisk> smooth, double amplitude, double r0,
                       double width)
    : GasDisk(smooth->star(), smooth->thermal()),
      smooth_(std::move(smooth)),
      amplitude_(amplitude),
      r0_(r0),
      width_(width),
      name_(std::string(smooth_->name()) + " with a Gaussian bump") {
  set_alpha_profile(smooth_->alpha_profile());
}

double BumpedDisk::sigma_g(double r) const {
  const double x = (r - r0_) / width_;
  return smooth_->sigma_g(r) * (1.0 + amplitude_ * std::exp(-0.5 * x * x));
}

double BumpedDisk::mass_between(double r1, double r2) const {
  // the bump's share, A int Sigma_smooth exp(-x^2/2) 2 pi r dr: 4-point Gauss-Legendre on
  // pieces <= w/4 long (the Gaussian is smooth on that scale), only within 8 w of r0
  const double lo = std::max(r1, r0_ - 8.0 * width_),
               hi = std::min(r2, r0_ + 8.0 * width_);
  double bump = 0.0;
  if (hi > lo) {
    constexpr double kX[4] = {-0.8611363115940526, -0.3399810435848563,
                              0.3399810435848563, 0.8611363115940526};
    constexpr double kW[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461,
                              0.3478548451374538};
    const int pieces = std::max(1, int(std::ceil((hi - lo) / (0.25 * width_))));
    const double h = (hi - lo) / pieces;
    for (int k = 0; k < pieces; ++k)
      for (int j = 0; j < 4; ++j) {
        const double r = lo + h * (k + 0.5 * (1.0 + kX[j]));
        const double x = (r - r0_) / width_;
        bump += 0.5 * h * kW[j] * smooth_->sigma_g(r) * std::exp(-0.5 * x * x) * 2.0 *
                kPi * r;
      }
  }
  return smooth_->mass_between(r1, r2) + amplitude_ * bump;
}

std::unique_ptr<GasDisk> make_disk(const DiskParams& params) {
  const GasProfile& g = params.profile;
  std::unique_ptr<GasDisk> disk;
  if (g.kind == GasProfile::Kind::kLbp74)
    disk = std::make_unique<Lbp74Disk>(params.star, params.thermal, g.m_disk, g.r_c,
                                       g.gamma);
  else if (g.kind == GasProfile::Kind::kTable)
    disk = std::make_unique<TableDisk>(params.star, params.thermal, g.sigma_table,
                                       g.t_table);
  else
    disk = std::make_unique<PowerLawDisk>(params.star, params.thermal, g.sigma_1au, g.p);
  disk->set_alpha_profile(params.alpha);
  if (g.bump_amplitude != 0.0)
    disk = std::make_unique<BumpedDisk>(std::move(disk), g.bump_amplitude, g.bump_r0,
                                        g.bump_width);
  return disk;
}

std::vector<double> dlnp_dlnr_centres(const GasDisk& disk, const Grid& grid,
                                      const std::vector<double>& sigma_g) {
  const int n = grid.n_cells();
  std::vector<double> lnp(n), out(n);
  for (int i = 0; i < n; ++i) lnp[i] = std::log(disk.pressure(sigma_g[i], grid.r_c(i)));
  // centred differences in ln r (one-sided at the edges), on any spacing of the centres
  for (int i = 0; i < n; ++i) {
    const int lo = i > 0 ? i - 1 : 0, hi = i < n - 1 ? i + 1 : n - 1;
    out[i] = (lnp[hi] - lnp[lo]) / std::log(grid.r_c(hi) / grid.r_c(lo));
  }
  return out;
}

std::vector<double> eta_centres(const GasDisk& disk, const Grid& grid,
                                const std::vector<double>& sigma_g) {
  auto eta = dlnp_dlnr_centres(disk, grid, sigma_g);
  for (int i = 0; i < grid.n_cells(); ++i) {
    const double hr = disk.h_g(grid.r_c(i)) / grid.r_c(i);
    eta[i] = pressure_gradient_eta(hr * hr, eta[i]);
  }
  return eta;
}

}  // namespace panoptic
