#include "physics/planetesimals.hpp"

#include <cmath>
#include <type_traits>

namespace panoptic {

Planetesimals::Planetesimals(StateLayout& layout, const ParticleCodec& codec,
                             const CellGas& gas, const StokesModel& stokes,
                             const std::vector<physics::Species>& species,
                             const physics::GrowthOptions& growth,
                             PlanetesimalOptions options, double sigma_scale)
    : layout_(layout),
      codec_(codec),
      gas_(gas),
      stokes_(stokes),
      species_(species),
      growth_(growth),
      opt_(options) {
  // Sigma_pl only books what the channels convert (no right-hand side reads it back): a
  // quadrature, left out of CVODE's error test (VarInfo::error_test). Its absolute
  // tolerance used to be 1e-8 of the largest initial Sigma_d (1e4 x Sigma_d's; before
  // that Sigma_d's own, which cost 15% of the fiducial steps); out of the error test the
  // fiducial run takes 5-7% fewer steps, its outcomes move by < 1e-4 relative (as much
  // as a change of round-off does) and the dust budget still closes to round-off
  // (tests/bench/results/performance_log.md). Nor does it carry CVODE's non-negativity
  // constraint: with no error weight, CVODE would clip any negative excursion to zero
  // without limit (its constraint correction is accepted when small in the weighted
  // norm), and each clip loses mass from the budget (2.4e-8 at rtol 1e-2 on fiducial
  // before this). Sigma_pl dips below zero only where Sigma_d itself sits within its
  // tolerance of zero.
  if (opt_.coagulation)
    coag_slot_ =
        layout.add_cell_var({"sigma_pl_coag", "g cm^-2",
                             "planetesimals formed by direct coagulation (spec §7.1)",
                             sigma_scale, false, false});
  if (opt_.si != StreamingInstability::kNone)
    si_slot_ = layout.add_cell_var({"sigma_pl_si", "g cm^-2",
                                    "planetesimals formed by the streaming instability "
                                    "(spec §7.2)",
                                    sigma_scale, false, false});
}

template <class T>
void Planetesimals::cell_rates(int cell, const T* yc, T& coag, T& si) const {
  const physics::LocalGas g = gas_.at(cell, yc);
  const T& sigma = yc[codec_.sigma_slot];
  const T st = stokes_.St(cell, yc);
  coag = T(0.0);
  si = T(0.0);
  if (opt_.coagulation) {
    // spec §7.1: St >= St_pl while the particle still grows
    T dlnm_dt;
    if (growth_module_) {
      if constexpr (std::is_same_v<T, double>) {
        dlnm_dt = growth_module_->cell_rates(cell, yc).dlnm_dt;
      } else {
        T unused;
        growth_module_->rates_ad(cell, yc, dlnm_dt, unused);
      }
    } else {
      dlnm_dt = physics::particle_rates(sigma, codec_.mass(cell, yc), codec_.phi(yc), st,
                                        g, species_[cell], growth_)
                    .dlnm_dt;
    }
    const double tau_pl = opt_.tau_pl_omega / g.omega_k;
    // dm/dt > 0, smoothly: on while the particle e-folds its mass within 1e9 / Omega (a
    // particle held by erosion or fragmentation grows far slower than that)
    const T growing = physics::tanh_step<T>(1e9 / g.omega_k * dlnm_dt);
    coag = sigma / tau_pl * physics::log_step(st, opt_.st_pl, opt_.width_dex) * growing;
  }
  if (opt_.si == StreamingInstability::kNone) return;
  // Sigma_d may dip below zero inside a Newton iteration where the dust is converted
  // away; the triggers take the log of Sigma_d, so they see a positive part.
  const T sigma_pos = physics::positive_part<T>(sigma, codec_.eps_sigma);
  if (opt_.si == StreamingInstability::kZcrit) {
    // spec §7.2 option: Z / Z_crit(St) >= 1 for St >= St_si_min (zcrit_lim25)
    const T z_ratio = sigma_pos / (g.sigma_g * zcrit_lim25(st));
    si = opt_.zeta * sigma * g.omega_k * physics::log_step(z_ratio, 1.0, opt_.width_dex) *
         physics::log_step(st, opt_.st_si_min, opt_.width_dex);
    return;
  }
  // spec §7.2: midplane rho_d/rho_g >= 1 (spec §2: rho_d = Sigma_d/(sqrt(2 pi) h_d))
  const T h_d = physics::dust_scale_height(st, g);
  const T eps_mid = physics::midplane_dust_to_gas(sigma_pos, h_d, g);
  const T trigger = physics::log_step(eps_mid, opt_.eps_crit, opt_.width_dex);
  if (opt_.si == StreamingInstability::kD16)  // Drazkowska et al. 2016
    si = opt_.zeta * sigma * g.omega_k * trigger *
         physics::log_step(st, opt_.st_si_min, opt_.width_dex);
  else  // Schoonenberg, Ormel & Krijt 2018
    si = opt_.zeta * sigma * st * g.omega_k * trigger;
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

void Planetesimals::add_rhs(double, std::span<const double> y,
                            std::span<double> ydot) const {
  const int nv = layout_.n_cell_vars();
  double out[kMaxLocalDerivs];
  for (int i = 0; i < layout_.n_cells(); ++i) {
    const double* yc = &y[layout_.index(i, 0)];
    double coag = 0.0, si = 0.0;
    cell_rates(i, yc, coag, si);
    sinks(codec_, coag_slot_, si_slot_, yc, coag, si, out, nv);
    for (int k = 0; k < nv; ++k) ydot[layout_.index(i, k)] += out[k];
  }
}

void Planetesimals::add_jacobian(double, std::span<const double> y,
                                 JacobianValues& jac) const {
  const int nv = layout_.n_cell_vars();
  AD yc[kMaxLocalDerivs], out[kMaxLocalDerivs];
  for (int i = 0; i < layout_.n_cells(); ++i) {
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
