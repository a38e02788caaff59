#include "src/observe_image.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

#include "src/units.hpp"

namespace panoptic {

double Beam::area() const { return units::kPi * bmaj * bmin / (4.0 * std::log(2.0)); }

double deprojected_radius(double x, double y, const DiskOrientation& o) {
  const double sp = std::sin(o.pa_rad), cp = std::cos(o.pa_rad);
  const double u = x * sp + y * cp;
  const double v = (x * cp - y * sp) / std::cos(o.incl_rad);
  return std::hypot(u, v);
}

DiskProjector::DiskProjector(const SkyGrid& grid, const DiskOrientation& o,
                             std::span<const double> edges, int sub)
    : n_cells_(static_cast<int>(edges.size()) - 1) {
  const int n = grid.n;
  offsets_.reserve(static_cast<std::size_t>(n) * n + 1);
  offsets_.push_back(0);
  std::map<int, int> hits;
  const double w = 1.0 / (static_cast<double>(sub) * sub);
  for (int iy = 0; iy < n; ++iy)
    for (int ix = 0; ix < n; ++ix) {
      hits.clear();
      for (int sy = 0; sy < sub; ++sy)
        for (int sx = 0; sx < sub; ++sx) {
          const double x = grid.coord(ix) + ((sx + 0.5) / sub - 0.5) * grid.pixel;
          const double y = grid.coord(iy) + ((sy + 0.5) / sub - 0.5) * grid.pixel;
          const double r = deprojected_radius(x, y, o);
          if (!(r >= edges.front() && r < edges.back())) continue;  // NaN too
          const auto it = std::upper_bound(edges.begin(), edges.end(), r);
          ++hits[static_cast<int>(it - edges.begin()) - 1];
        }
      for (const auto& [cell, count] : hits) {
        cells_.push_back(cell);
        weights_.push_back(count * w);
      }
      offsets_.push_back(cells_.size());
    }
}

std::vector<double> DiskProjector::image(std::span<const double> intensity) const {
  if (static_cast<int>(intensity.size()) != n_cells_)
    throw std::invalid_argument("DiskProjector::image: wrong number of cells");
  std::vector<double> img(offsets_.size() - 1, 0.0);
  for (std::size_t p = 0; p + 1 < offsets_.size(); ++p)
    for (std::size_t k = offsets_[p]; k < offsets_[p + 1]; ++k)
      img[p] += weights_[k] * intensity[cells_[k]];
  return img;
}

BeamConvolver::BeamConvolver(int n, double pixel, const Beam& beam) : n_(n) {
  const double fwhm_to_sigma = 1.0 / (2.0 * std::sqrt(2.0 * std::log(2.0)));
  const double s_maj = beam.bmaj * fwhm_to_sigma / pixel;  // [pixels]
  const double s_min = beam.bmin * fwhm_to_sigma / pixel;
  half_ = static_cast<int>(std::ceil(kHalfWidthSigma * s_maj));
  // padding: at least the kernel half-width on each side (the linear convolution of
  // an n-wide image with a (2h+1)-wide kernel needs n + 2h; more would do with n + h)
  const int p = fft_friendly_size(n + 2 * half_);
  fft_ = std::make_unique<RealFft2d>(p, p);
  // kernel centred on pixel (0, 0), wrapped around the padded array
  std::span<double> k = fft_->real();
  std::fill(k.begin(), k.end(), 0.0);
  const double sp = std::sin(beam.bpa_rad), cp = std::cos(beam.bpa_rad);
  double sum = 0.0;
  for (int dy = -half_; dy <= half_; ++dy)
    for (int dx = -half_; dx <= half_; ++dx) {
      const double u = dx * sp + dy * cp;  // along the beam's major axis [pixels]
      const double v = dx * cp - dy * sp;
      const double g =
          std::exp(-0.5 * (u * u / (s_maj * s_maj) + v * v / (s_min * s_min)));
      k[static_cast<std::size_t>((dy + p) % p) * p + (dx + p) % p] = g;
      sum += g;
    }
  // unit sum, and the 1/(p^2) of the unnormalised c2r folded in
  const double scale = 1.0 / (sum * static_cast<double>(p) * p);
  fft_->forward();
  const std::span<fftw_complex> s = fft_->spectrum();
  kernel_hat_.resize(s.size());
  for (std::size_t i = 0; i < s.size(); ++i)
    kernel_hat_[i] = std::complex<double>(s[i][0], s[i][1]) * scale;
}

std::vector<double> BeamConvolver::convolve(std::span<const double> image) {
  if (static_cast<int>(image.size()) != n_ * n_)
    throw std::invalid_argument("BeamConvolver::convolve: wrong image size");
  const int p = fft_->nx();
  std::span<double> buf = fft_->real();
  std::fill(buf.begin(), buf.end(), 0.0);
  for (int iy = 0; iy < n_; ++iy)
    std::copy_n(image.begin() + static_cast<std::ptrdiff_t>(iy) * n_, n_,
                buf.begin() + static_cast<std::ptrdiff_t>(iy) * p);
  fft_->forward();
  std::span<fftw_complex> s = fft_->spectrum();
  for (std::size_t i = 0; i < s.size(); ++i) {
    const std::complex<double> z =
        std::complex<double>(s[i][0], s[i][1]) * kernel_hat_[i];
    s[i][0] = z.real();
    s[i][1] = z.imag();
  }
  fft_->backward();
  std::vector<double> out(static_cast<std::size_t>(n_) * n_);
  for (int iy = 0; iy < n_; ++iy)
    std::copy_n(buf.begin() + static_cast<std::ptrdiff_t>(iy) * p, n_,
                out.begin() + static_cast<std::ptrdiff_t>(iy) * n_);
  return out;
}

RadialProfile radial_profile(std::span<const double> image, const SkyGrid& grid,
                             const DiskOrientation& o, double dr, double r_max) {
  const int nb = std::max(1, static_cast<int>(std::ceil(r_max / dr)));
  RadialProfile prof;
  prof.r_mid.resize(nb);
  std::vector<double> sum(nb, 0.0);
  prof.count.assign(nb, 0.0);
  for (int b = 0; b < nb; ++b) prof.r_mid[b] = (b + 0.5) * dr;
  for (int iy = 0; iy < grid.n; ++iy)
    for (int ix = 0; ix < grid.n; ++ix) {
      const double r = deprojected_radius(grid.coord(ix), grid.coord(iy), o);
      // tested as a double before the cast: near edge-on (i -> 90 deg) r / dr overflows
      // an int (which crashed with --incl-deg 89.999999)
      const double rb = r / dr;
      if (!(rb >= 0.0 && rb < nb)) continue;
      const int b = static_cast<int>(rb);
      sum[b] += image[static_cast<std::size_t>(iy) * grid.n + ix];
      prof.count[b] += 1.0;
    }
  prof.value.resize(nb);
  for (int b = 0; b < nb; ++b)
    prof.value[b] = prof.count[b] > 0.0 ? sum[b] / prof.count[b]
                                        : std::numeric_limits<double>::quiet_NaN();
  return prof;
}

}  // namespace panoptic
