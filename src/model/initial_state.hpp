#pragma once
//! The initial dust of a scene (spec §6.4): Sigma_d = Z Sigma_g, with Z_in = (1 - f_ice)
//! Z_out inside the snow line (spec §1.7), or a diffused test ring on a floor.
#include <span>
#include <vector>

#include "src/scene/config.hpp"

namespace panoptic {

class GasDisk;
class Grid;

struct InitialDust {
  std::vector<double> sigma_d;  //!< per cell [g cm^-2]
  double mass = 0.0;            //!< its cell-centre sum over the grid [g]
  //! The profile's own dust mass on r_in..r_out, integrated exactly (NaN for the ring).
  double profile_mass = 0.0;
};

//! The initial dust of every cell, on the gas `sigma_g` [g cm^-2, per cell], silicate in
//! the cells `inside` the snow line; r_snow [cm] bounds the exact integral.
InitialDust initial_dust(const Config& cfg, const Grid& grid, const GasDisk& disk,
                         std::span<const double> sigma_g, std::span<const char> inside,
                         double r_snow);

}  // namespace panoptic
