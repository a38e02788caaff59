#pragma once
//! The turbulence parameter alpha as a function of radius (spec §1.5 with a radial
//! profile): one alpha serves the gas diffusivity D_g = alpha c_s H, the turbulent
//! relative velocities (V_g^2 ∝ alpha c_s^2, §3), the dust scale height (§2) and, with
//! an evolving gas, the viscosity nu = alpha c_s H (§1.2): the spec has one alpha, no
//! separate alpha_turb and alpha_visc.
#include <cmath>
#include <memory>

#include "disk/radial_table.hpp"

namespace panoptic {

struct AlphaProfile {
  enum class Kind {
    kConstant,  //!< alpha = alpha_0 everywhere
    kGaussian,  //!< alpha = alpha_0 [1 + A exp(-(r - r0)^2 / (2 w^2))]: a bump (A > 0)
                //!< or a dip (-1 < A < 0), e.g. a dead zone's edge or a planet's gap
    kTable      //!< alpha(r) from a table (log-log interpolated), alpha_0 unused
  };
  Kind kind = Kind::kConstant;
  double amplitude = 0.0;                    //!< Gaussian: A [-], > -1
  double r0 = 0.0;                           //!< Gaussian: centre [cm]
  double width = 0.0;                        //!< Gaussian: w [cm]
  std::shared_ptr<const RadialTable> table;  //!< table: alpha(r)

  //! alpha at r [cm] for the plateau alpha_0; exactly alpha_0 for a constant profile.
  double at(double r, double alpha0) const {
    switch (kind) {
      case Kind::kGaussian: {
        const double x = (r - r0) / width;
        return alpha0 * (1.0 + amplitude * std::exp(-0.5 * x * x));
      }
      case Kind::kTable:
        return (*table)(r);
      case Kind::kConstant:
        break;
    }
    return alpha0;
  }
};

}  // namespace panoptic
