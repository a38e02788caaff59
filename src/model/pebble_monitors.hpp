#pragma once
//! The pebble-flux monitors (spec §8): the faces through which the dust's inward mass
//! flow is recorded (/snapshots/pebble_flux, m_through, /timeseries).
#include <string>
#include <vector>

#include "src/scene/config.hpp"

namespace panoptic {

class Grid;

//! A radius where the pebble flux is recorded (spec §8): the face nearest to it.
struct PebbleMonitor {
  std::string name;      //!< "snow line", "r_in", "10 au"
  double r_au = 0.0;     //!< radius of the face used [au]
  int face = 0;          //!< face index (0 = r_in)
  int global_slot = -1;  //!< cumulative-mass variable (m_out_dust for r_in)
};

//! The monitors of the scene (pebbles.radii_au, or the snow line r_snow [cm] and 1, 3,
//! 10, 30 au), each on the face nearest to its radius, those off the grid left out,
//! then r_in; their slots are set when the dust transport books them.
std::vector<PebbleMonitor> place_pebble_monitors(const Config& cfg, const Grid& grid,
                                                 double r_snow);

}  // namespace panoptic
