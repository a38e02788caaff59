#pragma once
//! The gas disk (spec §1): stellar parameters, the initial or static surface density
//! profile, and the thermal structure that follows from the temperature power law (or a
//! table). Everything cgs. Profiles are virtual (PowerLawDisk, Lbp74Disk, TableDisk, and
//! a Gaussian bump on either of the first two, BumpedDisk); the thermal structure,
//! midplane density, mean free path and pressure follow from sigma_g(r) and
//! temperature(r) the same way for all of them, and alpha(r) from an AlphaProfile.
#include <memory>
#include <string_view>
#include <vector>

#include "disk/alpha_profile.hpp"
#include "disk/gas_defaults.hpp"
#include "disk/radial_table.hpp"

namespace panoptic {

class Grid;

struct Star {
  double mass = 0.0;        //!< [g]
  double luminosity = 0.0;  //!< [erg s^-1]
};

struct ThermalParams {
  double T_1au = gas_defaults::kT1au;          //!< temperature at 1 au for L = L_sun [K]
  double q = gas_defaults::kQ;                 //!< T ∝ r^-q
  double T_floor = gas_defaults::kTFloor;      //!< [K]
  double mu = gas_defaults::kMu;               //!< mean molecular weight
  double alpha = gas_defaults::kAlpha;         //!< Shakura-Sunyaev alpha (plateau)
  double sigma_mol = gas_defaults::kSigmaMol;  //!< molecular cross section [cm^2]
  double T_sub = gas_defaults::kTSub;          //!< ice sublimation temperature [K]
};

class GasDisk {
 public:
  GasDisk(const Star& star, const ThermalParams& thermal) : star_(star), th_(thermal) {}
  virtual ~GasDisk() = default;

  virtual std::string_view name() const = 0;
  //! Initial (and, for static gas, permanent) gas surface density [g cm^-2].
  virtual double sigma_g(double r) const = 0;
  //! Gas mass of the annulus r1 <= r <= r2, the integral of sigma_g 2 pi r dr [g], in
  //! closed form: what the cell-centre values of sigma_g approximate on the grid (the
  //! run header prints both for the dust).
  virtual double mass_between(double r1, double r2) const = 0;

  const Star& star() const { return star_; }
  const ThermalParams& thermal() const { return th_; }
  //! The radial profile of alpha (constant by default: thermal().alpha everywhere).
  void set_alpha_profile(AlphaProfile profile) { alpha_profile_ = std::move(profile); }
  const AlphaProfile& alpha_profile() const { return alpha_profile_; }
  //! Shakura-Sunyaev alpha at r [-] (spec §1.5): the one alpha of D_g, nu, V_g and h_d.
  double alpha(double r) const { return alpha_profile_.at(r, th_.alpha); }

  //! T = T_1au (L/L_sun)^(1/4) (r/au)^-q, floored at T_floor [K] (spec §1.3).
  virtual double temperature(double r) const;
  //! Isothermal sound speed sqrt(k_B T / (mu m_H)) [cm s^-1] (spec §1.3).
  double c_s(double r) const;
  //! Mean thermal speed sqrt(8/pi) c_s [cm s^-1] (spec §1.3).
  double v_th(double r) const;
  //! Keplerian angular frequency sqrt(G M / r^3) [s^-1] (spec §1.1, §1.3).
  double omega_k(double r) const;
  //! Keplerian speed Omega_K r [cm s^-1] (spec §1.3).
  double v_k(double r) const;
  //! Pressure scale height c_s / Omega_K [cm] (spec §1.3).
  double h_g(double r) const;
  //! Turbulent viscosity = gas diffusivity alpha(r) c_s H [cm^2 s^-1] (spec §1.5,
  //! Sc = 1).
  double nu(double r) const;
  //! Midplane density Sigma / (sqrt(2 pi) H) [g cm^-3] (spec §1.3).
  double rho_mid(double sigma_g, double r) const;
  //! Midplane pressure rho c_s^2 [dyn cm^-2] (spec §1.3).
  double pressure(double sigma_g, double r) const;
  //! Mean free path mu m_H / (sigma_mol rho) [cm] (spec §1.6).
  double mfp(double rho_g) const;
  //! Snow-line radius where T falls to T_sub [cm] (spec §1.7): +inf when the disk is
  //! warmer than T_sub everywhere (T_floor > T_sub, or q = 0 and T > T_sub), 0 when it
  //! is colder everywhere (q = 0), NaN when T rises outward (q < 0: ice inside silicate,
  //! which the model does not describe; validate_scene refuses it with the snow line on).
  virtual double r_snow() const;

 private:
  Star star_;
  ThermalParams th_;
  AlphaProfile alpha_profile_;
};

//! Sigma_g = sigma_1au (r/au)^-p: MMSN for sigma_1au = 1700, p = 1.5 (spec §1.2 A).
class PowerLawDisk : public GasDisk {
 public:
  PowerLawDisk(const Star& star, const ThermalParams& th, double sigma_1au, double p)
      : GasDisk(star, th), sigma_1au_(sigma_1au), p_(p) {}
  std::string_view name() const override { return "powerlaw"; }
  double sigma_g(double r) const override;
  double mass_between(double r1, double r2) const override;

