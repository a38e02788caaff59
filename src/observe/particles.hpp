#pragma once
//! The particles each cell of the snapshot is seen with: one size per cell (the run's
//! mass-dominating particle, or --a-cm everywhere), or the bins of a size-distribution
//! run with their shares of the cell's dust mass; of silicate inside the snow line and of
//! the outer species beyond it.
#include <vector>

#include "src/observe/materials.hpp"
#include "src/observe/observe.hpp"
#include "src/observe/run_snapshot.hpp"

namespace panoptic {

//! A particle as its opacity sees it.
struct SeenParticle {
  double a_cm = 0.0;  //!< radius [cm]
  double phi = 1.0;   //!< filling factor: volume fraction of the optical solid
  double rho = 0.0;   //!< internal density [g cm^-3]
};

//! The particle of the run's radius `a_cm` and internal density `rho_int` made of an
//! optical solid of density `rho_solid`: its filling factor is rho_int / rho_solid
//! (capped at 1), so that it keeps the run's mass.
SeenParticle seen_particle(double a_cm, double rho_int, double rho_solid);

//! One bin of a cell's size distribution: its aggregate and its share of the dust mass.
struct BinParticle {
  double mass_fraction = 0.0;  //!< sigma_k / sum of the cell's sigma_k > 0
  SeenParticle particle;
};

//! The run's monomer densities material.ice_rho0, material.sil_rho0 [g cm^-3] (those of
//! a bin's aggregate: rho_int = phi rho0, spec §2).
struct MonomerDensities {
  double ice = 0.0, sil = 0.0;
};

struct CellParticles {
  std::vector<int> inner;  //!< 1: silicate (inside the snow line), 0: outer species
  //! The particle of each cell: the run's one size, --a-cm, or the size distribution's
  //! mass-dominating bin (argmax sigma_k, as the run's /snapshots/a).
  std::vector<double> a_cm;  //!< radius [cm]
  std::vector<double> phi;   //!< filling factor: volume fraction of the optical solid
  std::vector<double> rho;   //!< internal density [g cm^-3]
  //! A size-distribution run seen without --a-cm: per cell, the bins that hold dust
  //! (sigma_k > 0; a cell without any: its mass-dominating bin alone). Empty otherwise.
  std::vector<std::vector<BinParticle>> bins;
};

//! The particles of snapshot `s` (`snowline`: the scene's snowline.enabled).
CellParticles cell_particles(const RunSnapshot& s, const OpticalMaterials& mat,
                             bool snowline, const MonomerDensities& rho0,
                             const ObserveArgs& a);

}  // namespace panoptic
