#pragma once
//! The disk's collision kernel of a cell and the fragmentation probability of each pair
//! (spec §15.2): K_ij = pi (a_i + a_j)^2 dv_ij / sqrt(2 pi (h_i^2 + h_j^2)), the rate per
//! unit area of vertically integrated Gaussian layers applied to the number surface
//! densities (Birnstiel, Dullemond & Brauer 2010; DustPy, dust.f90 `kernel`); and
//! p_frag = (1 + 3/2 x) exp(-3/2 x), x = (v_frag/dv)^2, the probability that the pair
//! meets faster than v_frag when its speeds are Maxwell-Boltzmann distributed around dv
//! (DustPy, dust.f90 `pfrag`; Stammler & Birnstiel 2022); or, for the unequal pairs
//! with erosion on, Krijt et al.'s (2015) threshold at v_eros smoothed as spec §5.2's
//! S(x) (erosion_probability). The pair speeds come from a
//! caller-supplied function, so that the relative velocities of physics/
//! relative_velocity.hpp (spec §3 pair by pair) and the drag of physics/drag.hpp plug in
//! unchanged (bin_properties, pair_speeds below).
#include <cmath>
#include <span>
#include <vector>

#include "disk/local_gas.hpp"
#include "physics/coagulation/mass_grid.hpp"
#include "physics/coagulation/smoluchowski.hpp"
#include "physics/drag.hpp"
#include "physics/particle.hpp"
#include "physics/relative_velocity.hpp"
#include "src/core/units.hpp"

