// The best case of local time stepping, read from a coupled run (not a test; used by
// bench_fiducial --lts and bench_porous_newton --lts). After every accepted step of size
// h and order q, block b of B neighbouring cells has its own weighted RMS norm e_b of
// CVODE's local error estimate, and so could have taken h_b = h (tol_b e / e_b)^(1/(q+1))
// alone (e: the step's global norm, so the block that limits the step gets h), capped at
// the snapshot interval; the block then needs h / h_b steps for this stretch.
// tol_b = sqrt(N / n_b) holds every block to the accuracy CVODE's global norm allowed
// the cell that limited the step (one block alone at tol_b gives e = 1); tol_b = 1 holds
// every block to that of the whole disk (stricter). Transport is in the estimate (the
// coupled run's errors contain it); what is not: the cost of coupling the blocks and of
// restarting their integrators, and step-size selection better than this extrapolation.
// A bound, not a scheme. Results: tests/bench/README.md (single size),
// tests/bench/results/porous_cost.md (size distributions).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <span>
#include <string>
#include <vector>

#include "src/solver/state_layout.hpp"

namespace panoptic::bench {

class LtsEstimate {
 public:
  // the last: one block of every cell, the coupled run itself (a check of the estimate)
  static constexpr int kBlockSizes[] = {1, 4, 16, 64, 1 << 30};
  //! Cells with Sigma_d below these fractions of the largest count as nearly empty.
  static constexpr double kEmptyBelow[] = {1e-6, 1e-3};

  explicit LtsEstimate(const StateLayout& layout) : layout_(layout) {}

  //! One accepted step: weighted local errors |e_i w_i| of every component, the step's
  //! size and order, the snapshot interval it lies in [s], and each cell's Sigma_d after
  //! it (DustCarrier::sigma_d) [g cm^-2].
  void add(const std::vector<double>& e, double h, int q, double interval,
           std::span<const double> sigma_d) {
    const long n_all = static_cast<long>(e.size());
    double sum2 = 0.0;
    for (double x : e) sum2 += x * x;
    const double e_glob = std::sqrt(sum2 / double(n_all));
    if (!(e_glob > 0.0) || !(h > 0.0)) return;
    const int nc = layout_.n_cells(), nv = layout_.n_cell_vars();
    // One step size still, but the cells with little dust left out of the error test.
    const double sigma_max = *std::max_element(sigma_d.begin(), sigma_d.end());
    for (std::size_t k = 0; k < std::size(kEmptyBelow); ++k) {
      double s2 = sum2;
      for (int c = 0; c < nc; ++c)
        if (sigma_d[c] < kEmptyBelow[k] * sigma_max)
          for (long i = layout_.index(c, 0); i < layout_.index(c + 1, 0); ++i)
            s2 -= e[i] * e[i];
      const double e_rest = std::sqrt(std::max(s2, 0.0) / double(n_all));
      const double ratio =
          e_rest > 0.0 ? std::pow(e_glob / e_rest, 1.0 / (q + 1)) : 1e300;
      steps_without_empty_[k] += h / std::min(h * ratio, interval);
    }
    for (std::size_t k = 0; k < std::size(kBlockSizes); ++k) {
      const int bsize = kBlockSizes[k];
      for (int c0 = 0; c0 < nc; c0 += bsize) {
        const int c1 = std::min(nc, c0 + bsize);
        double s2 = 0.0;
        for (long i = layout_.index(c0, 0); i < layout_.index(c1, 0); ++i)
          s2 += e[i] * e[i];
        const double n_b = double(c1 - c0) * nv;
        const double e_b = std::sqrt(s2 / n_b);
        for (int strict = 0; strict < 2; ++strict) {
          const double tol = strict ? 1.0 : std::sqrt(double(n_all) / n_b);
          const double ratio =
              e_b > 0.0 ? std::pow(tol * e_glob / e_b, 1.0 / (q + 1)) : 1e300;
          const double h_b = std::min(h * ratio, interval);
          cell_steps_[k][strict] += (c1 - c0) * h / h_b;
        }
      }
    }
    coupled_ += nc;
  }

  void print(long steps) const {
    std::printf(
        "\nlocal time stepping, best case (--lts): cell-steps of blocks of B cells each "
        "on its own step size\n| B | cell-steps, tol_b = sqrt(N/n_b) | vs coupled | "
        "cell-steps, tol_b = 1 | vs coupled |\n|---|---|---|---|---|\n");
    std::printf("| coupled (%ld steps) | %.3g | 1 | | |\n", steps, coupled_);
    for (std::size_t k = 0; k < std::size(kBlockSizes); ++k)
      std::printf("| %s | %.3g | %.3f | %.3g | %.3f |\n",
                  kBlockSizes[k] >= layout_.n_cells()
                      ? "all"
                      : std::to_string(kBlockSizes[k]).c_str(),
                  cell_steps_[k][0], cell_steps_[k][0] / coupled_, cell_steps_[k][1],
                  cell_steps_[k][1] / coupled_);
    for (std::size_t k = 0; k < std::size(kEmptyBelow); ++k)
      std::printf(
          "one step size, cells with Sigma_d below %g of the largest left out of "
          "the error test: %.0f steps (%.3f of the run's)\n",
          kEmptyBelow[k], steps_without_empty_[k], steps_without_empty_[k] / steps);
  }

 private:
  const StateLayout& layout_;
  double cell_steps_[std::size(kBlockSizes)][2] = {};
  double coupled_ = 0.0;
  double steps_without_empty_[std::size(kEmptyBelow)] = {};
};

}  // namespace panoptic::bench
