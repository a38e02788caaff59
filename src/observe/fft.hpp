#pragma once
//! RAII over FFTW3 (double) for real 2-D convolutions: one r2c and one c2r plan of a
//! fixed size, made once and executed any number of times on their own buffers.
#include <fftw3.h>

#include <complex>
#include <span>

namespace panoptic {

//! fftw_malloc'ed array of T, freed with fftw_free.
template <class T>
class FftwBuffer {
 public:
  explicit FftwBuffer(std::size_t n)
      : data_(static_cast<T*>(fftw_malloc(sizeof(T) * n))), n_(n) {
    if (data_ == nullptr) throw std::bad_alloc();
  }
  ~FftwBuffer() { fftw_free(data_); }
  FftwBuffer(const FftwBuffer&) = delete;
  FftwBuffer& operator=(const FftwBuffer&) = delete;
  T* data() { return data_; }
  const T* data() const { return data_; }
  std::size_t size() const { return n_; }
  std::span<T> span() { return {data_, n_}; }

 private:
  T* data_;
  std::size_t n_;
};

//! r2c and c2r plans of an ny x nx real array (row-major, x fastest) and its
//! ny x (nx/2 + 1) half spectrum. forward(): real() -> spectrum(); backward():
//! spectrum() -> real(), unnormalised (times nx ny), spectrum() destroyed.
class RealFft2d {
 public:
  RealFft2d(int ny, int nx);
  ~RealFft2d();
  RealFft2d(const RealFft2d&) = delete;
  RealFft2d& operator=(const RealFft2d&) = delete;
  void forward();
  void backward();
  std::span<double> real() { return real_.span(); }
  std::span<fftw_complex> spectrum() { return spectrum_.span(); }
  int nx() const { return nx_; }
  int ny() const { return ny_; }

 private:
  int ny_, nx_;
  FftwBuffer<double> real_;
  FftwBuffer<fftw_complex> spectrum_;
  fftw_plan r2c_ = nullptr, c2r_ = nullptr;
};

//! Smallest n' >= n whose prime factors are 2, 3, 5, 7 (sizes FFTW does fastest).
int fft_friendly_size(int n);

}  // namespace panoptic
