#pragma once
//! Checks of the one-cell coagulation engine (physics/coagulation/smoluchowski.hpp)
//! shared by its tests: the analytic Jacobian against central differences of the
//! right-hand side (with the coefficients held fixed or rebuilt from the state), and the
//! imbalance of the mass and volume rates.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <span>
#include <utility>
#include <vector>

#include "physics/coagulation/smoluchowski.hpp"

namespace panoptic::physics::coagulation {

//! The analytic Jacobian `jac` (row-major, y.size() squared) against central differences
//! (step 1e-6 |y_j|) of the right-hand side f: the largest |J - J_fd|, |J| and |J_fd|;
//! with `column_scaled` each column j is multiplied by y_j (d/d ln y_j).
struct FdComparison {
  double err = 0.0, max_analytic = 0.0, max_fd = 0.0;
};
template <class F>
FdComparison compare_with_differences(F f, const std::vector<double>& jac,
                                      std::vector<double> y, bool column_scaled) {
  const int nv = static_cast<int>(y.size());
  FdComparison d;
  for (int col = 0; col < nv; ++col) {
    const double h = 1e-6 * std::abs(y[col]);
    const double keep = y[col];
    const double w = column_scaled ? keep : 1.0;
    y[col] = keep + h;
    const auto fp = f(y);
    y[col] = keep - h;
    const auto fm = f(y);
    y[col] = keep;
    for (int row = 0; row < nv; ++row) {
      const double fd = (fp[row] - fm[row]) / (2.0 * h) * w;
      const double an = jac[static_cast<std::size_t>(row) * nv + col] * w;
      d.err = std::max(d.err, std::abs(an - fd));
      d.max_analytic = std::max(d.max_analytic, std::abs(an));
      d.max_fd = std::max(d.max_fd, std::abs(fd));
    }
  }
  return d;
}

//! max |J - J_fd| / max |J|, J_fd by central differences of the right-hand side.
inline double jacobian_error(const Smoluchowski& eng, const CellCoefficients& c,
                             std::vector<double> y, bool porous) {
  const int n = eng.size();
  const int nv = porous ? 2 * n : n;
  auto f = [&](const std::vector<double>& yy) {
    std::vector<double> out(nv);
    std::span<const double> s(yy.data(), n);
    std::span<const double> p =
        porous ? std::span<const double>(yy.data() + n, n) : std::span<const double>();
    eng.rhs(c, s, p, std::span<double>(out.data(), n),
            porous ? std::span<double>(out.data() + n, n) : std::span<double>());
    return out;
  };
  std::vector<double> jac(static_cast<std::size_t>(nv) * nv);
  eng.jacobian(
      c, std::span<const double>(y.data(), n),
      porous ? std::span<const double>(y.data() + n, n) : std::span<const double>(), jac);
  const FdComparison d = compare_with_differences(f, jac, std::move(y), false);
  return d.err / d.max_analytic;
}

//! max |(J - J_fd) y_j| / max |J_fd y_j| with the coefficients rebuilt from the state
//! at every difference (`coefficients(y)`), J fed the coefficients' derivatives (after
//! `strip`, which may remove some, to show that the check sees them).
template <class Coefficients, class Strip = void (*)(CellCoefficients&)>
double full_jacobian_error(
    const Smoluchowski& eng, Coefficients coefficients, std::vector<double> y,
    Strip strip = [](CellCoefficients&) {}) {
  const int n = eng.size(), nv = 2 * n;
  auto f = [&](const std::vector<double>& yy) {
    const CellCoefficients c = coefficients(yy);
    std::vector<double> out(nv);
    eng.rhs(c, std::span<const double>(yy.data(), n),
            std::span<const double>(yy.data() + n, n), std::span<double>(out.data(), n),
            std::span<double>(out.data() + n, n));
    return out;
  };
  std::vector<double> jac(static_cast<std::size_t>(nv) * nv);
  CellCoefficients c = coefficients(y);
  strip(c);
  eng.jacobian(c, std::span<const double>(y.data(), n),
               std::span<const double>(y.data() + n, n), jac);
  const FdComparison d = compare_with_differences(f, jac, std::move(y), true);
  std::printf("full Jacobian error %.2e\n", d.err / d.max_fd);
  return d.err / d.max_fd;
}

//! |sum_k d sigma_k| / sum_k |d sigma_k| and the same for psi.
inline std::pair<double, double> imbalance(const Smoluchowski& eng,
                                           const CellCoefficients& c,
                                           const std::vector<double>& sigma,
                                           const std::vector<double>& psi) {
  const int n = eng.size();
  std::vector<double> ds(n), dp(psi.empty() ? 0 : n);
  eng.rhs(c, sigma, psi, ds, dp);
  double s = 0.0, a = 0.0, sp = 0.0, ap = 0.0;
  for (int k = 0; k < n; ++k) {
    s += ds[k];
    a += std::abs(ds[k]);
    if (!psi.empty()) {
      sp += dp[k];
      ap += std::abs(dp[k]);
    }
  }
  return {std::abs(s) / a, psi.empty() ? 0.0 : std::abs(sp) / ap};
}

//! sum_k dpsi_k/dt and sum_k |dpsi_k/dt| of the engine's right-hand side [g cm^-2 s^-1].
struct VolumeRates {
  double sum = 0.0, abs = 0.0;
};
inline VolumeRates volume_rates(const Smoluchowski& eng, const CellCoefficients& c,
                                const std::vector<double>& sigma,
                                const std::vector<double>& psi) {
  const int n = eng.size();
  std::vector<double> ds(n), dp(n);
  eng.rhs(c, sigma, psi, ds, dp);
  VolumeRates r;
  for (double v : dp) {
    r.sum += v;
    r.abs += std::abs(v);
  }
  return r;
}

//! G - 1, G the factor by which the two-bin split of the sticking product of bins a >=
//! b multiplies its volume (smoluchowski.hpp): the product m_p = m_a + m_b goes to the
//! bins k, k + 1 around it as eps m_k and (1 - eps) m_{k+1} (the split that conserves
//! mass and number), and each part's volume is extended along the product's step to its
//! bin's mass by (m_bin / m_p)^s, s = d / ln(m_p / m_a) bounded to |s| <=
//! kMaxSplitSlope. Written from the grid and these formulas alone, without cancelling
//! terms where m_p rounds to m_a (k = a: the mass fraction that moves up is m_b m_{a+1}
//! / (Delta m_p), Brauer et al. 2008 A.2).
inline double split_factor_minus_one(const std::vector<double>& m, int a, int b,
                                     double d) {
  const double mp = m[a] + m[b];
  int k = static_cast<int>(std::upper_bound(m.begin(), m.end(), mp) - m.begin()) - 1;
  k = std::max(k, a);
  const double ln_step = std::log1p(m[b] / m[a]);
  const double s = std::clamp(d / ln_step, -kMaxSplitSlope, kMaxSplitSlope);
  const double delta = m[k + 1] - m[k];
  const double up = std::exp(s * std::log(m[k + 1] / mp));
  if (k == a) {
    const double f_hi = m[b] * m[k + 1] / (delta * mp);
    return std::expm1(-s * ln_step) + f_hi * (up - std::exp(-s * ln_step));
  }
  const double eps = (m[k + 1] - mp) / delta;
  return eps * m[k] / mp * std::exp(s * std::log(m[k] / mp)) +
         (1.0 - eps) * m[k + 1] / mp * up - 1.0;
}

//! The psi a state gains by sticking alone, sum over pairs of (1 - p) R [V + (G - 1)
//! (m_a w_a + m_b w_b + V)] (products inside the grid), independently of the engine's
//! booking: the partners carry their own volumes w = psi / sigma, the voids V = m_p u_a
//! e^d - m_a u_a - m_b u_b are taken at the bins' u (bin_porosity with the
//! coefficients' empty-bin scale), G is the split's factor above.
inline double sticking_volume_gain(const Smoluchowski& eng, const CellCoefficients& c,
                                   const std::vector<double>& sigma,
                                   const std::vector<double>& psi) {
  const int n = eng.size();
  const auto& m = eng.grid().m;
  double gain = 0.0;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b <= a; ++b) {
      if (m[a] + m[b] >= m[n - 1]) continue;
      const std::size_t ab = static_cast<std::size_t>(a) * n + b;
      const double pf = c.p_frag.empty() ? 0.0 : c.p_frag[ab];
      const double r = (a == b ? 0.5 : 1.0) * c.kernel[ab] * (sigma[a] / m[a]) *
                       (sigma[b] / m[b]) * (1.0 - pf);
      const double ua = bin_porosity(sigma[a], psi[a], c.empty_scale).u;
      const double ub = bin_porosity(sigma[b], psi[b], c.empty_scale).u;
      const double d = c.ln_u_ratio[ab];
      // without the cancelling terms
      const double voids = m[a] * ua * std::expm1(d) + m[b] * (ua * std::exp(d) - ub);
      const double own = m[a] * psi[a] / sigma[a] + m[b] * psi[b] / sigma[b];
      gain += r * (voids + split_factor_minus_one(m, a, b, d) * (own + voids));
    }
  return gain;
}

}  // namespace panoptic::physics::coagulation
