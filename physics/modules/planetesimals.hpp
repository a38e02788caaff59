#pragma once
//! Planetesimal formation (spec §7): dust of a cell is converted into planetesimals,
//! which are not transported, by
//!   direct coagulation (§7.1): Sdot = Sigma_d / tau_pl W(St/St_pl) I(dm/dt > 0),
//!                              tau_pl = 10/Omega_K, St_pl = 10;
//!   streaming instability (§7.2), when the midplane rho_d/rho_g >= 1:
//!     d16 (Drazkowska et al. 2016, default): Sdot = zeta Sigma_d Omega_K, zeta = 0.01,
//!     for
//!         St >= 0.01;
//!     s18 (Schoonenberg, Ormel & Krijt 2018): Sdot = zeta Sigma_d St Omega_K, zeta =
//!     0.1.
//!   streaming instability, critical-metallicity option (zcrit), when the column
//!   metallicity Z = Sigma_d/Sigma_g exceeds Z_crit(St) (zcrit_lim25 below) for St >=
//!   0.01:
//!     Sdot = zeta Sigma_d Omega_K, zeta = 0.01.
//! Every threshold is a smooth step (logistic in ln x over +-0.1 dex) so CVODE's Newton
//! iteration sees no kink. The sinks conserve the particle properties: dSigma_d = -Sdot,
//! dQ = -(Q/Sigma_d) Sdot (spec §6.2). Owns one Sigma_pl variable per channel that is on.
#include "physics/modules/porous_growth.hpp"

namespace panoptic {

enum class StreamingInstability { kNone, kD16, kS18, kZcrit };

//! Critical column metallicity Z = Sigma_d/Sigma_g above which the streaming instability
//! clumps particles strongly enough to form planetesimals [-] (spec §7.2, option):
//!   log10 Z_crit = 0.10 (log10 St)^2 + 0.07 log10 St - 2.36,
//! Lim et al. 2025 (ApJ; arXiv:2410.17319) eq. 15, their revision for tau_s = St >= 0.01
//! of the Li & Youdin (2021, ApJ 919, 107) fit, for the pressure-gradient parameter
//! Pi = 0.05 and no external turbulence. The papers' full text was not reachable from
//! here; the coefficients were checked against what was: the fit's minimum, 0.43% at
//! St = 0.45, is Li & Youdin's "critical metallicity as low as 0.4% for the optimum
//! particle sizes" (Pi = 0.05); at St = 0.01 it gives 0.79%, Lim et al.'s "strong
//! clumping even at Z <~ 0.01 for tau_s = 0.01"; and a public implementation quotes the
//! same three numbers as Lim et al. 2025 eq. 15. Below St = 0.01 the fits do not apply
//! (Li & Youdin: Z_crit rises sharply), so the channel is switched off there
//! (St_si_min).
template <class T>
T zcrit_lim25(const T& st) {
  using std::exp;
  using std::log;
  const double ln10 = std::log(10.0);
  const T x = log(st) / ln10;  // log10 St
  const T log10_z = 0.10 * x * x + 0.07 * x - 2.36;
  return exp(ln10 * log10_z);
}

struct PlanetesimalOptions {
  bool coagulation = true;     //!< direct coagulation channel (spec §7.1)
  double st_pl = 10.0;         //!< St threshold of direct coagulation
  double tau_pl_omega = 10.0;  //!< tau_pl Omega_K
  StreamingInstability si = StreamingInstability::kD16;
  double zeta = 0.01;       //!< SI efficiency (d16: 0.01, s18: 0.1)
  double st_si_min = 0.01;  //!< d16: smallest St that counts
  double eps_crit = 1.0;    //!< midplane rho_d/rho_g that triggers SI
  double width_dex = 0.1;   //!< half width of the smooth thresholds [dex]
};

class Planetesimals : public PhysicsModule {
 public:
  //! Registers sigma_pl_coag and/or sigma_pl_si.
  Planetesimals(StateLayout& layout, const ParticleCodec& codec, const CellGas& gas,
                const StokesModel& stokes, const std::vector<physics::Species>& species,
                const physics::GrowthOptions& growth, PlanetesimalOptions options,
                double sigma_scale);

  std::string_view name() const override { return "planetesimals"; }
  void declare_pattern(PatternBuilder& pattern) const override;
  void add_rhs(double t, std::span<const double> y,
               std::span<double> ydot) const override;
  void add_jacobian(double t, std::span<const double> y,
                    JacobianValues& jac) const override;
  void add_rhs_cells(double t, std::span<const double> y, std::span<double> ydot, int lo,
                     int hi) const override;
  void add_jacobian_cells(double t, std::span<const double> y, JacobianValues& jac,
                          int lo, int hi) const override;

  //! Take the growth rates of the coagulation channel from the growth module's memo
  //! (same state, same options: the same numbers, computed once per RHS).
  void use_growth_rates(const PorousGrowth* growth) { growth_module_ = growth; }

  //! sigma_pl and that of each channel that is on.
  std::vector<OutputField> output_fields() const override;
  int coag_slot() const { return coag_slot_; }  //!< -1 when the channel is off
  int si_slot() const { return si_slot_; }      //!< -1 when the channel is off
  //! Conversion rates of cell `cell` at state y [g cm^-2 s^-1]: {coagulation, SI}.
  std::pair<double, double> rates(int cell, std::span<const double> y) const;

 private:
  template <class T>
  void cell_rates(int cell, const T* yc, T& coag, T& si) const;
  //! The same with the cell's gas `g` (LocalGas, or LocalGasT<AD> where Sigma_g evolves
  //! and is differentiated).
  template <class T, class G>
  void cell_rates_with(int cell, const T* yc, const physics::LocalGasT<G>& g, T& coag,
                       T& si) const;
  //! cell_rates_with on CellGas::at_ad (physics/modules/evolving_gas_ad.cpp).
  void cell_rates_ad_gas(int cell, const AD* yc, AD& coag, AD& si) const;

  const StateLayout& layout_;
  const ParticleCodec& codec_;
  const CellGas& gas_;
  const StokesModel& stokes_;
  const std::vector<physics::Species>& species_;
  physics::GrowthOptions growth_;
  PlanetesimalOptions opt_;
  int coag_slot_ = -1, si_slot_ = -1;
  const PorousGrowth* growth_module_ = nullptr;
};

}  // namespace panoptic
