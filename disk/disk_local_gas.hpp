#pragma once
//! The gas a cell sees (physics::LocalGas, disk/local_gas.hpp) taken from a gas disk: the
//! one builder used by the grid (Simulation: every cell centre) and by the Lagrangian
//! track (one radius off the grid). Thermal structure of spec §1.3, mean free path and
//! molecular viscosity of spec §1.6, eta of spec §1.4.
#include <span>
#include <vector>

#include "disk/gas_disk.hpp"
#include "disk/local_gas.hpp"

namespace panoptic {

class Grid;

//! The local gas at radius r [cm] of `disk`, with surface density sigma_g [g cm^-2] and
//! midplane pressure slope dlnp_dlnr [-] there.
physics::LocalGas local_gas_at(const GasDisk& disk, double r, double sigma_g,
                               double dlnp_dlnr);

//! The local gas of every cell centre of `grid` with the surface densities `sigma_g`
//! [g cm^-2, per cell]; dlnP/dlnr from dlnp_dlnr_centres (spec §1.4: numerical
//! gradient on the grid).
std::vector<physics::LocalGas> local_gas_centres(const GasDisk& disk, const Grid& grid,
                                                 std::span<const double> sigma_g);

}  // namespace panoptic
