#pragma once
//! `panoptic observe`: synthetic millimetre continuum images of one snapshot of a run.
//! Per cell the mass-dominating particle gives the absorption opacity, and the dust
//! emits at the gas temperature from a geometrically thin slab (emission.hpp); the image
//! is projected, convolved with the beam and averaged over deprojected annuli
//! (sky_images.hpp); the spectral index is taken between every pair of wavelengths
//! (spectral_index.hpp). The steps: src/observe/README.md; output layout: the same
//! README, Synthetic observations.
#include <string>
#include <vector>

namespace panoptic {

struct ObserveArgs {
  std::string run_file;
  std::string output;  //!< -o; default <run stem>_obs.h5 next to the run
  bool overwrite = false;
  double time_yr = 0.0;
  std::vector<double> lambda_mm;
  double distance_pc = 140.0;
  double incl_deg = 0.0, pa_deg = 0.0;
  double bmaj_arcsec = 0.05, bmin_arcsec = 0.05, bpa_deg = 0.0;
  double a_cm = 0.0;        //!< with a_cm_given: this particle radius everywhere [cm]
  bool a_cm_given = false;  //!< --a-cm was given (replaces the run's sizes)
  std::vector<std::string> overrides;  //!< --set observe.key=value
};

//! Runs the command; returns the exit code. Throws ConfigError (exit 2) for bad
//! arguments and files that are not panoptic runs, IoError (4) when writing fails.
int observe(const ObserveArgs& args);

}  // namespace panoptic
