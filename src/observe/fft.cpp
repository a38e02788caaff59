#include "src/observe/fft.hpp"

#include <algorithm>
#include <new>
#include <stdexcept>
#include <string>

namespace panoptic {

RealFft2d::RealFft2d(int ny, int nx)
    : ny_(ny),
      nx_(nx),
      real_(static_cast<std::size_t>(ny) * nx),
      spectrum_(static_cast<std::size_t>(ny) * (nx / 2 + 1)) {
  // FFTW_ESTIMATE: planning does not touch the buffers and the result does not depend on
  // timing measurements (reproducible output).
  r2c_ = fftw_plan_dft_r2c_2d(ny, nx, real_.data(), spectrum_.data(), FFTW_ESTIMATE);
  c2r_ = fftw_plan_dft_c2r_2d(ny, nx, spectrum_.data(), real_.data(), FFTW_ESTIMATE);
  if (r2c_ == nullptr || c2r_ == nullptr) {
    if (r2c_) fftw_destroy_plan(r2c_);
    if (c2r_) fftw_destroy_plan(c2r_);
    throw std::runtime_error("FFTW: cannot plan a " + std::to_string(ny) + " x " +
                             std::to_string(nx) + " transform");
  }
}

RealFft2d::~RealFft2d() {
  fftw_destroy_plan(r2c_);
  fftw_destroy_plan(c2r_);
}

void RealFft2d::forward() { fftw_execute(r2c_); }
void RealFft2d::backward() { fftw_execute(c2r_); }

int fft_friendly_size(int n) {
  for (int m = std::max(n, 1);; ++m) {
    int r = m;
    for (const int p : {2, 3, 5, 7})
      while (r % p == 0) r /= p;
    if (r == 1) return m;
  }
}

}  // namespace panoptic
