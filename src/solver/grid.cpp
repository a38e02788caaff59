#include "src/solver/grid.hpp"

#include <algorithm>
#include <cmath>

#include "src/core/units.hpp"

namespace panoptic {

Grid::Grid(double r_in, double r_out, int n, double stretch)
    : n_(n), stretch_(stretch), r_c_(n), r_f_(n + 1), area_(n), dlnr_(n) {
  const double L = std::log(r_out / r_in);
  // A stretch this small shifts no face by more than a round-off (|p| L^2/8 < 1e-12 in
  // ln r): the log grid, exactly (a subnormal p lost the expm1 form's precision).
  if (std::abs(stretch) * L * L < 1e-12) {
    const double h = L / n;
    for (int i = 0; i <= n; ++i) r_f_[i] = r_in * std::exp(h * i);
  } else if (std::abs(stretch * L) < 1e-3) {
    // The same faces written without the cancellation of u1 - u0 (below), which for a
    // tiny stretch loses all digits (p = 1e-16 gave faces out of order): u_i = u0 (1 +
    // t expm1(-p L)), t = i/n, L = ln(r_out/r_in), so ln(r_i/r_in) = -log1p(t expm1(-p
    // L))/p, which tends to t L (log spacing) as p -> 0. Used only here, so that the
    // faces of larger stretches keep their bits.
    const double em = std::expm1(-stretch * L);
    for (int i = 0; i <= n; ++i)
      r_f_[i] = r_in * std::exp(-std::log1p(em * i / n) / stretch);
  } else {
    // d ln r = r^p du/(-p) for u = r^-p: faces uniform in u put d ln r ∝ r^p.
    const double u0 = std::pow(r_in, -stretch), u1 = std::pow(r_out, -stretch);
    for (int i = 0; i <= n; ++i)
      r_f_[i] = std::pow(u0 + (u1 - u0) * i / n, -1.0 / stretch);
  }
  r_f_[0] = r_in;
  r_f_[n] = r_out;  // exact edges, whatever the rounding
  for (int i = 0; i < n; ++i) {
    dlnr_[i] = std::log(r_f_[i + 1] / r_f_[i]);
    r_c_[i] = std::sqrt(r_f_[i] * r_f_[i + 1]);
    area_[i] = units::kPi * (r_f_[i + 1] * r_f_[i + 1] - r_f_[i] * r_f_[i]);
  }
  dlnr_c_.assign(n, 0.0);
  for (int i = 1; i < n; ++i) dlnr_c_[i] = std::log(r_c_[i] / r_c_[i - 1]);
}

int Grid::cell_of(double r) const {
  const auto it = std::upper_bound(r_f_.begin(), r_f_.end(), r);
  const int i = static_cast<int>(it - r_f_.begin()) - 1;
  return std::clamp(i, 0, n_ - 1);
}

}  // namespace panoptic
