#pragma once
//! Optical constants of the dust for `panoptic observe`: tables of the complex refractive
//! index m = n + i k against wavelength (set per species in the scene, [observe] keys in
//! src/scene/scene_keys.cpp), effective-medium rules for porous aggregates and for the
//! ice-silicate mix, and the absorption opacity of one sphere.
#include <complex>
#include <span>
#include <string>
#include <vector>

namespace panoptic::physics {

//! m(lambda) of one material from a table: n interpolated linearly and k log-linearly
//! in ln lambda (k spans decades); no extrapolation.
class OpticalTable {
 public:
  //! lambda_mm increasing, n >= 1... (any n > 0), k >= 0; equal lengths >= 2. Throws
  //! std::invalid_argument naming `name` otherwise.
  OpticalTable(std::string name, std::vector<double> lambda_mm, std::vector<double> n,
               std::vector<double> k);
  //! m at lambda [mm]; throws std::out_of_range naming the table's range outside it.
  std::complex<double> at(double lambda_mm) const;
  bool covers(double lambda_mm) const;
  double lambda_min_mm() const { return lambda_mm_.front(); }
  double lambda_max_mm() const { return lambda_mm_.back(); }
  const std::string& name() const { return name_; }

 private:
  std::string name_;
  std::vector<double> lambda_mm_, n_, k_;
};

//! Maxwell-Garnett rule (Bohren & Huffman 1983, eq. 8.50): inclusions of dielectric
//! function eps_i at volume fraction f in a matrix eps_m,
//! eps = eps_m (eps_i + 2 eps_m + 2 f (eps_i - eps_m)) / (eps_i + 2 eps_m - f (eps_i -
//! eps_m)).
std::complex<double> maxwell_garnett(std::complex<double> eps_m,
                                     std::complex<double> eps_i, double f);

//! Bruggeman rule for two components (Bohren & Huffman 1983, eq. 8.51), volume
//! fractions 1 - f2 and f2: f1 (e1 - e)/(e1 + 2e) + f2 (e2 - e)/(e2 + 2e) = 0, i.e.
//! 2 e^2 - B e - e1 e2 = 0 with B = (3 f1 - 1) e1 + (3 f2 - 1) e2; the root with
//! Im e >= 0 (the physical branch; it is unique when the inputs absorb).
std::complex<double> bruggeman(std::complex<double> eps1, std::complex<double> eps2,
                               double f2);

//! Refractive index of a porous aggregate of filling factor phi: Maxwell-Garnett with
//! vacuum as the matrix and the solid as inclusions of volume fraction phi, (eps - 1) /
//! (eps + 2) = phi (eps_s - 1)/(eps_s + 2) (Kataoka et al. 2014, A&A 568, A42, §2.2,
//! eq. 3, for porous aggregates at mm wavelengths). In the dilute limit an aggregate
//! small against the wavelength absorbs per gram as its solid does (Rayleigh).
std::complex<double> porous_index(std::complex<double> m_solid, double phi);

//! Absorption opacity per gram of dust of a sphere of radius a [cm] and internal
//! density rho_int [g cm^-3] with refractive index m at wavelength lambda [cm]:
//! kappa = 3 Q_abs / (4 a rho_int) [cm^2 g^-1] (pi a^2 Q_abs over (4/3) pi a^3 rho_int).
double kappa_abs(std::complex<double> m, double a_cm, double rho_int, double lambda_cm);

}  // namespace panoptic::physics
