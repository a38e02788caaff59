#pragma once
//! The dust flux operator on the cell faces (spec §6.1, §6.3), shared by the modules that
//! move dust: DustTransport (one population and its passengers) and SizeDistribution
//! (every mass bin with its own St):
//!   F = q v_r - D_d Sigma_g d(q/Sigma_g)/dr,
//!   v_r = -2 St eta v_K/(1+St^2) + v_g/(1+St^2),   D_d = alpha c_s H/(1+St^2)
//! (Youdin & Lithwick 2007 for D_d). Upwind advection of r q (first order, or MUSCL with
//! the van Leer limiter, option `limited`) and centred diffusion of the concentration;
//! the inner face is open (outflow with the upwind state, no diffusive flux, no inflow),
//! the outer face closed. Every function is a template on the scalar type, so that the
//! callers' Jacobians stay exact by AD.
#include <cmath>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "disk/gas_column.hpp"
#include "disk/pressure_gradient.hpp"
#include "disk/viscous_gas.hpp"
#include "src/core/autodiff.hpp"
#include "src/core/units.hpp"
#include "src/solver/grid.hpp"
#include "src/solver/physics_module.hpp"
#include "src/solver/state_layout.hpp"

namespace panoptic {

class GasDisk;

struct DustTransportOptions {
  bool drift = true;      //!< advection by v_r (drift, and gas motion when it evolves)
  bool diffusion = true;  //!< turbulent diffusion
  //! Second-order advection (MUSCL, van Leer 1977 limiter): the face value of r Sigma
  //! (and of each passenger's r Q) is reconstructed from the upwind cell with the limited
  //! slope of the upwind cell, psi(a, b) = 2ab/(a + b) for ab > 0, else 0, a the
  //! difference behind the upwind cell, b the one across the face. The inner face and the
  //! faces whose far upwind cell lies off the grid stay first order.
  bool limited = false;
  //! The Stokes number that sets the drift speed on an interior face: false, the
  //! geometric mean of its two cells' (`face_stokes`); true, each cell's own (flux-vector
  //! splitting: the flow is v(St_a)^+ q_a + v(St_b)^- q_b), so a cell of St >> 1 does not
  //! slow the outflow of its neighbour (tests/bench/results/porous_mmsn.md, "Why the
  //! single size's front creeps"). First-order advection of one population per cell.
  bool upwind_stokes = false;
};

//! The VarInfo of a global variable booking a dust mass (the outflow through r_in, the
//! ice sublimated, a pebble monitor): in units of `mass_unit` [g], in CVODE's error test
//! at the absolute tolerance `sigma_abs_scale` [g cm^-2] over a disk of radius r_out
//! [cm], without a >= 0 constraint (clipping would lose mass).
inline VarInfo booked_mass_info(const std::string& name, const std::string& what,
                                double sigma_abs_scale, double r_out, double mass_unit) {
  return {name, "initial dust mass",
          what + ", in units of the initial dust mass on the grid",
          sigma_abs_scale * units::kPi * r_out * r_out / mass_unit, false};
}

//! The budget terms of the dust that leaves through the open inner face (m_out_inner) and
//! sublimates at the snow line (m_sublimated), from their booked masses [g] at state y.
inline std::vector<BudgetTerm> outflow_budget_terms(
    std::function<double(std::span<const double>)> out,
    std::function<double(std::span<const double>)> sublimated) {
  return {{"m_out_inner", "through r_in", "cumulative dust mass that left through r_in",
           true, std::move(out)},
          {"m_sublimated", "sublimated",
           "cumulative ice that sublimated at the snow line (spec §6.3)", true,
           std::move(sublimated)}};
}

//! What the model reads of the module that carries the dust over the grid: DustTransport
//! (one population per cell) or SizeDistribution (every mass bin), whichever the scene
//! builds (model.kind). The mass on the grid, the pebble fluxes and the booked pebble
//! masses (spec §8) are read through it, so no caller asks which one it is.
class DustCarrier {
 public:
  virtual ~DustCarrier() = default;
  //! Sigma_d of a cell at state y [g cm^-2].
  virtual double sigma_d(int cell, std::span<const double> y) const = 0;
  //! Dust mass flow through every face, positive outward [g s^-1]; n_cells + 1 entries.
  virtual std::vector<double> mass_flow(std::span<const double> y) const = 0;
  //! The unit of the booked masses (the initial dust mass on the grid) [g].
  virtual double mass_unit() const = 0;
};

//! van Leer's limited half-slope a b/(a + b) (for a b > 0), with the derivative
//! (b/(a + b))^2 a' + (a/(a + b))^2 b'. Both weights lie in (0, 1). Differentiating the
//! product a (b/(a + b)) instead divides by a + b, which overflows for the differences of
//! ~1e-300 between the nearly empty bins of a size distribution (a NaN Jacobian entry).
inline double van_leer_half_slope(double a, double b) { return a * (b / (a + b)); }
template <class D>
Eigen::AutoDiffScalar<D> van_leer_half_slope(const Eigen::AutoDiffScalar<D>& a,
                                             const Eigen::AutoDiffScalar<D>& b) {
  const double sum = a.value() + b.value();
  const double share_b = b.value() / sum, share_a = a.value() / sum;
  return Eigen::AutoDiffScalar<D>(
      a.value() * share_b,
      share_b * share_b * a.derivatives() + share_a * share_a * b.derivatives());
}

class DustFaceFlux {
 public:
  //! `viscous` is null for static gas.
  DustFaceFlux(const Grid& grid, const GasDisk& disk, const GasColumn& gas,
               const ViscousStencil* viscous, DustTransportOptions options);

