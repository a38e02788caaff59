#pragma once
//! What the two planetesimal modules share (spec §7): their options, the Sigma_pl
//! variables of the channels that are on (sigma_pl_coag, sigma_pl_si: per cell, not
//! transported), their snapshot fields and the conversion rates of a cell, so that the
//! model (Simulation: the mass budget, /summary, the first formation times) reads a
//! single-size run (physics/modules/planetesimals.hpp) and a size-distribution run
//! (physics/modules/bin_planetesimals.hpp) alike.
#include <span>
#include <utility>
#include <vector>

#include "src/solver/physics_module.hpp"
#include "src/solver/state_layout.hpp"

namespace panoptic {

//! The streaming-instability criterion (physics/planetesimal_criteria.hpp; d16 the
//! default).
enum class StreamingInstability { kNone, kD16, kS18, kZcrit };

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

class PlanetesimalChannels {
 public:
  virtual ~PlanetesimalChannels() = default;
  int coag_slot() const { return coag_slot_; }  //!< -1 when the channel is off
  int si_slot() const { return si_slot_; }      //!< -1 when the channel is off
  //! Conversion rates of cell `cell` at state y [g cm^-2 s^-1]: {coagulation, SI}.
  virtual std::pair<double, double> rates(int cell, std::span<const double> y) const = 0;

 protected:
  //! Registers sigma_pl_coag and/or sigma_pl_si, those of the channels that are on.
  PlanetesimalChannels(StateLayout& layout, const PlanetesimalOptions& options,
                       double sigma_scale);
  //! sigma_pl and that of each channel that is on, at every cell of `layout`.
  std::vector<OutputField> channel_fields(const StateLayout& layout) const;

  PlanetesimalOptions opt_;
  int coag_slot_ = -1, si_slot_ = -1;
};

}  // namespace panoptic
