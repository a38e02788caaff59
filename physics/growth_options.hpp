#pragma once
//! The monomer species of a cell and the switches and parameters of the growth model
//! (scene tables growth, porosity, erosion, fragmentation, bouncing; physics/
//! growth_rates.hpp and the processes it combines read them).
#include "physics/drag.hpp"
#include "physics/relative_velocity.hpp"

namespace panoptic::physics {

//! Monomer species of a cell (ice outside the snow line, silicate inside; spec §1.7).
struct Species {
  double a0 = 1e-5;     //!< monomer radius [cm]
  double rho0 = 1.4;    //!< monomer density [g cm^-3]
  double m0 = 0.0;      //!< monomer mass [g]
  double e_roll = 0.0;  //!< rolling energy [erg] (spec §0)
  double v_frag = 6e3;  //!< fragmentation speed [cm s^-1] (spec §5.3)
  //! Whether its aggregates fragment where GrowthOptions::fragmentation is on
  //! (fragmentation.species: silicate only, spec §11 #17 with §5.3's unfragmented
  //! porous ice).
  bool fragments = true;
};

enum class ErosionModel { kNone, kHalt, kBalance };

//! Switches and parameters of the growth model (scene tables growth, porosity, erosion,
//! fragmentation, bouncing). Speeds cgs.
struct GrowthOptions {
  double f_grow = 1.0;  //!< growth-rate multiplier (spec §4.1)
  double eps = 0.5;     //!< partner size ratio (spec §3)
  DragLaw drag = DragLaw::kStokesRe;
  double st_max = 1e4;   //!< soft cap of St: growth switched off smoothly above
  bool porosity = true;  //!< evolve phi; off: phi = 1
  double s_hs = -0.58;   //!< hit-and-stick slope (spec §4.3)
  double b = 0.15;       //!< compression threshold factor (spec §4.2)
  double phi_max = 0.5;  //!< spec §4.3
  bool gas_compaction = true;
  bool self_gravity = true;
  ErosionModel erosion = ErosionModel::kNone;
  //! Erosion on: particle_rates computes dv_ls, and the snapshots write it.
  bool eroding() const { return erosion != ErosionModel::kNone; }
  double v_eros = 4e3;    //!< [cm s^-1] (spec §5.1)
  double w_eros = 0.01;   //!< switch width (spec §5.2 has 0.05; see scene_keys.cpp)
  double f_s = 0.1;       //!< E2: small-projectile mass fraction
  double eps_eros = 1.0;  //!< E2: eroded mass per projectile mass
  double st_small = 0.0;  //!< projectile St; 0 = a monomer
  bool fragmentation = false;
  bool bouncing = false;
  double phi_bounce = 0.3;
  TurbulenceModel turbulence;  //!< V_g^2 normalisation and y_a of the turbulent dv (§3.5)
};

}  // namespace panoptic::physics
