#include "physics/modules/bin_planetesimals.hpp"

#include "physics/modules/size_distribution.hpp"
#include "physics/particle.hpp"
#include "physics/planetesimal_criteria.hpp"

namespace panoptic {

BinPlanetesimals::BinPlanetesimals(StateLayout& layout, const SizeDistribution& dist,
                                   PlanetesimalOptions options, double sigma_scale,
                                   double eps_sigma)
    : PlanetesimalChannels(layout, options, sigma_scale),
      layout_(layout),
      dist_(dist),
      eps_sigma_(eps_sigma) {}

BinPlanetesimals::BinState BinPlanetesimals::bin_state(int cell, int k,
                                                       std::span<const double> y) const {
  const double s = y[layout_.index(cell, dist_.bin_slot(k))];
  if (!dist_.porous()) return {s, s, 1.0};
  const auto u = dist_.porosity(cell, k, y);
  return {s, y[layout_.index(cell, dist_.psi_slot(k))], u.phi(), -u.dlnu_dsigma,
          -u.dlnu_dpsi};
}

template <class T>
BinPlanetesimals::Bin<T> BinPlanetesimals::bin(const T& sigma, const T& psi, const T& st,
                                               const physics::LocalGas& g) const {
  Bin<T> b{st, T(0.0), T(0.0), T(0.0)};
  if (opt_.coagulation) {  // spec §7.1, §15.4
    b.coag = physics::conversion_above_st_pl(sigma, b.st, g.omega_k, opt_.tau_pl_omega,
                                             opt_.st_pl, opt_.width_dex);
    b.coag_psi = physics::conversion_above_st_pl(psi, b.st, g.omega_k, opt_.tau_pl_omega,
                                                 opt_.st_pl, opt_.width_dex);
  }
  if (opt_.si != StreamingInstability::kNone) {
    // spec §7.2, §15.4: the bin's share of the midplane density, if its St counts
    const T counted = physics::log_step(b.st, opt_.st_si_min, opt_.width_dex) * sigma;
    b.rho_mid =
        physics::midplane_dust_density(counted, physics::dust_scale_height(b.st, g));
  }
  return b;
}

template <class T>
T BinPlanetesimals::si_law(const T& sigma, const T& st, double trigger,
                           double omega_k) const {
  const T on(trigger);
  if (opt_.si == StreamingInstability::kD16)
    return physics::si_conversion_d16(sigma, st, on, omega_k, opt_.zeta, opt_.st_si_min,
                                      opt_.width_dex);
  return physics::si_conversion_s18(sigma, st, on, omega_k, opt_.zeta);
}

//! The SI trigger (spec §7.2) on the summed midplane density of the counted bins, and
//! its derivative by that density. As the single-size trigger takes the positive part of
//! Sigma_d (it may dip below zero inside a Newton iteration, and the trigger takes a
//! logarithm), this one takes that of rho_mid, with the floor eps_sigma spread over the
//! gas scale height: an empty bin adds nothing.
std::pair<double, double> BinPlanetesimals::trigger(double rho_mid,
                                                    const physics::LocalGas& g) const {
  using AD1 = Eigen::AutoDiffScalar<Eigen::Matrix<double, 1, 1>>;
  const double floor = physics::midplane_dust_density(eps_sigma_, g.h_g);
  const AD1 rho_pos = physics::positive_part(ad_seed<AD1>(rho_mid, 0), floor);
  const AD1 on = physics::log_step(AD1(rho_pos / g.rho_g), opt_.eps_crit, opt_.width_dex);
  return {on.value(), on.derivatives()[0]};
}

void BinPlanetesimals::cell_rates(int cell, std::span<const double> y,
                                  CellRates& out) const {
  const int nb = dist_.n_bins();
  cell_rates(cell, y,
             dist_.bin_stokes_numbers(y).subspan(static_cast<std::size_t>(cell) * nb, nb),
             out);
}

void BinPlanetesimals::cell_rates(int cell, std::span<const double> y,
                                  std::span<const double> st, CellRates& out) const {
  const int nb = dist_.n_bins();
  const physics::LocalGas& g = dist_.bin_gas(cell);
  for (auto* v : {&out.coag, &out.si, &out.coag_psi, &out.si_psi}) v->assign(nb, 0.0);
  // each bin's state, read once: the SI rates below need the trigger of all bins
  std::vector<BinState> state(nb);
  double rho_mid = 0.0;
  for (int k = 0; k < nb; ++k) {
    state[k] = bin_state(cell, k, y);
    const BinState& v = state[k];
    const Bin<double> b = bin(v.sigma, v.psi, st[k], g);
    out.coag[k] = b.coag;
    out.coag_psi[k] = b.coag_psi;
    rho_mid += b.rho_mid;
  }
  if (opt_.si == StreamingInstability::kNone) return;
  const double on = trigger(rho_mid, g).first;
  for (int k = 0; k < nb; ++k) {
    out.si[k] = si_law(state[k].sigma, st[k], on, g.omega_k);
    out.si_psi[k] = si_law(state[k].psi, st[k], on, g.omega_k);
  }
}

std::pair<double, double> BinPlanetesimals::rates(int cell,
                                                  std::span<const double> y) const {
  CellRates r;
  cell_rates(cell, y, r);
  double coag = 0.0, si = 0.0;
  for (std::size_t k = 0; k < r.coag.size(); ++k) {
    coag += r.coag[k];
    si += r.si[k];
  }
  return {coag, si};
}

void BinPlanetesimals::declare_pattern(PatternBuilder& p) const {
  const int nb = dist_.n_bins(), nv = dist_.cell_vars();
  const bool si = si_slot_ >= 0;
  for (int i = 0; i < layout_.n_cells(); ++i) {
    const long base = layout_.index(i, dist_.bin_slot(0));
    for (int r = 0; r < nv; ++r)
      for (int c = 0; c < nv; ++c)
        // SI: every bin's rate reads the trigger, which reads every bin; coagulation
        // alone: sigma_k and psi_k of the bin itself
        if (si || r % nb == c % nb) p.add(base + r, base + c);
    for (int slot : {coag_slot_, si_slot_})
      for (int c = 0; slot >= 0 && c < nv; ++c) p.add(layout_.index(i, slot), base + c);
  }
}

void BinPlanetesimals::add_rhs(double, std::span<const double> y,
                               std::span<double> ydot) const {
  CellRates r;
  const std::span<const double> st = dist_.bin_stokes_numbers(y);
  const auto nb = static_cast<std::size_t>(dist_.n_bins());
  for (int i = 0; i < layout_.n_cells(); ++i) {
    cell_rates(i, y, st.subspan(static_cast<std::size_t>(i) * nb, nb), r);
    double booked_coag = 0.0, booked_si = 0.0;
    for (int k = 0; k < dist_.n_bins(); ++k) {
      ydot[layout_.index(i, dist_.bin_slot(k))] -= r.coag[k] + r.si[k];
      // psi_k loses the same fraction: the same laws on psi_k
      if (dist_.porous())
        ydot[layout_.index(i, dist_.psi_slot(k))] -= r.coag_psi[k] + r.si_psi[k];
      booked_coag += r.coag[k];
      booked_si += r.si[k];
    }
    if (coag_slot_ >= 0) ydot[layout_.index(i, coag_slot_)] += booked_coag;
    if (si_slot_ >= 0) ydot[layout_.index(i, si_slot_)] += booked_si;
  }
}

void BinPlanetesimals::add_jacobian(double, std::span<const double> y,
                                    JacobianValues& jac) const {
  const int nb = dist_.n_bins();
  const bool porous = dist_.porous(), si_on = si_slot_ >= 0;
  std::vector<BinState> state(nb);
  std::vector<Bin<ADCell>> bins(nb);
  std::vector<ADCell> sig(nb), psi(nb);
  // d (SI rate of sigma_k, of psi_k) / d trigger: the laws are linear in the trigger
  std::vector<double> dsi_dtrigger(nb), dsi_psi_dtrigger(nb);
  for (int i = 0; i < layout_.n_cells(); ++i) {
    const physics::LocalGas& g = dist_.bin_gas(i);
    // J(row, bin k) += scale dv/d(sigma_k, psi_k), v in bin k's directions: 0 and 1 its
    // sigma_k and psi_k where a law is linear in them, 2 ln phi_k (through St_k),
    // chained to sigma_k and psi_k by the derivatives of SizeDistribution::porosity
    // (bounded in nearly empty bins).
    const auto add = [&](long row, int k, const ADCell& v, double scale) {
      const BinState& b = state[k];
      const double d_lnphi = v.derivatives()[2];
      const double d_sigma = v.derivatives()[0] + d_lnphi * b.dlnphi_dsigma;
      const double d_psi = v.derivatives()[1] + d_lnphi * b.dlnphi_dpsi;
      if (d_sigma != 0.0)
        jac.add(row, layout_.index(i, dist_.bin_slot(k)), scale * d_sigma);
      if (porous && d_psi != 0.0)
        jac.add(row, layout_.index(i, dist_.psi_slot(k)), scale * d_psi);
    };
    double rho_mid = 0.0;
    for (int k = 0; k < nb; ++k) {
      state[k] = bin_state(i, k, y);
      const BinState& v = state[k];
      sig[k] = ad_seed<ADCell>(v.sigma, 0);
      psi[k] = ad_seed<ADCell>(v.psi, 1);
      // phi follows the state by SizeDistribution::porosity (its derivatives in add)
      ADCell phi(v.phi);
      if (porous) phi.derivatives()[2] = v.phi;
      bins[k] = bin(sig[k], psi[k], dist_.bin_stokes(i, k, phi), g);
      rho_mid += bins[k].rho_mid.value();
    }
    const auto [on, don_drho] =
        si_on ? trigger(rho_mid, g) : std::pair<double, double>{0.0, 0.0};
    double dtotal_dtrigger = 0.0;  // d (sum_k SI rate of sigma_k) / d trigger
    for (int k = 0; k < nb; ++k) {
      const Bin<ADCell>& b = bins[k];
      const long row = layout_.index(i, dist_.bin_slot(k));
      ADCell loss = b.coag, loss_psi = b.coag_psi;
      if (si_on) {
        const ADCell si = si_law(sig[k], b.st, on, g.omega_k);
        loss += si;
        loss_psi += si_law(psi[k], b.st, on, g.omega_k);
        add(layout_.index(i, si_slot_), k, si, 1.0);
        dsi_dtrigger[k] = si_law(state[k].sigma, b.st.value(), 1.0, g.omega_k);
        dsi_psi_dtrigger[k] = si_law(state[k].psi, b.st.value(), 1.0, g.omega_k);
        dtotal_dtrigger += dsi_dtrigger[k];
      }
      add(row, k, loss, -1.0);
      if (porous) add(layout_.index(i, dist_.psi_slot(k)), k, loss_psi, -1.0);
      if (coag_slot_ >= 0) add(layout_.index(i, coag_slot_), k, b.coag, 1.0);
    }
    if (!si_on || don_drho == 0.0) continue;
    // the trigger reads every bin j: d trigger / d y_j = d trigger / d rho_mid d
    // rho_mid,j / d y_j, onto every row that carries the trigger
    const double dtrigger_drho = don_drho;
    for (int j = 0; j < nb; ++j) {
      const ADCell& rho_j = bins[j].rho_mid;
      add(layout_.index(i, si_slot_), j, rho_j, dtrigger_drho * dtotal_dtrigger);
      for (int k = 0; k < nb; ++k) {
        if (dsi_dtrigger[k] != 0.0)
          add(layout_.index(i, dist_.bin_slot(k)), j, rho_j,
              -dtrigger_drho * dsi_dtrigger[k]);
        if (porous && dsi_psi_dtrigger[k] != 0.0)
          add(layout_.index(i, dist_.psi_slot(k)), j, rho_j,
              -dtrigger_drho * dsi_psi_dtrigger[k]);
      }
    }
  }
}

}  // namespace panoptic