namespace panoptic::physics::coagulation {

//! Radius, Stokes number and dust scale height of every bin of a cell (spec §15.1).
struct BinProperties {
  std::vector<double> a;    //!< radius [cm]
  std::vector<double> St;   //!< Stokes number [-]
  std::vector<double> h_d;  //!< dust scale height [cm]
};

//! The bins' properties from their filling factors phi_k (spec §2 laws per bin), into b
//! (its buffers reused).
inline void bin_properties(const MassGrid& grid, std::span<const double> phi, double rho0,
                           const LocalGas& gas, DragLaw law, BinProperties& b) {
  const int n = grid.size();
  b.a.resize(n);
  b.St.resize(n);
  b.h_d.resize(n);
  for (int k = 0; k < n; ++k) {
    b.a[k] = radius(grid.m[k], phi[k], rho0);                           // spec §2
    b.St[k] = stokes_number_of_radius(b.a[k], phi[k], rho0, gas, law);  // spec §2
    b.h_d[k] = dust_scale_height(b.St[k], gas);                         // spec §2
  }
}

//! The bins' properties from their filling factors phi_k (spec §2 laws per bin).
inline BinProperties bin_properties(const MassGrid& grid, std::span<const double> phi,
                                    double rho0, const LocalGas& gas,
                                    DragLaw law = DragLaw::kStokesRe) {
  BinProperties b;
  bin_properties(grid, phi, rho0, gas, law, b);
  return b;
}

//! dv_ij of every pair from the components of spec §3 with St1 = St_i, St2 = St_j (no
//! eps): N x N, row-major [cm s^-1].
inline std::vector<double> pair_speeds(const MassGrid& grid, const BinProperties& b,
                                       const LocalGas& gas,
                                       const TurbulenceModel& turbulence = {}) {
  const int n = grid.size();
  std::vector<double> dv(static_cast<std::size_t>(n) * n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j <= i; ++j) {
      const double v =
          dv_total(b.St[i], b.St[j], grid.m[i], grid.m[j], gas, turbulence);  // spec §3
      dv[static_cast<std::size_t>(i) * n + j] = v;
      dv[static_cast<std::size_t>(j) * n + i] = v;
    }
  return dv;
}

//! K_ij = pi (a_i + a_j)^2 dv_ij / sqrt(2 pi (h_i^2 + h_j^2)) of one pair (spec §15.2)
//! [cm^2 s^-1]; a [cm], h [cm], dv [cm s^-1].
inline double pair_kernel(double a_i, double a_j, double h_i, double h_j, double dv) {
  const double sum = a_i + a_j;
  const double h2 = h_i * h_i + h_j * h_j;
  return units::kPi * sum * sum * dv / std::sqrt(2.0 * units::kPi * h2);
}

//! K_ij of every pair (pair_kernel), N x N row-major [cm^2 s^-1]; dv(i, j) [cm s^-1]
//! from the caller.
template <class PairSpeed>
std::vector<double> collision_kernel(std::span<const double> a,
                                     std::span<const double> h_d, PairSpeed dv) {
  const std::size_t n = a.size();
  std::vector<double> k(n * n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j <= i; ++j) {
      const double v = pair_kernel(a[i], a[j], h_d[i], h_d[j],
                                   dv(static_cast<int>(i), static_cast<int>(j)));
      k[i * n + j] = v;
      k[j * n + i] = v;
    }
  return k;
}

//! x above which exp(-x) is 0 in double (e^-746 = 1.1e-324) [-].
inline constexpr double kExpUnderflow = 746.0;

//! Probability that a pair at mean speed dv fragments, (1 + 3x/2) exp(-3x/2), x =
//! (v_frag/dv)^2 (DustPy `pfrag`, a Maxwell-Boltzmann speed distribution) [-]; 0 at dv =
//! 0, 0.5 at dv = 0.945 v_frag, -> 1 for dv >> v_frag.
inline double fragmentation_probability(double dv, double v_frag) {
  if (dv <= 0.0) return 0.0;
  const double x = 1.5 * (v_frag / dv) * (v_frag / dv);
  // exp(-x) < 2.4e-324, half the least subnormal, rounds to 0 exactly: the same bits
  // without libm's slow underflow path (most pairs of a cell meet far below v_frag)
  if (x > kExpUnderflow) return 0.0;
  return (1.0 + x) * std::exp(-x);
}

//! Probability that an unequal pair at speed dv erodes its target: Krijt et al.'s (2015)
//! rule (spec §5.1: erosion above v_eros, sticking below) with the threshold smoothed
//! as the single-size model's (spec §5.2, physics/erosion.hpp), 1 - S(dv/v_eros) =
//! 1/2 [1 + tanh((dv/v_eros - 1)/w)] [-].
inline double erosion_probability(double dv, double v_eros, double w) {
  return tanh_step((dv / v_eros - 1.0) / w);
}

//! d erosion_probability / d dv = (1 - tanh^2 z) / (2 w v_eros), z = (dv/v_eros - 1)/w
//! [s cm^-1]; 0 where the step is saturated (tanh_step).
inline double erosion_probability_slope(double dv, double v_eros, double w) {
  const double z = (dv / v_eros - 1.0) / w;
  if (std::abs(z) > 20.0) return 0.0;
  const double t = std::tanh(z);
  return 0.5 * (1.0 - t * t) / (w * v_eros);
}

//! The switches of the outcome model (spec §9 style; each off by default).
struct OutcomeSwitches {
  bool fragmentation = false;  //!< similar-size pairs fragment above v_frag
  bool cratering = false;      //!< unequal pairs crater above v_eros (Krijt et al. 2015)
  double v_frag = 100.0;       //!< [cm s^-1] (DustPy default 1 m/s)
  //! [cm s^-1]; DustPy uses v_frag for its cratering pairs too, Krijt et al. (2015)
  //! their own v_eros (spec §5.1).
  double v_eros = 100.0;
  //! The unequal pairs' switch at v_eros: 0, DustPy's Maxwell-Boltzmann probability
  //! (fragmentation_probability); > 0, Krijt et al.'s (2015) threshold smoothed with
  //! this width (erosion_probability, erosion.width) [-].
  double w_eros = 0.0;
};

//! Probability that a pair at speed dv [cm s^-1] fragments (similar sizes) or craters
//! (`crater`: unequal, more than Smoluchowski::crater_bins() bins apart) under the
//! switches s; a process switched off has probability 0 (the pair sticks) [-].
inline double pair_loss_probability(double dv, bool crater, const OutcomeSwitches& s) {
  if (!crater) return s.fragmentation ? fragmentation_probability(dv, s.v_frag) : 0.0;
  if (!s.cratering) return 0.0;
  return s.w_eros > 0.0 ? erosion_probability(dv, s.v_eros, s.w_eros)
                        : fragmentation_probability(dv, s.v_eros);
}

//! p_ij of every pair (N x N row-major): pairs more than engine.crater_bins() bins apart
//! crater with the probability of v_eros, the others fragment with that of v_frag
//! (pair_loss_probability) [-].
inline std::vector<double> fragmentation_probabilities(const Smoluchowski& engine,
                                                       std::span<const double> dv,
                                                       const OutcomeSwitches& s) {
  const int n = engine.size();
  std::vector<double> p(static_cast<std::size_t>(n) * n, 0.0);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j <= i; ++j) {
      const bool crater = i - j > engine.crater_bins();
      const std::size_t ij = static_cast<std::size_t>(i) * n + j;
      const double pf = pair_loss_probability(dv[ij], crater, s);
      p[ij] = pf;
      p[static_cast<std::size_t>(j) * n + i] = pf;
    }
  return p;
}

}  // namespace panoptic::physics::coagulation
