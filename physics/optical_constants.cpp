#include "physics/optical_constants.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "physics/mie.hpp"

namespace panoptic::physics {

using cplx = std::complex<double>;

OpticalTable::OpticalTable(std::string name, std::vector<double> lambda_mm,
                           std::vector<double> n, std::vector<double> k)
    : name_(std::move(name)),
      lambda_mm_(std::move(lambda_mm)),
      n_(std::move(n)),
      k_(std::move(k)) {
  const auto fail = [&](const std::string& what) {
    throw std::invalid_argument("optical constants of " + name_ + ": " + what);
  };
  if (lambda_mm_.size() < 2) fail("need at least 2 wavelengths");
  if (n_.size() != lambda_mm_.size() || k_.size() != lambda_mm_.size())
    fail("the wavelength, n and k lists must have the same length (" +
         std::to_string(lambda_mm_.size()) + ", " + std::to_string(n_.size()) + ", " +
         std::to_string(k_.size()) + ")");
  for (std::size_t i = 0; i < lambda_mm_.size(); ++i) {
    if (!(lambda_mm_[i] > 0.0)) fail("wavelengths must be > 0");
    if (i > 0 && !(lambda_mm_[i] > lambda_mm_[i - 1]))
      fail("wavelengths must increase strictly");
    // natural materials have n and k of order 1-10 (metals at mm wavelengths ~1e3);
    // 1e100 overflowed the Mie series (an internal error, exit 1)
    if (!(n_[i] > 0.0 && n_[i] <= 1e4)) fail("n must be > 0 and <= 1e4");
    if (!(k_[i] > 0.0 && k_[i] <= 1e4))
      fail("k must be > 0 (log interpolation; use 1e-12 for none) and <= 1e4");
  }
}

bool OpticalTable::covers(double lambda_mm) const {
  return lambda_mm >= lambda_mm_.front() && lambda_mm <= lambda_mm_.back();
}

cplx OpticalTable::at(double lambda_mm) const {
  if (!covers(lambda_mm)) {
    std::ostringstream s;
    s << "optical constants of " << name_ << ": lambda = " << lambda_mm
      << " mm is outside the table (" << lambda_mm_.front() << " - " << lambda_mm_.back()
      << " mm)";
    throw std::out_of_range(s.str());
  }
  const auto it = std::upper_bound(lambda_mm_.begin(), lambda_mm_.end(), lambda_mm);
  const std::size_t j = std::min<std::size_t>(
      static_cast<std::size_t>(it - lambda_mm_.begin()), lambda_mm_.size() - 1);
  const std::size_t i = j - 1;
  const double t =
      std::log(lambda_mm / lambda_mm_[i]) / std::log(lambda_mm_[j] / lambda_mm_[i]);
  const double n = n_[i] + t * (n_[j] - n_[i]);
  const double k = std::exp(std::log(k_[i]) + t * std::log(k_[j] / k_[i]));
  return {n, k};
}

cplx maxwell_garnett(cplx eps_m, cplx eps_i, double f) {
  const cplx d = eps_i - eps_m;
  return eps_m * (eps_i + 2.0 * eps_m + 2.0 * f * d) / (eps_i + 2.0 * eps_m - f * d);
}

cplx bruggeman(cplx eps1, cplx eps2, double f2) {
  const double f1 = 1.0 - f2;
  const cplx b = (3.0 * f1 - 1.0) * eps1 + (3.0 * f2 - 1.0) * eps2;
  const cplx s = std::sqrt(b * b + 8.0 * eps1 * eps2);
  const cplx e_plus = (b + s) / 4.0, e_minus = (b - s) / 4.0;
  // The physical root has Im >= 0 (absorbing media) and, for real inputs, Re > 0.
  if (e_plus.imag() < 0.0 && e_minus.imag() >= e_plus.imag()) return e_minus;
  if (e_plus.real() <= 0.0 && e_minus.real() > 0.0) return e_minus;
  return e_plus;
}

cplx porous_index(cplx m_solid, double phi) {
  if (phi >= 1.0) return m_solid;
  // Vacuum is the matrix and the solid the inclusions, at volume fraction phi (Kataoka
  // et al. 2014, eq. 3). The other way round (vacuum bubbles in a solid, the
  // Hashin-Shtrikman bound of a foam) gave an aggregate of phi ~ 1e-3 3.2x (ice-silicate
  // mix) to 14x (silicate) the absorption per gram of its own monomers at 1.3 mm.
  const cplx eps = maxwell_garnett(cplx(1.0, 0.0), m_solid * m_solid, phi);
  cplx m = std::sqrt(eps);
  if (m.imag() < 0.0) m = -m;
  return m;
}

double kappa_abs(cplx m, double a_cm, double rho_int, double lambda_cm) {
  const double x = 2.0 * 3.14159265358979323846 * a_cm / lambda_cm;
  const MieEfficiencies q = sphere_efficiencies(m, x);
  return 3.0 * q.q_abs / (4.0 * a_cm * rho_int);
}

}  // namespace panoptic::physics
