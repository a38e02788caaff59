#pragma once
//! The pair coefficients of a cell's compact bins (u = 1, phi = 1) for its gas: a porous
//! cell whose bins i and j both have u = 1 exactly (bin_porosity: empty bins, and bins
//! whose |psi| does not exceed |sigma|) has the pair speed, kernel, loss probability
//! (spec §3, §15.2) and product porosity (spec §15.3) of the compact cell, which depend
//! only on the gas, the grid and the model. CompactPairTable keeps them while the gas
//! stays the same, computed by the functions of cell_coefficients on the compact bins,
//! so that a pair read from it has the bits the pair's own evaluation would give. Early
//! in a run most of a disk's pairs are of two compact bins, the nearly empty bins above
//! the growth front (the DustPy default disk porous at 30 yr: 69 %;
//! tests/bench/results/porous_cost.md).
#include <algorithm>
#include <cstddef>
#include <cstring>
#include <span>
#include <type_traits>
#include <vector>

#include "disk/local_gas.hpp"
#include "physics/coagulation/collision_kernel.hpp"
#include "physics/coagulation/mass_grid.hpp"
#include "physics/coagulation/pair_speed_evaluator.hpp"
#include "physics/coagulation/porosity.hpp"
#include "physics/drag.hpp"
#include "physics/relative_velocity.hpp"

namespace panoptic::physics::coagulation {

//! A pair's speed [cm s^-1], kernel [cm^2 s^-1] and loss probability [-].
struct PairRates {
  double dv = 0.0;
  double kernel = 0.0;
  double p_loss = 0.0;  //!< 0 where the switches have no losses
};

//! PairRates of bins i and j (spec §3, §15.2) from their properties and speed terms on
//! the evaluator `speeds` (set to the cell's gas); `crater`: the pair is more than the
//! engine's crater_bins() bins apart; `losses`: fragmentation or cratering is on.
inline PairRates pair_rates(const PairSpeedEvaluator& speeds, const BinProperties& bins,
                            std::span<const BinSpeedTerms> terms, int i, int j,
                            bool crater, const OutcomeSwitches& s, bool losses) {
  const double v = speeds.dv(terms[i], terms[j], i, j);  // spec §3
  const double k = pair_kernel(bins.a[i], bins.a[j], bins.h_d[i], bins.h_d[j], v);
  return {v, k, losses ? pair_loss_probability(v, crater, s) : 0.0};
}

//! Everything besides the grid that the compact pairs' coefficients depend on.
struct CompactTableKey {
  LocalGas gas;
  double rho0 = 0.0;         //!< monomer density [g cm^-3]
  double e_threshold = 0.0;  //!< 3 b E_roll (spec §4.2) [erg]
  DragLaw drag = DragLaw::kStokesRe;
  TurbulenceModel turbulence;
  OutcomeSwitches outcomes;
  int crater_bins = 0;  //!< Smoluchowski::crater_bins() [-]
};

//! Whether two keys are the same to the bit (the gas field by field: a field added to
//! LocalGas or to the switches fails the size checks until it is compared here).
inline bool same_key(const CompactTableKey& a, const CompactTableKey& b) {
  static_assert(std::is_trivially_copyable_v<LocalGas> &&
                sizeof(LocalGas) == 13 * sizeof(double));
  static_assert(sizeof(TurbulenceModel) == 3 * sizeof(double));
  static_assert(sizeof(OutcomeSwitches) == 4 * sizeof(double));
  const auto bits = [](const auto& x, const auto& y) {
    return std::memcmp(&x, &y, sizeof(x)) == 0;
  };
  const OutcomeSwitches &s = a.outcomes, &t = b.outcomes;
  return bits(a.gas, b.gas) && bits(a.rho0, b.rho0) &&
         bits(a.e_threshold, b.e_threshold) && a.drag == b.drag &&
         bits(a.turbulence, b.turbulence) && s.fragmentation == t.fragmentation &&
         s.cratering == t.cratering && bits(s.v_frag, t.v_frag) &&
         bits(s.v_eros, t.v_eros) && bits(s.w_eros, t.w_eros) &&
         a.crater_bins == b.crater_bins;
}

//! The coefficients of every pair of a cell's grid with both bins compact, kept while
//! the grid and the key stay the same.
class CompactPairTable {
 public:
  //! Builds the table for the grid `grid` with pair mass terms `masses` (at i N + j, j
  //! <= i) and the key `key`, unless it holds them; `speeds` is set to key.gas and the
  //! grid's masses.
  [[gnu::noinline]] void set(const MassGrid& grid, std::span<const PairMasses> masses,
                             const PairSpeedEvaluator& speeds,
                             const CompactTableKey& key) {
    const std::vector<double>& m = grid.m;
    if (built_ && same_key(key, key_) && std::ranges::equal(m, m_)) return;
    built_ = true;
    key_ = key;
    m_.assign(m.begin(), m.end());
    const int n = static_cast<int>(m.size());
    const std::vector<double> phi(n, 1.0);
    BinProperties bins;
    bin_properties(grid, phi, key.rho0, key.gas, key.drag, bins);
    std::vector<BinSpeedTerms> terms(n);
    for (int k = 0; k < n; ++k) terms[k] = speeds.bin_terms(bins.St[k]);
    const OutcomeSwitches& s = key.outcomes;
    const bool losses = s.fragmentation || s.cratering;
    rates_.resize(static_cast<std::size_t>(n) * (n + 1) / 2);
    ln_u_ratio_.resize(rates_.size());
    for (int i = 0; i < n; ++i) {
      const double s_c = compression_slope_of_target(bins.a[i], bins.St[i], key.gas,
                                                     key.drag);  // spec §4.3
      for (int j = 0; j <= i; ++j) {
        const std::size_t p = index(i, j);
        rates_[p] =
            pair_rates(speeds, bins, terms, i, j, i - j > key.crater_bins, s, losses);
        const PairMasses& pm = masses[static_cast<std::size_t>(i) * n + j];
        ln_u_ratio_[p] = product_ln_u_ratio(pm, 1.0, 1.0, impact_energy(pm, rates_[p].dv),
                                            key.e_threshold, s_c);  // spec §15.3
      }
    }
  }