  const DustTransportOptions& options() const { return opt_; }
  const Grid& grid() const { return grid_; }

  //! Stokes number on face f from those of its two cells: the geometric mean (exact for
  //! power laws on the log-spaced grid, where r_f is the geometric mean of the centres);
  //! the inner face takes the first cell's value.
  template <class T>
  static T face_stokes(int f, const T& st_a, const T& st_b) {
    using std::sqrt;
    return f > 0 ? T(sqrt(st_a * st_b)) : st_a;
  }

  //! Dust radial velocity on face f (spec §6.1) [cm s^-1] for the face Stokes number st;
  //! sg_a, sg_b: Sigma_g of the cells a = max(f - 1, 0) and a + 1.
  template <class T>
  T velocity(int f, const T& sg_a, const T& sg_b, const T& st) const {
    using std::log;
    const int a = f > 0 ? f - 1 : 0;
    const T one_plus_st2 = 1.0 + st * st;
    T eta_vk;
    if (gas_.evolves()) {
      const T dlnp = (log(sg_b) - log(sg_a) + (ln_cs_omega_[a + 1] - ln_cs_omega_[a])) /
                     grid_.dlnr_centres(a + 1);
      eta_vk = pressure_gradient_eta(hr2vk_[f], dlnp);
    } else {
      eta_vk = T(eta_vk_static_[f]);
    }
    T v = -2.0 * st * eta_vk / one_plus_st2;  // spec §6.1 drift
    if (gas_.evolves()) {
      // v_g = F_g / Sigma_g on the face (spec §1.2, §6.1)
      v += viscous_->face_velocity(f, sg_a, sg_b) / one_plus_st2;
    }
    return v;
  }

  //! -D_d Sigma_g,f / dr on interior face f (D_d = D_g/(1+St^2), spec §6.1; Sigma_g,f
  //! the geometric mean); sg_a, sg_b of cells f - 1 and f.
  template <class T>
  T diffusion_coefficient(int f, const T& st, const T& sg_a, const T& sg_b) const {
    using std::sqrt;
    return -d_gas_[f] / (1.0 + st * st) * sqrt(sg_a * sg_b) / dr_[f];
  }

  //! The far upwind cell of interior face f for the limited scheme (behind the upwind
  //! cell), or -1 (first order there, or off the grid).
  int far_cell(int f, bool from_left) const {
    const int n = grid_.n_cells();
    return !opt_.limited || !opt_.drift ? -1
           : from_left                  ? (f >= 2 ? f - 2 : -1)
                                        : (f + 1 < n ? f + 1 : -1);
  }

  //! What the flows through face f share: the velocity, the diffusion coefficient and
  //! the far upwind cell of the limited scheme.
  template <class T>
  struct FaceTerms {
    T v;          //!< velocity() (0 without drift) [cm s^-1]
    T diff_coef;  //!< diffusion_coefficient() (0 without diffusion, and at f = 0)
    int far;      //!< far_cell() (-1 at f = 0)
  };
  //! The terms of face f for the face Stokes number st and the gas of its cells, sg_a
  //! and sg_b (cells max(f - 1, 0) and max(f, 1)).
  template <class T>
  FaceTerms<T> face_terms(int f, const T& st, const T& sg_a, const T& sg_b) const {
    const T v = opt_.drift ? velocity(f, sg_a, sg_b, st) : T(0.0);
    const T diff_coef =
        f > 0 && opt_.diffusion ? diffusion_coefficient(f, st, sg_a, sg_b) : T(0.0);
    return {v, diff_coef, f > 0 ? far_cell(f, value_of(v) > 0.0) : -1};
  }

