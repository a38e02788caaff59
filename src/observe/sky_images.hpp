#pragma once
//! The sky of `panoptic observe`: the cells' intensities projected onto a pixel grid
//! (pixel from the beam, field = disk + margin), convolved with the beam, averaged over
//! deprojected annuli, and summed to total fluxes (the tools: observe_image.hpp).
#include <vector>

#include "src/observe/emission.hpp"
#include "src/observe/observe.hpp"
#include "src/observe/observe_image.hpp"
#include "src/observe/run_snapshot.hpp"

namespace panoptic {

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

//! Images [wavelength][y][x], profiles [wavelength][bin] and fluxes [wavelength].
struct SkyImages {
  SkyGrid grid;
  Beam beam;
  int padded_size = 0, kernel_half_width = 0;  //!< of the beam's FFT (BeamConvolver)
  std::vector<double> r_mid_arcsec;            //!< deprojected radius of the profile bins
  std::vector<double> count;                   //!< pixels in each bin
  std::vector<double> model;                   //!< before the beam [Jy arcsec^-2]
  std::vector<double> convolved;               //!< after it [Jy beam^-1]
  std::vector<double> profile_model, profile_convolved;  //!< azimuthal means
  std::vector<double> flux_model, flux_convolved;        //!< image sums [Jy]
  //! Sum over the cells' projected annuli, I_i mu pi (r_o^2 - r_i^2) / d^2 [Jy]:
  //! independent of the pixels, the check of the image-summed fluxes.
  std::vector<double> flux_annuli;
};

//! The images of the emission `e` of snapshot `s`'s cells. Throws ConfigError when the
//! image would exceed kMaxImageSide pixels, or its disk's projected minor axis span
//! fewer than kMinMinorAxisPixels.
SkyImages sky_images(const ObserveArgs& a, const RunSnapshot& s, const CellEmission& e);

}  // namespace panoptic