  //! The pairs (i, j) and (j, i) of two bins that are `compact` (per bin: u = 1) into
  //! the N x N row-major pair speeds dv [cm s^-1], kernel [cm^2 s^-1] and loss
  //! probabilities p_loss [-] (left alone if empty), sized by the caller.
  [[gnu::noinline]] void fill_rates(std::span<const char> compact, std::span<double> dv,
                                    std::span<double> kernel,
                                    std::span<double> p_loss) const {
    for_compact_pairs(compact, [&](std::size_t p, std::size_t ij, std::size_t ji) {
      dv[ij] = dv[ji] = rates_[p].dv;
      kernel[ij] = kernel[ji] = rates_[p].kernel;
      if (!p_loss.empty()) p_loss[ij] = p_loss[ji] = rates_[p].p_loss;
    });
  }

  //! ln(u_p / u_i) of the products of two `compact` bins i >= j (product_ln_u_ratio) into
  //! the N x N row-major ln_u_ratio at (i, j) [-].
  [[gnu::noinline]] void fill_ln_u_ratio(std::span<const char> compact,
                                         std::span<double> ln_u_ratio) const {
    for_compact_pairs(compact, [&](std::size_t p, std::size_t ij, std::size_t) {
      ln_u_ratio[ij] = ln_u_ratio_[p];
    });
  }

 private:
  static std::size_t index(int i, int j) {
    return static_cast<std::size_t>(i) * (i + 1) / 2 + j;
  }

  //! f(p, ij, ji) for each pair i >= j of two compact bins: its index in the table and
  //! in an N x N row-major matrix.
  template <class F>
  static void for_compact_pairs(std::span<const char> compact, F f) {
    const std::size_t n = compact.size();
    for (std::size_t i = 0; i < n; ++i) {
      if (!compact[i]) continue;
      for (std::size_t j = 0; j <= i; ++j)
        if (compact[j]) f(index(i, j), i * n + j, j * n + i);
    }
  }

  bool built_ = false;
  CompactTableKey key_;
  std::vector<double> m_;
  std::vector<PairRates> rates_;
  std::vector<double> ln_u_ratio_;
};

}  // namespace panoptic::physics::coagulation
