#pragma once
//! The radiative transfer of `panoptic observe`, per wavelength and cell: absorption
//! opacity of the cell's particle kappa_abs(lambda) = 3 Q_abs / (4 a rho_int)
//! (physics/mie.hpp; porosity by Maxwell-Garnett with vacuum,
//! physics/optical_constants.hpp), or of a size distribution the mass-weighted mean of
//! its bins', kappa_abs = Sum_k sigma_k kappa_abs,k / Sigma_d; and the emission of a
//! geometrically thin slab at the gas temperature T(r), seen at inclination i,
//! absorption only (no albedo reduction, no scattered light):
//!   I_nu(r) = B_nu(T) (1 - exp(-tau_nu / cos i)),  tau_nu = Sigma_d kappa_abs
//! (= Sum_k sigma_k kappa_abs,k).
#include <cstddef>
#include <vector>

#include "src/observe/materials.hpp"
#include "src/observe/particles.hpp"
#include "src/observe/run_snapshot.hpp"

namespace panoptic {

//! Planck function B_nu(T) [erg s^-1 cm^-2 Hz^-1 sr^-1].
double planck_nu(double nu_hz, double T);
//! Surface brightness of a slab [Jy arcsec^-2]: B_nu(T) (1 - exp(-tau / mu)).
double slab_intensity_jy_arcsec2(double nu_hz, double T, double tau, double mu);

//! Per wavelength l and cell i, at index l n_cells + i.
struct CellEmission {
  std::size_t n_cells = 0;
  double mu = 1.0;                //!< cos i
  std::vector<double> nu;         //!< frequency of each wavelength [Hz]
  std::vector<double> kappa_abs;  //!< absorption opacity per gram of dust [cm^2 g^-1]
  std::vector<double> tau;        //!< vertical optical depth Sigma_d kappa_abs
  std::vector<double> intensity;  //!< B_nu(T) (1 - exp(-tau / mu)) [Jy arcsec^-2]
  std::vector<double> b_nu;       //!< B_nu(T) [Jy arcsec^-2]
};

//! The emission of snapshot `s`'s cells at `lambda_mm`, seen at `incl_deg`.
CellEmission cell_emission(const std::vector<double>& lambda_mm, double incl_deg,
                           const RunSnapshot& s, const OpticalMaterials& mat,
                           const CellParticles& p);

}  // namespace panoptic
