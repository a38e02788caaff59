#pragma once
//! `panoptic observe`: synthetic millimetre continuum images of one snapshot of a run.
//!
//! Per cell, the mass-dominating particle (radius a, filling factor phi, internal
//! density rho_int of the snapshot) gives the absorption opacity kappa_abs(lambda) =
//! 3 Q_abs / (4 a rho_int) (physics/mie.hpp; porosity by Maxwell-Garnett with vacuum,
//! physics/optical_constants.hpp); the dust emits at the gas temperature T(r) of /disk/T.
//! ABSORPTION ONLY: scattering is neglected (no albedo reduction of the emission, no
//! scattered light), and the disk is a geometrically thin slab seen at inclination i:
//!   I_nu(r) = B_nu(T) (1 - exp(-tau_nu / cos i)),  tau_nu = Sigma_d kappa_abs.
//! The image is projected, convolved with the beam by FFT (src/observe/observe_image.hpp)
//! and averaged over deprojected annuli; the spectral index is taken between every pair
//! of wavelengths. Output layout: README "Synthetic observations".
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

//! Planck function B_nu(T) [erg s^-1 cm^-2 Hz^-1 sr^-1].
double planck_nu(double nu_hz, double T);
//! Surface brightness of a slab [Jy arcsec^-2]: B_nu(T) (1 - exp(-tau / mu)).
double slab_intensity_jy_arcsec2(double nu_hz, double T, double tau, double mu);

//! Pixels per FWHM of the beam's minor axis (image pixel = bmin / this).
inline constexpr int kPixelsPerBeamMinor = 5;
//! Field margin beyond the disk's outer edge, in beam major-axis FWHM: 4 FWHM = 9.4
//! sigma, so the beam spills < 1e-19 of the flux out of the field.
inline constexpr double kFieldMarginBeams = 4.0;
//! Largest image side [pixels] (memory: 8 bytes x 2 images x n^2 per wavelength).
inline constexpr int kMaxImageSide = 4097;
//! Fewest pixels across the projected minor axis of the disk (2 r_out cos i / d; or half
//! the major axis for a disk smaller than that): below, nearly edge-on, the pixels miss
//! the disk at some position angles (from i ~ 89.7 deg for the fiducial disk at 140 pc
//! and the default beam).
inline constexpr double kMinMinorAxisPixels = 3.0;
//! Largest relative difference between the image-summed flux and the flux over the
//! annuli: the projection makes them equal to round-off (DiskProjector), so a larger
//! one is a bug, reported as an internal error before anything is written.
inline constexpr double kFluxRoundOff = 1e-9;

}  // namespace panoptic
