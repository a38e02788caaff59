#pragma once
//! Lagrangian mode (`panoptic track`, spec §13): one particle followed along its drift
//! path, dr/dt = v_r, with the same local growth model as the grid (spec §2-§5), in a
//! dust background Sigma_d = Z Sigma_g(r) that does not evolve. A check of the growth
//! model against simple tracks, independent of the transport scheme.
#include <vector>

#include "src/scene/config.hpp"

namespace panoptic {

struct TrackPoint {
  double t = 0.0;    //!< [s]
  double r = 0.0;    //!< [cm]
  double m = 0.0;    //!< [g]
  double phi = 1.0;  //!< filling factor
  double a = 0.0;    //!< radius [cm]
  double St = 0.0;   //!< Stokes number
};

struct TrackResult {
  std::vector<TrackPoint> points;  //!< after every CVODE step
  bool reached = false;            //!< the particle reached a_stop
  TrackPoint at_stop;              //!< interpolated to a = a_stop when reached
  long steps = 0;
};

//! Follows a monomer released at r0 [cm] until its radius reaches a_stop [cm], it
//! drifts to the inner edge of the scene's grid, or t_max [s].
TrackResult track_particle(const Config& cfg, double r0, double a_stop, double t_max);

}  // namespace panoptic
