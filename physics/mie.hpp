#pragma once
//! Absorption and scattering efficiencies of a homogeneous sphere (Mie theory), with a
//! geometric-optics limit for size parameters too large for the series. Used by
//! `panoptic observe` for the millimetre opacity of the mass-dominating particle.
//!
//! Conventions (Bohren & Huffman 1983, "Absorption and Scattering of Light by Small
//! Particles", hereafter BH83): refractive index m = n + i k relative to the medium
//! (vacuum), k >= 0 absorbs; size parameter x = 2 pi a / lambda; efficiencies are cross
//! sections over pi a^2.
#include <complex>

namespace panoptic::physics {

//! Efficiencies of one sphere [-]; q_abs = q_ext - q_sca.
struct MieEfficiencies {
  double q_ext = 0.0;
  double q_sca = 0.0;
  double q_abs = 0.0;
  double q_back = 0.0;  //!< backscattering, 4 |S_1(180 deg)|^2 / x^2 (BH83 §4.6)
  double g = 0.0;       //!< asymmetry parameter <cos theta>
  int n_terms = 0;      //!< terms of the series summed (0: geometric optics)
};

//! Mie series (BH83 appendix A, BHMIE, as revised by B. T. Draine): a_n, b_n from the
//! logarithmic derivative D_n(mx) by downward recurrence (BH83 §4.8) started at
//! max(N, |mx|) + 8 |mx|^(1/3) + 15 (BHMIE's + 15 is too close for weakly absorbing
//! spheres), Riccati-Bessel functions by
//! upward recurrence, series truncated after N = x + 4 x^(1/3) + 2 terms (Wiscombe 1980,
//! Appl. Opt. 19, 1505). Requires x > 0 and Re m > 0, Im m >= 0.
MieEfficiencies mie_series(std::complex<double> m, double x);

//! Geometric-optics limit for x >> 1 (van de Hulst 1957, "Light Scattering by Small
//! Particles", §12.3 and §11.22): extinction 2 (half of it diffraction); the fraction of
//! the rays that enter the sphere is 1 - R, R the Fresnel reflectance averaged over the
//! projected disk (unpolarised light); of those a fraction Q_ADT(w) is absorbed along
//! the chord, Q_ADT(w) = 1 + 2 e^-w / w + 2 (e^-w - 1) / w^2 with w = 4 x k (the
//! anomalous-diffraction absorption, which ignores refraction of the chords: exact in
//! the opaque limit w >> 1, approximate for weakly absorbing spheres).
MieEfficiencies geometric_optics(std::complex<double> m, double x);

//! Size parameter above which geometric_optics replaces mie_series [-]. At x = 1e4 the
//! two agree to 0.2 % in q_abs for m = 1.5 + i and for the default ice and silicate at
//! 1.3 mm (opaque spheres, 4 x k >> 1); for weakly absorbing compact spheres (4 x k ~ 1)
//! the ADT chord absorption is 20-30 % low (m = 1.33 + 1e-5 i: 0.215 vs 0.280). The
//! porous aggregates of a run are weakly absorbing too, but their index is within O(phi)
//! of 1, where ADT is accurate (src/observe/README.md, Synthetic observations:
//! < 1 % at 1 Myr).
inline constexpr double kMieMaxSizeParameter = 1e4;

//! mie_series for x <= kMieMaxSizeParameter, geometric_optics above.
MieEfficiencies sphere_efficiencies(std::complex<double> m, double x);

//! Fresnel reflectance of a plane interface vacuum -> m, averaged over the projected
//! disk of a sphere, R = int_0^1 R(mu) 2 mu dmu (mu = cos of the incidence angle) [-].
double disk_averaged_reflectance(std::complex<double> m);

}  // namespace panoptic::physics
