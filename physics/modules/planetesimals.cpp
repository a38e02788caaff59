#include "physics/modules/planetesimals.hpp"

#include <cmath>
#include <type_traits>

#include "physics/modules/planetesimals_cell_rates.hpp"

namespace panoptic {

Planetesimals::Planetesimals(StateLayout& layout, const ParticleCodec& codec,
                             const CellGas& gas, const StokesModel& stokes,
                             const std::vector<physics::Species>& species,
                             const physics::GrowthOptions& growth,
                             PlanetesimalOptions options, double sigma_scale)
    : CellRangeForm(layout),
      PlanetesimalChannels(layout, options, sigma_scale),
      codec_(codec),
      gas_(gas),
      stokes_(stokes),
      species_(species),
      growth_(growth) {}

template <class T>
void Planetesimals::cell_rates(int cell, const T* yc, T& coag, T& si) const {
  if constexpr (!std::is_same_v<T, double>) {
    if (gas_.evolves_slot() >= 0) {
      cell_rates_ad_gas(cell, yc, coag, si);
      return;
    }
  }
  cell_rates_with(cell, yc, gas_.at(cell, yc), coag, si);
}

void Planetesimals::declare_pattern(PatternBuilder& p) const {
  const int nv = layout_.n_cell_vars();
  for (int i = 0; i < layout_.n_cells(); ++i)
    for (int row = 0; row < nv; ++row)  // sinks of Sigma_d and of every Q; the Sigma_pl
      for (int j = 0; j < nv; ++j) p.add(layout_.index(i, row), layout_.index(i, j));
}

namespace {

//! The sinks of one cell: Sigma_d and the log-moments lose Sdot (times Q/Sigma_d), the
//! channels gain it. Writes d(state)/dt into `out` (length nv).
template <class T>
void sinks(const ParticleCodec& codec, int coag_slot, int si_slot, const T* yc,
           const T& coag, const T& si, T* out, int nv) {
  for (int k = 0; k < nv; ++k) out[k] = T(0.0);
  const T total = coag + si;
  const T& sigma = yc[codec.sigma_slot];
  const double eps2 = codec.eps_sigma * codec.eps_sigma;
  out[codec.sigma_slot] = -total;
  for (int q : {codec.qm_slot, codec.qphi_slot})  // spec §6.2: -(Q/Sigma_d) Sdot
    if (q >= 0) out[q] = -(yc[q] * sigma / (sigma * sigma + eps2)) * total;
  if (coag_slot >= 0) out[coag_slot] = coag;
  if (si_slot >= 0) out[si_slot] = si;
}

}  // namespace

void Planetesimals::add_rhs_cells(double, std::span<const double> y,
                                  std::span<double> ydot, int lo, int hi) const {
  const int nv = layout_.n_cell_vars();
  double out[kMaxLocalDerivs];
  for (int i = lo; i < hi; ++i) {
    const double* yc = &y[layout_.index(i, 0)];
    double coag = 0.0, si = 0.0;
    cell_rates(i, yc, coag, si);
    sinks(codec_, coag_slot_, si_slot_, yc, coag, si, out, nv);
    for (int k = 0; k < nv; ++k) ydot[layout_.index(i, k)] += out[k];
  }
}

void Planetesimals::add_jacobian_cells(double, std::span<const double> y,
                                       JacobianValues& jac, int lo, int hi) const {
  const int nv = layout_.n_cell_vars();
  AD yc[kMaxLocalDerivs], out[kMaxLocalDerivs];
  for (int i = lo; i < hi; ++i) {
    for (int j = 0; j < nv; ++j) yc[j] = ad_seed(y[layout_.index(i, j)], j);
    AD coag, si;
    cell_rates(i, yc, coag, si);
    sinks(codec_, coag_slot_, si_slot_, yc, coag, si, out, nv);
    for (int k = 0; k < nv; ++k)
      for (int j = 0; j < nv; ++j)
        if (out[k].derivatives()[j] != 0.0)
          jac.add(layout_.index(i, k), layout_.index(i, j), out[k].derivatives()[j]);
  }
}

std::pair<double, double> Planetesimals::rates(int cell,
                                               std::span<const double> y) const {
  double coag = 0.0, si = 0.0;
  cell_rates(cell, &y[layout_.index(cell, 0)], coag, si);
  return {coag, si};
}

}  // namespace panoptic