  //! sigma_1au [g cm^-2] that puts the gas mass m [g] between r1 and r2 [cm] on a power
  //! law of index p (disk.sigma_norm = "mass").
  static double sigma_1au_for_mass(double m, double p, double r1, double r2);

 private:
  double sigma_1au_, p_;
};

//! Lynden-Bell & Pringle (1974) similarity profile at t = 0 (spec §1.2 B):
//! Sigma = (2-gamma) M/(2 pi r_c^2) (r/r_c)^-gamma exp[-(r/r_c)^(2-gamma)].
class Lbp74Disk : public GasDisk {
 public:
  Lbp74Disk(const Star& star, const ThermalParams& th, double m_disk, double r_c,
            double gamma)
      : GasDisk(star, th), m_disk_(m_disk), r_c_(r_c), gamma_(gamma) {}
  std::string_view name() const override { return "lbp"; }
  double sigma_g(double r) const override;
  double mass_between(double r1, double r2) const override;

 private:
  double m_disk_, r_c_, gamma_;
};

//! Sigma_g(r) and T(r) from tables (disk.model = "table"), log-log interpolated; the
//! pressure, its gradient (eta, spec §1.4) and the snow line (§1.7) follow from them.
//! ThermalParams' T_1au, q and T_floor are not used.
class TableDisk : public GasDisk {
 public:
  TableDisk(const Star& star, const ThermalParams& th,
            std::shared_ptr<const RadialTable> sigma,
            std::shared_ptr<const RadialTable> temperature)
      : GasDisk(star, th), sigma_(std::move(sigma)), t_(std::move(temperature)) {}
  std::string_view name() const override { return "table"; }
  double sigma_g(double r) const override { return (*sigma_)(r); }
  double mass_between(double r1, double r2) const override {
    return sigma_->annulus_integral(r1, r2);
  }
  double temperature(double r) const override { return (*t_)(r); }
  //! The innermost radius where the table's T falls to T_sub (0, +inf as for the power
  //! law: colder, warmer everywhere).
  double r_snow() const override;

 private:
  std::shared_ptr<const RadialTable> sigma_, t_;
};

//! A Gaussian bump (A > 0) or gap (-1 < A < 0) on a smooth profile:
//! Sigma_g = Sigma_smooth(r) [1 + A exp(-(r - r0)^2 / (2 w^2))], the pressure maximum
//! that traps dust (Pinilla et al. 2012; Dullemond et al. 2018). Same star, temperature
//! and alpha as the smooth disk.
class BumpedDisk : public GasDisk {
 public:
  BumpedDisk(std::unique_ptr<GasDisk> smooth, double amplitude, double r0, double width);
  std::string_view name() const override { return name_; }
  double sigma_g(double r) const override;
  //! The smooth disk's closed form plus the bump's share, by Gauss-Legendre quadrature
  //! on pieces a quarter of the width long.
  double mass_between(double r1, double r2) const override;
  double temperature(double r) const override { return smooth_->temperature(r); }
  double r_snow() const override { return smooth_->r_snow(); }

 private:
  std::unique_ptr<GasDisk> smooth_;
  double amplitude_, r0_, width_;
  std::string name_;
};

//! The initial (or static) surface density profile of the gas (spec §1.2).
struct GasProfile {
  enum class Kind { kPowerLaw, kLbp74, kTable };
  Kind kind = Kind::kPowerLaw;
  double sigma_1au = 1700.0;  //!< power law: Sigma_g at 1 au [g cm^-2]
  double p = 1.5;             //!< power law: Sigma_g ∝ r^-p
  double m_disk = 0.0;        //!< LBP: disk mass [g]
  double r_c = 0.0;           //!< LBP: characteristic radius [cm]
  double gamma = 1.0;         //!< LBP: viscosity index
  std::shared_ptr<const RadialTable> sigma_table;  //!< table: Sigma_g(r) [g cm^-2]
  std::shared_ptr<const RadialTable> t_table;      //!< table: T(r) [K]
  //! Gaussian bump on a power law or LBP profile (amplitude 0: none)
  double bump_amplitude = 0.0;  //!< A [-], > -1
  double bump_r0 = 0.0;         //!< centre [cm]
  double bump_width = 0.0;      //!< w [cm]
};

//! Everything a gas disk is built from, in cgs (src/model/scene_to_physics.hpp fills it
//! from a scene).
struct DiskParams {
  Star star;
  ThermalParams thermal;
  GasProfile profile;
  AlphaProfile alpha;
};

//! Builds the disk of `params`: a PowerLawDisk, an Lbp74Disk or a TableDisk, in a
//! BumpedDisk when the profile has a bump, with the alpha profile of `params`.
std::unique_ptr<GasDisk> make_disk(const DiskParams& params);

//! dlnP/dlnr at cell centres from the pressure of `sigma_g` [per cell]: centred
//! differences in ln r inside, one-sided at the two ends (spec §1.4: numerical gradient).
std::vector<double> dlnp_dlnr_centres(const GasDisk& disk, const Grid& grid,
                                      const std::vector<double>& sigma_g);
//! eta = -1/2 (H/r)^2 dlnP/dlnr at cell centres (spec §1.4).
std::vector<double> eta_centres(const GasDisk& disk, const Grid& grid,
                                const std::vector<double>& sigma_g);

}  // namespace panoptic
