#pragma once
//! Planetesimal formation on the grid (spec §7): the dust of each cell is converted into
//! planetesimals, which are not transported, by direct coagulation and one streaming
//! instability criterion (the laws: physics/planetesimal_criteria.hpp). The sinks
//! conserve the particle properties: dSigma_d = -Sdot, dQ = -(Q/Sigma_d) Sdot (spec
//! §6.2). Owns one Sigma_pl variable per channel that is on (PlanetesimalChannels).
#include "physics/modules/cell_range_form.hpp"
#include "physics/modules/planetesimal_channels.hpp"
#include "physics/modules/porous_growth.hpp"

namespace panoptic {

class Planetesimals : public CellRangeForm<Planetesimals>, public PlanetesimalChannels {
 public:
  //! Registers sigma_pl_coag and/or sigma_pl_si.
  Planetesimals(StateLayout& layout, const ParticleCodec& codec, const CellGas& gas,
                const StokesModel& stokes, const std::vector<physics::Species>& species,
                const physics::GrowthOptions& growth, PlanetesimalOptions options,
                double sigma_scale);

  std::string_view name() const override { return "planetesimals"; }
  void declare_pattern(PatternBuilder& pattern) const override;
  //! The range form of add_rhs() and add_jacobian() (CellRangeForm).
  void add_rhs_cells(double t, std::span<const double> y, std::span<double> ydot, int lo,
                     int hi) const;
  void add_jacobian_cells(double t, std::span<const double> y, JacobianValues& jac,
                          int lo, int hi) const;

  //! Take the growth rates of the coagulation channel from the growth module's memo
  //! (same state, same options: the same numbers, computed once per RHS).
  void use_growth_rates(const PorousGrowth* growth) { growth_module_ = growth; }

  //! sigma_pl and that of each channel that is on.
  std::vector<OutputField> output_fields() const override {
    return channel_fields(layout_);
  }
  std::pair<double, double> rates(int cell, std::span<const double> y) const override;

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

  const ParticleCodec& codec_;
  const CellGas& gas_;
  const StokesModel& stokes_;
  const std::vector<physics::Species>& species_;
  physics::GrowthOptions growth_;
  const PorousGrowth* growth_module_ = nullptr;
};

}  // namespace panoptic
