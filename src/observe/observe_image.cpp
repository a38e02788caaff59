#include "src/observe/observe_image.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "src/core/units.hpp"

namespace panoptic {

double Beam::area() const { return units::kPi * bmaj * bmin / (4.0 * std::log(2.0)); }

double deprojected_radius(double x, double y, const DiskOrientation& o) {
  const double sp = std::sin(o.pa_rad), cp = std::cos(o.pa_rad);
  const double u = x * sp + y * cp;
  const double v = (x * cp - y * sp) / std::cos(o.incl_rad);
  return std::hypot(u, v);
}

namespace {

struct Vec2 {
  double x, y;
};
double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }

//! Signed area of the disk |p| <= R intersected with the triangle (0, a, b): the parts
//! of the edge a -> b inside the circle bound triangles, the parts outside circular
//! sectors.
double circle_triangle_area(Vec2 a, Vec2 b, double R) {
  const auto sector = [R](Vec2 p, Vec2 q) {
    return 0.5 * R * R * std::atan2(cross(p, q), dot(p, q));
  };
  const Vec2 d{b.x - a.x, b.y - a.y};
  const double A = dot(d, d), B = dot(a, d), C = dot(a, a) - R * R;
  const double disc = B * B - A * C;
  if (A == 0.0) return 0.0;
  if (disc <= 0.0) return sector(a, b);  // the edge's line misses the circle
  // roots of A t^2 + 2 B t + C = 0 without cancellation
  const double q = -(B + std::copysign(std::sqrt(disc), B));
  double t1 = q / A, t2 = q != 0.0 ? C / q : -t1;
  if (t1 > t2) std::swap(t1, t2);
  if (t2 <= 0.0 || t1 >= 1.0) return sector(a, b);  // the chord lies off the edge
  t1 = std::max(t1, 0.0);
  t2 = std::min(t2, 1.0);
  const Vec2 p1{a.x + t1 * d.x, a.y + t1 * d.y}, p2{a.x + t2 * d.x, a.y + t2 * d.y};
  return sector(a, p1) + 0.5 * cross(p1, p2) + sector(p2, b);
}

//! Area of the disk |p| <= R intersected with a convex quadrilateral (either
//! orientation).
double circle_quad_area(const std::array<Vec2, 4>& quad, double R) {
  double a = 0.0;
  for (int i = 0; i < 4; ++i) a += circle_triangle_area(quad[i], quad[(i + 1) % 4], R);
  return std::abs(a);
}

//! Distance from the origin to a convex quadrilateral (0 if it holds the origin).
double distance_to_quad(const std::array<Vec2, 4>& quad) {
  double side = 0.0, dmin = std::numeric_limits<double>::infinity();
  bool inside = true;
  for (int i = 0; i < 4; ++i) {
    const Vec2 a = quad[i], b = quad[(i + 1) % 4];
    const Vec2 d{b.x - a.x, b.y - a.y};
    const double c = cross(d, Vec2{-a.x, -a.y});  // which side of a -> b the origin is
    if (c != 0.0) {
      if (side == 0.0)
        side = c;
      else if ((c > 0.0) != (side > 0.0))
        inside = false;
    }
    const double t = std::clamp(-dot(a, d) / dot(d, d), 0.0, 1.0);
    dmin = std::min(dmin, std::hypot(a.x + t * d.x, a.y + t * d.y));
  }
  return inside ? 0.0 : dmin;
}

}  // namespace

DiskProjector::DiskProjector(const SkyGrid& grid, const DiskOrientation& o,
                             std::span<const double> edges)
    : n_cells_(static_cast<int>(edges.size()) - 1) {
  const int n = grid.n;
  const double sp = std::sin(o.pa_rad), cp = std::cos(o.pa_rad);
  const double cos_i = std::cos(o.incl_rad), h = 0.5 * grid.pixel;
  // disk-plane coordinates of a sky point: u along the major axis, v / cos i along the
  // minor (deprojected_radius); linear, so a pixel maps to a parallelogram, and areas
  // on the sky are cos i times those in the disk plane
  const auto to_disk = [&](double x, double y) {
    return Vec2{x * sp + y * cp, (x * cp - y * sp) / cos_i};
  };
  const double to_pixels = cos_i / (grid.pixel * grid.pixel);
  offsets_.reserve(static_cast<std::size_t>(n) * n + 1);
  offsets_.push_back(0);
  for (int iy = 0; iy < n; ++iy)
    for (int ix = 0; ix < n; ++ix) {
      const double xc = grid.coord(ix), yc = grid.coord(iy);
      const std::array<Vec2, 4> quad = {to_disk(xc - h, yc - h), to_disk(xc + h, yc - h),
                                        to_disk(xc + h, yc + h), to_disk(xc - h, yc + h)};
      double r_max = 0.0;
      for (const Vec2& v : quad) r_max = std::max(r_max, std::hypot(v.x, v.y));
      const double r_min = distance_to_quad(quad);
      if (r_max > edges.front() && r_min < edges.back()) {
        // the pixel's area within each edge R: 0 for R <= r_min, all of it for R >=
        // r_max; annulus k gets the difference between its two edges
        double whole = 0.0;
        for (int i = 0; i < 4; ++i) whole += 0.5 * cross(quad[i], quad[(i + 1) % 4]);
        whole = std::abs(whole);
        const auto within = [&](double r) {
          return r >= r_max ? whole : r <= r_min ? 0.0 : circle_quad_area(quad, r);
        };
        // the first annulus that can reach the pixel: the one holding r_min
        const std::size_t lo = static_cast<std::size_t>(
            std::upper_bound(edges.begin(), edges.end(), r_min) - edges.begin());
        std::size_t k = lo == 0 ? 0 : lo - 1;
        double inner = within(edges[k]);
        for (; k + 1 < edges.size(); ++k) {
          const double outer = within(edges[k + 1]);
          if (outer > inner) {
            cells_.push_back(static_cast<int>(k));
            weights_.push_back((outer - inner) * to_pixels);
          }
          inner = outer;
          if (edges[k + 1] >= r_max) break;
        }
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
