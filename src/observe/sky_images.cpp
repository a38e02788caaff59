#include "src/observe/sky_images.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>
#include <string>
#include <utility>

#include "src/core/error.hpp"
#include "src/core/units.hpp"

namespace panoptic {
namespace {

//! The pixel grid: pixel from the beam, field = disk + margin.
SkyGrid sky_grid(const ObserveArgs& a, double r_out_arcsec, double mu) {
  SkyGrid grid;
  grid.pixel = a.bmin_arcsec / kPixelsPerBeamMinor;
  const double half = r_out_arcsec + kFieldMarginBeams * a.bmaj_arcsec;
  const double n_side = 2.0 * std::ceil(half / grid.pixel) + 1.0;
  if (n_side > kMaxImageSide)
    throw ConfigError("--beam-arcsec " + num(a.bmaj_arcsec) + "," + num(a.bmin_arcsec) +
                      ": the image would need " + num(n_side) + " x " + num(n_side) +
                      " pixels (" + std::to_string(kPixelsPerBeamMinor) +
                      " per bmin over the disk, " + num(2.0 * half) +
                      " arcsec); the limit is " + std::to_string(kMaxImageSide) +
                      ": use a larger beam or a larger --distance-pc");
  grid.n = static_cast<int>(n_side);
  // Nearly edge-on the projected disk is thinner than a pixel: its flux is still exact
  // (DiskProjector), but neither the image nor the deprojected profile then resolves
  // anything across the minor axis (with point samples the image missed the disk
  // altogether, flux 0 at i = 89.999999 deg, PA 30). Require the projected minor axis
  // to span a few pixels. (Only where the inclination thins it: a disk smaller than the
  // beam's pixels is observed face-on or inclined alike, as a point source.)
  const double major_px = 2.0 * r_out_arcsec / grid.pixel, minor_px = major_px * mu;
  if (minor_px < std::min(kMinMinorAxisPixels, 0.5 * major_px))
    throw ConfigError("--incl-deg " + num(a.incl_deg) +
                      ": the disk's projected minor "
                      "axis would be " +
                      num(minor_px) + " pixels (" + num(grid.pixel) +
                      " arcsec each, from the beam), fewer than " +
                      num(kMinMinorAxisPixels) +
                      " to sample it; use a smaller inclination or a smaller beam");
  return grid;
}

}  // namespace

SkyImages sky_images(const ObserveArgs& a, const RunSnapshot& s, const CellEmission& e) {
  const std::size_t nl = a.lambda_mm.size(), n = e.n_cells;
  // angles reduced to one turn first: sin and cos of a huge angle lose all precision
  const DiskOrientation orient{a.incl_deg * units::kPi / 180.0,
                               std::fmod(a.pa_deg, 360.0) * units::kPi / 180.0};
  SkyImages im;
  im.beam = Beam{a.bmaj_arcsec, a.bmin_arcsec,
                 std::fmod(a.bpa_deg, 360.0) * units::kPi / 180.0};
  const double r_out_arcsec = s.r_f_au.back() / a.distance_pc;
  im.grid = sky_grid(a, r_out_arcsec, e.mu);
  const SkyGrid& grid = im.grid;
  std::vector<double> edges_arcsec(n + 1);
  for (std::size_t i = 0; i <= n; ++i) edges_arcsec[i] = s.r_f_au[i] / a.distance_pc;
  const DiskProjector projector(grid, orient, edges_arcsec);
  BeamConvolver convolver(grid.n, grid.pixel, im.beam);  // plans made once, reused below
  im.padded_size = convolver.padded_size();
  im.kernel_half_width = convolver.kernel_half_width();
  const std::size_t npix = static_cast<std::size_t>(grid.n) * grid.n;
  const double dr = grid.pixel;
  RadialProfile geometry =
      radial_profile(std::vector<double>(npix, 0.0), grid, orient, dr, r_out_arcsec);
  const std::size_t nb = geometry.r_mid.size();
  im.model.resize(nl * npix);
  im.convolved.resize(nl * npix);
  im.flux_annuli.assign(nl, 0.0);
  for (std::size_t l = 0; l < nl; ++l)
    for (std::size_t i = 0; i < n; ++i)
      im.flux_annuli[l] +=
          e.intensity[l * n + i] * e.mu * units::kPi *
          (edges_arcsec[i + 1] * edges_arcsec[i + 1] - edges_arcsec[i] * edges_arcsec[i]);
  im.profile_convolved.resize(nl * nb);
  im.profile_model.resize(nl * nb);
  im.flux_model.resize(nl);
  im.flux_convolved.resize(nl);
  const double pix2 = grid.pixel * grid.pixel;
  for (std::size_t l = 0; l < nl; ++l) {
    const std::vector<double> model =
        projector.image(std::span<const double>(e.intensity).subspan(l * n, n));
    std::vector<double> conv = convolver.convolve(model);
    double fm = 0.0, fc = 0.0;
    for (std::size_t p = 0; p < npix; ++p) {
      fm += model[p] * pix2;
      fc += conv[p] * pix2;
      conv[p] *= im.beam.area();  // Jy/arcsec^2 -> Jy/beam
    }
    im.flux_model[l] = fm;
    im.flux_convolved[l] = fc;
    const RadialProfile pc = radial_profile(conv, grid, orient, dr, r_out_arcsec);
    const RadialProfile pm = radial_profile(model, grid, orient, dr, r_out_arcsec);
    std::copy(pc.value.begin(), pc.value.end(), im.profile_convolved.begin() + l * nb);
    std::copy(pm.value.begin(), pm.value.end(), im.profile_model.begin() + l * nb);
    std::copy(model.begin(), model.end(), im.model.begin() + l * npix);
    std::copy(conv.begin(), conv.end(), im.convolved.begin() + l * npix);
  }
  im.r_mid_arcsec = std::move(geometry.r_mid);
  im.count = std::move(geometry.count);
  return im;
}

}  // namespace panoptic
