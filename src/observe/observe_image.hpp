#pragma once
//! Sky images of an axisymmetric, geometrically thin disk (`panoptic observe`): the
//! projection of I(r) onto a pixel grid for an inclination and position angle, the
//! convolution with an elliptical Gaussian beam by FFT, and the deprojected azimuthal
//! average.
//!
//! Sky coordinates: X = offset to the east, Y = offset to the north [arcsec], origin at
//! the star; images are row-major [iy][ix], X and Y increasing with the index (display
//! with east to the left). Position angles are measured from north through east. A
//! disk of inclination i with its major axis at PA p: the sky point (X, Y) lies at
//! u = X sin p + Y cos p along the major axis and v = X cos p - Y sin p along the minor
//! axis, i.e. at radius r = sqrt(u^2 + (v / cos i)^2) in the disk plane.
#include <memory>
#include <span>
#include <vector>

#include "src/observe/fft.hpp"

namespace panoptic {

struct DiskOrientation {
  double incl_rad = 0.0;  //!< 0 = face-on; < pi/2
  double pa_rad = 0.0;    //!< PA of the major axis (north through east)
};

//! Elliptical Gaussian beam: FWHM of the major and minor axes [arcsec], PA of the major
//! axis [rad].
struct Beam {
  double bmaj = 0.0, bmin = 0.0, bpa_rad = 0.0;
  //! Solid angle pi bmaj bmin / (4 ln 2) [arcsec^2]: Jy/beam = Jy/arcsec^2 * area().
  double area() const;
};

//! Square pixel grid of n x n pixels of side `pixel` [arcsec], centred on the star (n
//! odd: the star is the centre of pixel (n-1)/2).
struct SkyGrid {
  int n = 0;
  double pixel = 0.0;
  double coord(int j) const { return (j - 0.5 * (n - 1)) * pixel; }
};

//! Disk-plane radius [arcsec] of the sky point (X, Y) [arcsec].
double deprojected_radius(double x, double y, const DiskOrientation& o);

//! Image [Jy/arcsec^2 or any surface brightness] of a disk whose intensity is I_k in the
//! annulus edges_arcsec[k] <= r < edges_arcsec[k+1] (zero elsewhere): each pixel holds
//! the mean of I over its area, from the exact area each annulus shares with it (the
//! pixel, mapped into the disk plane, is a parallelogram; its area within a circle is
//! summed edge by edge from triangles and circular sectors). So a pixel wholly inside
//! the disk has weights summing to 1, and the image's flux is
//! sum_k I_k pi (r_k+1^2 - r_k^2) cos i to round-off however coarse the pixels (a disk
//! far smaller than one pixel included). The pixel-to-annulus weights are computed once
//! (made for one grid and orientation) and applied to every intensity profile.
class DiskProjector {
 public:
  DiskProjector(const SkyGrid& grid, const DiskOrientation& o,
                std::span<const double> edges_arcsec);
  std::vector<double> image(std::span<const double> intensity) const;

 private:
  int n_cells_;
  std::vector<std::size_t> offsets_;  // CSR over pixels
  std::vector<int> cells_;
  std::vector<double> weights_;
};

//! Convolution of n x n images with a Gaussian beam by FFT (FFTW r2c/c2r): the kernel is
//! sampled on the pixel grid out to kHalfWidthSigma sigma of the major axis and
//! normalised to unit sum (flux is conserved to round-off); the image is zero-padded by
//! the kernel half-width on each side (at least) so that the circular convolution of the
//! FFT equals the linear one on the image. The plans and the kernel spectrum are made
//! once, in the constructor, and reused by every convolve().
class BeamConvolver {
 public:
  //! Kernel radius in units of the major-axis sigma: exp(-8.5^2/2) = 2e-16.
  static constexpr double kHalfWidthSigma = 8.5;
  BeamConvolver(int n, double pixel, const Beam& beam);
  //! image (n x n) convolved with the beam normalised to unit integral: same unit.
  std::vector<double> convolve(std::span<const double> image);
  int padded_size() const { return fft_->nx(); }
  int kernel_half_width() const { return half_; }

 private:
  int n_, half_;
  std::unique_ptr<RealFft2d> fft_;
  std::vector<std::complex<double>> kernel_hat_;
};

//! Azimuthal average of an n x n image over deprojected annuli of the disk plane:
//! bins [k dr, (k+1) dr) out to r_max [arcsec]; NaN where no pixel centre falls.
struct RadialProfile {
  std::vector<double> r_mid;  //!< bin centres [arcsec]
  std::vector<double> value;  //!< mean of the pixels in the bin
  std::vector<double> count;  //!< pixels in the bin
};
RadialProfile radial_profile(std::span<const double> image, const SkyGrid& grid,
                             const DiskOrientation& o, double dr, double r_max);

}  // namespace panoptic
