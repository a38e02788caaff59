#pragma once
//! Planetesimal formation per mass bin in the size-distribution mode (spec §15.4, §7):
//! the laws of physics/planetesimal_criteria.hpp applied to the bins of every cell of a
//! SizeDistribution, each bin k with its own St_k (compact, or porous through u_k =
//! psi_k/sigma_k), booked in sigma_pl_coag and sigma_pl_si as the single-size model
//! books them (PlanetesimalChannels), so that the mass budget, /summary and the
//! planetesimal fields of a distribution run read like a single-size run.
//!
//! Direct coagulation (§7.1): bin k converts at sigma_k/tau_pl W(St_k/St_pl). The
//! single-size law also asks dm/dt > 0, because its one particle per cell may sit above
//! St_pl while held by erosion or fragmentation; a bin has a fixed mass, and mass stands
//! above St_pl only as the product of growth (spec §15.4: "bins with St_k >= St_pl
//! convert"), so no growth factor is applied.
//!
//! Streaming instability (§7.2): the trigger's midplane dust-to-gas ratio counts the
//! bins with St_k >= st_si_min (smoothly, the rate's own switch W_si(St_k)), each with
//! its own scale height: eps_mid = sum_k W_si(St_k) sigma_k / (sqrt(2 pi) h_d,k rho_g)
//! (spec §15.4), of which the trigger takes the positive part as the single-size one
//! takes that of Sigma_d; the rate is the single-size law per bin with that trigger (d16:
//! zeta sigma_k Omega_K W_si(St_k); s18: zeta sigma_k St_k Omega_K), so d16 removes zeta
//! Sigma_d(St >= 0.01) Omega_K from those bins in proportion. The single-size trigger
//! counts all of its dust, whose one St the rate then switches (spec §7.2, last item):
//! for the dust in one bin where W_si = 1 to round-off (St >= 32 st_si_min at the
//! default width) both are the same operations, so the same rate (to the bit where the
//! positive parts' floors are below round-off); inside the switch's band (and for s18
//! below st_si_min) the distribution counts only the dust that St_k admits.
//! zcrit (a column metallicity against Z_crit of one St) has no per-bin form and is
//! refused with the distribution (src/model/scene_validation.cpp).
//!
//! Sinks: sigma_k loses its rate, and psi_k (porous) the same fraction, by the same
//! laws, linear in their surface density, applied to psi_k: phi_k is kept (spec §6.2).
//! St and the gas are the SizeDistribution's (the gas of its last refresh): the St of
//! the state asked, SizeDistribution::bin_stokes_numbers, computed once per state by
//! whichever of the two is evaluated first at it (this module, rank 2 < 3).
//! Jacobian: exact, each bin's laws by AD in its sigma_k, psi_k and ln phi_k (St through
//! phi by the same law, SizeDistribution::bin_stokes), the trigger's dependence on every
//! bin of the cell chained through d trigger / d rho_mid: a dense block per cell when SI
//! is on (that of the coagulation engine), each bin's own sigma_k, psi_k otherwise, and
//! the rows of sigma_pl.
#include <span>
#include <utility>
#include <vector>

#include "disk/local_gas.hpp"
#include "physics/modules/planetesimal_channels.hpp"
#include "src/solver/physics_module.hpp"
#include "src/solver/state_layout.hpp"

namespace panoptic {

class SizeDistribution;

class BinPlanetesimals : public PhysicsModule, public PlanetesimalChannels {
 public:
  //! Registers sigma_pl_coag and/or sigma_pl_si. `eps_sigma` [g cm^-2]: the smoothing of
  //! the positive part in the SI trigger (ParticleCodec::eps_sigma, as single size).
  BinPlanetesimals(StateLayout& layout, const SizeDistribution& dist,
                   PlanetesimalOptions options, double sigma_scale, double eps_sigma);

  std::string_view name() const override { return "bin_planetesimals"; }
  std::vector<OutputField> output_fields() const override {
    return channel_fields(layout_);
  }
  //! Per cell: the bins' block (dense with SI, each bin's own sigma_k, psi_k without)
  //! and the rows of sigma_pl by every bin.
  void declare_pattern(PatternBuilder& pattern) const override;
  //! Every bin's sinks, booked in sigma_pl_coag and sigma_pl_si.
  void add_rhs(double t, std::span<const double> y,
               std::span<double> ydot) const override;
  void add_jacobian(double t, std::span<const double> y,
                    JacobianValues& jac) const override;
  //! Summed over the bins of the cell.
  std::pair<double, double> rates(int cell, std::span<const double> y) const override;
  //! The sinks of every bin of a cell [g cm^-2 s^-1]: of sigma_k by each channel, and
  //! (porous) of psi_k.
  struct CellRates {
    std::vector<double> coag, si, coag_psi, si_psi;
  };
  void cell_rates(int cell, std::span<const double> y, CellRates& out) const;

 private:
  //! cell_rates with the St of the cell's bins, `st` (N values).
  void cell_rates(int cell, std::span<const double> y, std::span<const double> st,
                  CellRates& out) const;
  //! The laws of bin k of `cell` at its (sigma, psi) and Stokes number st (T: double,
  //! or AD seeded in sigma, psi and ln phi).
  template <class T>
  struct Bin {
    T st;              //!< St_k
    T coag, coag_psi;  //!< direct coagulation of sigma_k and of psi_k
    T rho_mid;         //!< SI: W_si(St_k) sigma_k / (sqrt(2 pi) h_d,k) [g cm^-3]
  };
  template <class T>
  Bin<T> bin(const T& sigma, const T& psi, const T& st, const physics::LocalGas& g) const;
  //! The SI rate of a bin of surface density `sigma` (sigma_k or psi_k) and St_k with
  //! trigger `trigger` (d16 or s18).
  template <class T>
  T si_law(const T& sigma, const T& st, double trigger, double omega_k) const;
  //! The SI trigger at the counted midplane density rho_mid [g cm^-3] and its
  //! derivative by rho_mid.
  std::pair<double, double> trigger(double rho_mid, const physics::LocalGas& g) const;
  //! The state of bin k of `cell`: {sigma_k, psi_k, phi_k} (compact: psi_k = sigma_k,
  //! phi_k = 1) and d ln phi_k / d sigma_k, d psi_k (SizeDistribution::porosity).
  struct BinState {
    double sigma, psi, phi;
    double dlnphi_dsigma = 0.0, dlnphi_dpsi = 0.0;
  };
  BinState bin_state(int cell, int k, std::span<const double> y) const;

  const StateLayout& layout_;
  const SizeDistribution& dist_;
  double eps_sigma_;
};

}  // namespace panoptic
