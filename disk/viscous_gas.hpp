#pragma once
//! Viscous evolution of the gas surface density (spec §1.2; Lynden-Bell & Pringle 1974):
//!   dSigma_g/dt = (3/r) d/dr [ r^(1/2) d/dr (nu Sigma_g r^(1/2)) ],   nu = alpha c_s H,
//! in flux form dSigma_g/dt + (1/r) d(r F_g)/dr = 0 with F_g = -(3/r^(1/2)) d(nu Sigma_g
//! r^(1/2))/dr = Sigma_g v_g on the cell faces. Boundaries: zero torque at r_in
//! (the mass that leaves through r_in is booked in the global variable m_out_gas), zero
//! flux at r_out. Owns the Sigma_g cell variable.
//! Inner boundary (gas.inner_bc): free_flow (default) lets the gas leave at the steady
//! accretion rate of the first cell, Mdot = 3 pi nu Sigma_g (Lynden-Bell & Pringle 1974:
//! the rate far from any torque), as if the disk went on inside r_in; zero_torque sets
//! nu Sigma_g r^(1/2) = 0 on the inner face (a stellar surface or cavity edge at r_in).
#include <cmath>
#include <memory>
#include <vector>

#include "disk/gas_column.hpp"
#include "src/solver/physics_module.hpp"
#include "src/solver/state_layout.hpp"

namespace panoptic {

class GasDisk;
class Grid;

//! Geometry and viscosity data of the viscous flux, shared with the dust drift (v_g).
struct ViscousStencil {
  bool zero_torque = false;       //!< inner boundary: nu Sigma r^(1/2) = 0 at r_in
  std::vector<double> g_coef;     //!< nu(r_c) sqrt(r_c) per cell [cm^2.5 s^-1]
  std::vector<double> face_coef;  //!< flux per unit difference of nu Sigma r^(1/2)
  //! Gas flux through face f (0..n-1) [g cm^-1 s^-1]. Interior faces: from the columns
  //! of cells a = f-1 and b = f. Inner face (f = 0): from cell a = 0 alone (b unused):
  //! free flow, Mdot = -3 pi nu Sigma_g of the first cell, the steady accretion rate, as
  //! if the disk went on inside r_in; zero torque, nu Sigma_g r^(1/2) = 0 on the face.
  template <class T>
  T face_flux(int f, const T& sigma_a, const T& sigma_b) const {
    if (f == 0) return face_coef[0] * (g_coef[0] * sigma_a);
    return face_coef[f] * (g_coef[f] * sigma_b - g_coef[f - 1] * sigma_a);
  }
  //! Gas radial velocity on face f, v_g = F_g / Sigma_g (spec §1.2, §6.1) [cm s^-1]:
  //! over the geometric mean of the two cells' Sigma_g, on the inner face the first
  //! cell's (the dust drift's, and the particle laws' via Simulation::refresh_local_gas).
  template <class T>
  T face_velocity(int f, const T& sigma_a, const T& sigma_b) const {
    using std::sqrt;
    const T sigma_face = f > 0 ? T(sqrt(sigma_a * sigma_b)) : sigma_a;
    return face_flux(f, sigma_a, sigma_b) / sigma_face;
  }
};

ViscousStencil make_viscous_stencil(const GasDisk& disk, const Grid& grid,
                                    bool zero_torque);

class ViscousGas : public PhysicsModule {
 public:
  //! Registers Sigma_g (cell) and m_out_gas (global) with the layout.
  ViscousGas(StateLayout& layout, const GasDisk& disk, const Grid& grid,
             double sigma_scale, bool zero_torque);

  std::string_view name() const override { return "viscous_gas"; }
  void declare_pattern(PatternBuilder& pattern) const override;
  void add_rhs(double t, std::span<const double> y,
               std::span<double> ydot) const override;
  void add_jacobian(double t, std::span<const double> y,
                    JacobianValues& jac) const override;

  //! m_out_gas.
  std::vector<OutputField> output_fields() const override;
  int sigma_slot() const { return slot_; }
  int m_out_slot() const { return g_out_; }
  const ViscousStencil& stencil() const { return stencil_; }
  //! Mass unit of the booked global variable [g].
  double mass_unit() const { return mass_unit_; }

 private:
  const StateLayout& layout_;
  const Grid& grid_;
  ViscousStencil stencil_;
  int slot_ = -1, g_out_ = -1;
  double mass_unit_ = 1.0;
};

}  // namespace panoptic