  //! The flow of one transported quantity through interior face f with each cell's dust
  //! drifting at its own speed (`DustTransportOptions::upwind_stokes`): ta and tb are
  //! face f's terms at the St of cell a = f - 1 and of cell b = f, t_mean at their mean
  //! (for the diffusion, as `flow`). First order: 2 pi r_c(a) v_a^+ qa + 2 pi r_c(b)
  //! v_b^- qb, the upwinded r Sigma of `flow`.
  template <class T>
  T split_flow(int f, const FaceTerms<T>& ta, const FaceTerms<T>& tb,
               const FaceTerms<T>& t_mean, const T& sg_a, const T& sg_b, const T& qa,
               const T& qb) const {
    T out(0.0);
    if (value_of(ta.v) > 0.0) out += two_pi_rc_[f - 1] * ta.v * qa;
    if (value_of(tb.v) < 0.0) out += two_pi_rc_[f] * tb.v * qb;
    if (opt_.diffusion) out += two_pi_r_[f] * t_mean.diff_coef * (qb / sg_b - qa / sg_a);
    return out;
  }

  //! The mass-like flow 2 pi r_f F of one transported quantity through face f with the
  //! face's terms `t`, its values qa, qb in the cells of the stencil (f - 1 and f; at
  //! f = 0: 0 and 1), sg_a and sg_b as for face_terms(), and its value q_far in the far
  //! upwind cell t.far (limited scheme); d_far (if not null): d flow / d q_far.
  template <class T>
  T flow(int f, const FaceTerms<T>& t, const T& sg_a, const T& sg_b, const T& qa,
         const T& qb, double q_far, double* d_far) const {
    const T& v = t.v;
    const int far = t.far;
    if (d_far) *d_far = 0.0;
    if (f == 0)  // open inner boundary: outflow with the upwind state, never inflow
      return value_of(v) < 0.0 ? T(two_pi_rc_[0] * v * qa) : T(0.0);
    const bool from_left = value_of(v) > 0.0;
    // Upwind advection of r Sigma (the mass per unit radius / 2 pi) rather than of
    // Sigma: first order either way, but this keeps the steady drift profile Sigma ∝
    // 1/(r v) exact on the grid, so the pebble flux through a face has no truncation
    // error there.
    const double two_pi_r_up = 2.0 * units::kPi * grid_.r_c(from_left ? f - 1 : f);
    T out = two_pi_r_up * v * (from_left ? qa : qb);
    if (far >= 0) {
      // MUSCL with the van Leer limiter on q = 2 pi r_c y (the variable the first-order
      // scheme upwinds): face value q_up + psi(a, b)/2, a = q_up - q_far, b = q_down -
      // q_up, psi = 2ab/(a + b) for ab > 0, else 0 (van Leer 1977; LeVeque 2002 §6.9).
      const T q_up = two_pi_r_up * (from_left ? qa : qb);
      const T q_down =
          2.0 * units::kPi * grid_.r_c(from_left ? f : f - 1) * (from_left ? qb : qa);
      const double q_far_r = two_pi_rc_[far] * q_far;
      const T a = q_up - q_far_r, b = q_down - q_up;
      if ((value_of(a) > 0.0) == (value_of(b) > 0.0) && value_of(a) != 0.0 &&
          value_of(b) != 0.0) {
        // ab/(a + b) as a b/(a + b), the ratio in (0, 1) first: a nearly empty bin of a
        // size distribution has differences of ~1e-170, whose product and square
        // underflow
        out += v * van_leer_half_slope(a, b);
        // d(face value)/d q_far = -(1/2) d psi/d a = -b^2/(a + b)^2
        if (d_far) {
          const double sv = value_of(b) / (value_of(a) + value_of(b));
          *d_far = -value_of(v) * sv * sv * two_pi_rc_[far];
        }
      }
    }
    if (opt_.diffusion) out += two_pi_r_[f] * t.diff_coef * (qb / sg_b - qa / sg_a);
    return out;
  }

 private:
  const Grid& grid_;
  const GasColumn& gas_;
  const ViscousStencil* viscous_;
  DustTransportOptions opt_;
  // Per face (0..n-1): 2 pi r_f, centre spacing, gas diffusivity, (H/r)^2 v_K, and the
  // static eta v_K (used when the gas does not evolve).
  std::vector<double> two_pi_r_, dr_, d_gas_, hr2vk_, eta_vk_static_;
  std::vector<double> two_pi_rc_;    //!< per cell: 2 pi r_c, for the upwinded r Sigma
  std::vector<double> ln_cs_omega_;  //!< per cell: ln(c_s Omega_K), for ln P
};

}  // namespace panoptic
