//! Cost of the one-cell coagulation engine (physics/coagulation, spec §15) at DustPy's
//! resolution, 120 bins (1e-12 ... 1e5 g, 7 per decade), compact and porous: one
//! right-hand side, one dense analytic Jacobian, one rebuild of the cell's coefficients
//! (kernel, pair speeds, fragmentation probabilities, product porosity, floors; for the
//! porous Jacobian also their derivatives by the porosity) and one dense LU of the Newton
//! matrix, to plan the disk-wide solver of issue 35 (100 cells x 120 bins x 2); last,
//! porous with the upper half of the bins empty (compact, u = 1: their pairs from the
//! CompactPairTable), as a disk's cells early in a run. Results:
//! tests/bench/results/coagulation_cell.md, tests/bench/results/porous_cost.md.
//!   build/tests/bench_coagulation [repeats [variant]]   (variant 0-3: that row only)
#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <utility>
#include <vector>

#include "physics/coagulation/cell_coefficients.hpp"
#include "physics/coagulation/mass_grid.hpp"
#include "physics/coagulation/smoluchowski.hpp"
#include "physics/contact_mechanics.hpp"
#include "physics/particle.hpp"
#include "tests/unit/support/ice_cell_model.hpp"
#include "tests/unit/support/mmsn_gas.hpp"

using namespace panoptic::physics;
using namespace panoptic::physics::coagulation;

namespace {

//! Median wall time of `f` over `repeats` calls [s].
double time_it(int repeats, const std::function<void()>& f) {
  std::vector<double> t(repeats);
  for (int r = 0; r < repeats; ++r) {
    const auto a = std::chrono::steady_clock::now();
    f();
    const auto b = std::chrono::steady_clock::now();
    t[r] = std::chrono::duration<double>(b - a).count();
  }
  std::sort(t.begin(), t.end());
  return t[repeats / 2];
}

}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::atoi(argv[1]) : 50;
  const int only = argc > 2 ? std::atoi(argv[2]) : -1;
  const LocalGas gas = mmsn_gas(5.0);
  const CellModel model = panoptic::testing::ice_cell_model(
      {.fragmentation = true, .cratering = true, .v_frag = 100.0, .v_eros = 100.0});
  const Smoluchowski eng(MassGrid(1e-12, 1e5, 7.0));
  const int n = eng.size();
  std::vector<double> sigma_full(n), psi(n);
  for (int k = 0; k < n; ++k) {
    sigma_full[k] = 1e-3 * std::pow(eng.grid().m[k] / 1e-12, 1.0 / 6.0) *
                    std::exp(-eng.grid().m[k] / 1e2);
    psi[k] = sigma_full[k] * std::exp(0.05 * k);
  }
  std::printf(
      "| cell | bins | unknowns | coefficients [us] | RHS [us] | Jacobian [us] | dense "
      "LU [us] |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  // the upper half of the bins empty
  std::vector<double> sigma_half(sigma_full), psi_half(psi);
  std::fill(sigma_half.begin() + n / 2, sigma_half.end(), 0.0);
  std::fill(psi_half.begin() + n / 2, psi_half.end(), 0.0);
  // compact, porous, porous + derivatives, porous with the upper half empty
  for (const int variant : {0, 1, 2, 3}) {
    if (only >= 0 && variant != only) continue;
    const bool porous = variant > 0, derivatives = variant == 2;
    const bool half = variant == 3;
    const std::span<const double> p = !porous ? std::span<const double>()
                                      : half  ? std::span<const double>(psi_half)
                                              : std::span<const double>(psi);
    const std::vector<double>& sigma = half ? sigma_half : sigma_full;
    const int nv = porous ? 2 * n : n;
    // as the distribution mode calls it: the cell's workspace and coefficients reused
    CoefficientWorkspace ws;
    CellCoefficients c = cell_coefficients(eng, sigma, p, gas, model, derivatives, &ws);
    std::vector<double> ds(n), dp(porous ? n : 0), jac(static_cast<std::size_t>(nv) * nv);
    const double t_coef = time_it(std::max(3, repeats / 10), [&] {
      c = cell_coefficients(eng, sigma, p, gas, model, derivatives, &ws, std::move(c));
    });
    const double t_rhs = time_it(repeats, [&] { eng.rhs(c, sigma, p, ds, dp); });
    const double t_jac = time_it(repeats, [&] { eng.jacobian(c, sigma, p, jac); });
    // the Newton matrix I - gamma J of one cell, factorised densely
    Eigen::MatrixXd a(nv, nv);
    for (int r = 0; r < nv; ++r)
      for (int q = 0; q < nv; ++q)
        a(r, q) = (r == q ? 1.0 : 0.0) - 1e3 * jac[static_cast<std::size_t>(r) * nv + q];
    Eigen::PartialPivLU<Eigen::MatrixXd> lu(nv);
    const double t_lu = time_it(repeats, [&] { lu.compute(a); });
    std::printf("| %s | %d | %d | %.0f | %.0f | %.0f | %.0f |\n",
                variant == 0   ? "compact"
                : variant == 1 ? "porous"
                : variant == 2 ? "porous, d/d ln u"
                               : "porous, upper half empty",
                n, nv, 1e6 * t_coef, 1e6 * t_rhs, 1e6 * t_jac, 1e6 * t_lu);
  }
  return 0;
}
