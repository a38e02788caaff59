#pragma once
//! The particle each cell of the snapshot is seen with: one size per cell (the run's
//! mass-dominating particle, or --a-cm everywhere), of silicate inside the snow line and
//! of the outer species beyond it.
#include <vector>

#include "src/observe/materials.hpp"
#include "src/observe/observe.hpp"
#include "src/observe/run_snapshot.hpp"

namespace panoptic {

struct CellParticles {
  std::vector<int> inner;    //!< 1: silicate (inside the snow line), 0: outer species
  std::vector<double> a_cm;  //!< radius [cm]
  std::vector<double> phi;   //!< filling factor: volume fraction of the optical solid
  std::vector<double> rho;   //!< internal density [g cm^-3]
};

//! The particles of snapshot `s` (`snowline`: the scene's snowline.enabled).
CellParticles cell_particles(const RunSnapshot& s, const OpticalMaterials& mat,
                             bool snowline, const ObserveArgs& a);

}  // namespace panoptic
