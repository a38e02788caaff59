#pragma once
//! The porous growth model on the grid (spec §4-§6.2): the mass m and filling factor phi
//! of the mass-dominating particle of every cell, carried as the conservative
//! log-moments Q_m = Sigma_d ln(m/m_ref) and Q_phi = Sigma_d ln(1/phi) (spec §6.2). Their
//! transport is the dust transport's (they are its passengers); this module adds the
//! local sources
//!   dQ_m/dt   = Sigma_d d ln m/dt,      dQ_phi/dt = -Sigma_d d ln phi/dt,
//! with the rates of physics/growth_rates.hpp. Cell Jacobian blocks: exact, by AD, in
//! Sigma_d, Q_m, Q_phi and (gas.evolve) Sigma_g.
//! Owns Q_m (growth.enabled) and Q_phi (porosity.enabled).
#include <array>
#include <memory>
#include <span>
#include <vector>

#include "disk/gas_column.hpp"
#include "physics/growth_rates.hpp"
#include "physics/modules/cell_range_form.hpp"
#include "physics/stokes_model.hpp"
#include "src/solver/state_layout.hpp"

namespace panoptic {

//! Reads m and phi of a cell from its state (Sigma_d, Q_m, Q_phi), safely: where Sigma_d
//! is near zero the ratios Q/Sigma_d are dominated by integration error, so they are
//! taken as Q Sigma/(Sigma^2 + eps^2) (-> monomers when there is no dust) and softly
//! clamped to m_species_0 <= m <= m_ref e^x_max and 1e-10 <= phi <= 1. The log-moments
//! themselves carry no positivity constraint: the clamps keep every decoded value
//! physical, so CVODE need not reject steps for them.
struct ParticleCodec {
  int sigma_slot = -1, qm_slot = -1, qphi_slot = -1;
  double m_ref = 0.0;         //!< mass unit of Q_m [g]
  double eps_sigma = 1e-300;  //!< Sigma_d below which the dust counts as monomers
  double x_max = 120.0;       //!< largest ln(m/m_ref)
  double y_max = 23.0;        //!< largest ln(1/phi): phi >= 1e-10
  std::vector<double> x_lo;   //!< per cell: ln(m0_species/m_ref)

  template <class T>
  T ln_mass_ratio(int cell, const T* yc) const;  //!< ln(m/m_ref)
  template <class T>
  T mass(int cell, const T* yc) const;  //!< m [g]
  template <class T>
  T phi(const T* yc) const;  //!< filling factor
};

//! The local gas of every cell for the particle laws. Where the gas evolves, its
//! density-dependent quantities (density, mean free path, molecular viscosity) follow the
//! cell's Sigma_g at every evaluation, and its pressure-gradient parameter eta and radial
//! velocity v_r_gas, which depend on the neighbours' Sigma_g, are set from the state at
//! every snapshot (set_pressure_and_flow, from Simulation::refresh_local_gas): between
//! snapshots they stay fixed, so that each cell's particle laws stay local in the
//! Jacobian (tests/README.md, "What works": what an instantaneous eta would change).
class CellGas {
 public:
  CellGas(std::vector<physics::LocalGas> reference, const GasColumn& gas)
      : reference_(std::move(reference)), gas_(gas) {}
  //! The gas of `cell` whose state is `yc`, read at its value (the RHS, and static gas).
  template <class T>
  physics::LocalGas at(int cell, const T* yc) const {
    if (!gas_.evolves()) return reference_[cell];
    // Density-dependent quantities follow the evolving Sigma_g (spec §1.3, §1.6); eta
    // and v_r_gas are those of the last snapshot (set_pressure_and_flow).
    return physics::with_density_ratio(
        reference_[cell], value_of(yc[gas_.slot]) / reference_[cell].sigma_g);
  }
  //! The same with the density-dependent quantities as functions of Sigma_g (AD), for
  //! Jacobians of cells whose gas evolves (call only then).
  physics::LocalGasT<AD> at_ad(int cell, const AD* yc) const;
  //! The gas the cell's particle laws start from: its density-dependent quantities at
  //! the initial Sigma_g (scaled by at()), eta and v_r_gas of the last refresh.
  const physics::LocalGas& reference(int cell) const { return reference_[cell]; }
  //! Sets eta [-] and v_r_gas [cm s^-1] of every cell (spec §1.4; §3 item 2); the
  //! density-dependent quantities keep their reference at the initial Sigma_g.
  void set_pressure_and_flow(std::span<const double> eta,
                             std::span<const double> v_r_gas) {
    for (std::size_t i = 0; i < reference_.size(); ++i) {
      reference_[i].eta = eta[i];
      reference_[i].v_r_gas = v_r_gas[i];
    }
  }
  //! Slot of Sigma_g in the cell state, or -1 for static gas.
  int evolves_slot() const { return gas_.slot; }

 private:
  std::vector<physics::LocalGas> reference_;
  const GasColumn& gas_;
};

//! St of the particles in a cell from its state (spec §2).
class GrowthStokes : public StokesModel {
 public:
  GrowthStokes(const ParticleCodec& codec, const CellGas& gas,
               const std::vector<physics::Species>& species, physics::DragLaw law)
      : codec_(codec), gas_(gas), species_(species), law_(law) {}
  //! Cached per cell: within one RHS evaluation the transport asks for each cell's St
  //! twice and the growth rates once; the cache is keyed by the cell's state values.
  double St(int cell, const double* ycell) const override;
  //! m, phi, radius and St of a cell, cached together: the growth rates of the same
  //! state reuse the decoded m and phi and the radius (two exp and a cbrt per cell and
  //! RHS) instead of computing them again.
  struct Particle {
    double m = 0.0, phi = 0.0, a = 0.0, st = 0.0;
  };
  const Particle& particle(int cell, const double* ycell) const;
  //! The same for the Jacobian: St and its gradient with respect to (Sigma_d, Q_m,
  //! Q_phi) are computed once per cell state and chained onto the caller's seeds
  //! (ad_chain), instead of one AD Newton solve per use (four per cell and Jacobian).
  AD St(int cell, const AD* ycell) const override;
  //! Empties the caches: the gas they were computed with has changed
  //! (CellGas::set_pressure_and_flow).
  void forget() const {
    cache_key_.clear();
    cache_.clear();
    ad_cache_.clear();
  }
  //! The same chained onto ADCell seeds (the growth rates' own Jacobian, static gas).
  ADCell St(int cell, const ADCell* ycell) const;

 private:
  template <class A>
  A st_chained(int cell, const A* ycell) const;
  static constexpr int kKey = 4;
  mutable std::vector<std::array<double, kKey>> cache_key_;
  mutable std::vector<Particle> cache_;
  struct AdEntry {
    std::array<double, kKey> key{-1.0, -1.0, -1.0, -1.0};
    double st = 0.0;
    std::array<double, 4> grad{};  // d St / d (Sigma_d, Q_m, Q_phi, Sigma_g)
  };
  mutable std::vector<AdEntry> ad_cache_;
  const ParticleCodec& codec_;
  const CellGas& gas_;
  const std::vector<physics::Species>& species_;
  physics::DragLaw law_;
};

class PorousGrowth : public CellRangeForm<PorousGrowth> {
 public:
  //! Registers Q_m and, with porosity, Q_phi; fills their slots into `codec`.
  PorousGrowth(StateLayout& layout, ParticleCodec& codec, const CellGas& gas,
               const GrowthStokes& stokes, const std::vector<physics::Species>& species,
               physics::GrowthOptions options, double sigma_scale);

  std::string_view name() const override { return "porous_growth"; }
  void declare_pattern(PatternBuilder& pattern) const override;
  //! The range form of add_rhs() and add_jacobian() (CellRangeForm).
  void add_rhs_cells(double t, std::span<const double> y, std::span<double> ydot, int lo,
                     int hi) const;
  void add_jacobian_cells(double t, std::span<const double> y, JacobianValues& jac,
                          int lo, int hi) const;

  //! The rates of cell `cell` at state y, for output and tests.
  physics::ParticleRates<double> rates(int cell, std::span<const double> y) const;
  //! The same from the cell state `yc`, memoised by its values: within one RHS the
  //! growth sources and the coagulation channel (physics/modules/planetesimals.cpp) ask
  //! for the rates of the same state, which cost as much as the rest of the cell's RHS.
  const physics::ParticleRates<double>& cell_rates(int cell, const double* yc) const;
  //! d ln m/dt and d ln phi/dt as AD for the Jacobians, memoised the same way: their
  //! gradients with respect to (Sigma_d, Q_m, Q_phi) are computed once per cell state
  //! and chained onto the caller's seeds (ad_chain).
  void rates_ad(int cell, const AD* yc, AD& dlnm_dt, AD& dlnphi_dt) const;
  const physics::GrowthOptions& options() const { return opt_; }
  //! m, phi, a, rho_int, dv, t_grow and, with erosion, dv_ls.
  std::vector<OutputField> output_fields() const override;
  //! Empties the memos of cell_rates and rates_ad (GrowthStokes::forget).
  void forget() const {
    memo_key_.clear();
    memo_.clear();
    ad_memo_.clear();
  }

 private:
  template <class T>
  void cell_sources(int cell, const T* yc, T& dqm, T& dqphi) const;
  template <class T>
  physics::ParticleRates<T> compute_rates(int cell, const T* yc) const;

  const ParticleCodec& codec_;
  const CellGas& gas_;
  //! St of the growth model's particles; its cache also holds the decoded m, phi and
  //! radius of the state the rates are asked for (GrowthStokes::particle)
  const GrowthStokes& stokes_;
  const std::vector<physics::Species>& species_;
  physics::GrowthOptions opt_;
  static constexpr int kKey = 4;  // Sigma_d, Q_m, Q_phi, Sigma_g: all the rates depend on
  mutable std::vector<std::array<double, kKey>> memo_key_;
  mutable std::vector<physics::ParticleRates<double>> memo_;
  struct AdRates {
    std::array<double, kKey> key{-1.0, -1.0, -1.0, -1.0};
    double dlnm = 0.0, dlnphi = 0.0;
    std::array<double, 4> grad_m{}, grad_phi{};
  };
  mutable std::vector<AdRates> ad_memo_;
};

}  // namespace panoptic
