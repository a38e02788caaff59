#pragma once
//! Radial transport of the dust surface density (spec §6.1, §6.3):
//!   dSigma_d/dt + (1/r) d(r F_d)/dr = 0,
//!   F_d = Sigma_d v_r - D_d Sigma_g d(Sigma_d/Sigma_g)/dr,
//!   v_r = -2 St eta v_K/(1+St^2) + v_g/(1+St^2),   D_d = alpha c_s H/(1+St^2)
//! (Youdin & Lithwick 2007 for D_d). Finite volumes on the log grid: upwind advection
//! (first order, or second order with a van Leer-limited reconstruction, option
//! `limited`) and centred diffusion of the concentration on the faces, so the mass moved
//! between cells cancels exactly and the budget closes to round-off.
//! Boundaries (spec §6.3): inner face open (outflow with the upwind state, no diffusive
//! flux, no inflow; the mass that leaves is booked in the global variable m_out_dust);
//! outer face closed (zero flux).
//! Snow line (spec §6.3, optional): inward flow through its face loses f_ice of its mass.
//! Other conserved quantities that ride with the dust (the log-moments Q_m, Q_phi of
//! spec §6.2) are "passengers": add_passenger() transports them with the same operator.
//! Jacobian: exact, by forward-mode AD of the face flux over its two-cell stencil; with
//! the limited scheme the far upwind cell's entries are added from the limiter's
//! analytic derivative (the AD vector holds two cells).
#include <array>
#include <span>
#include <string>
#include <vector>

#include "disk/gas_column.hpp"
#include "physics/modules/cell_range_form.hpp"
#include "physics/modules/dust_face_flux.hpp"
#include "physics/stokes_model.hpp"
#include "src/solver/state_layout.hpp"

namespace panoptic {

class GasDisk;
class Grid;
struct ViscousStencil;

class DustTransport : public CellRangeForm<DustTransport>, public DustCarrier {
 public:
  //! Registers Sigma_d (cell) and m_out_dust (global). `viscous` is null for static gas.
  //! `sigma_scale` [g cm^-2] sets CVODE's absolute tolerance scale; `dust_mass` [g] is
  //! the unit of the booked outflow.
  DustTransport(StateLayout& layout, const Grid& grid, const GasDisk& disk,
                const GasColumn& gas, const ViscousStencil* viscous,
                const StokesModel& stokes, DustTransportOptions options,
                double sigma_scale, double dust_mass);

  //! Transports another cell variable with the same flux operator (before set-up ends).
  void add_passenger(int slot) { transported_.push_back(slot); }

  //! Snow line at face `face` (spec §6.3): icy dust crossing it inward loses the fraction
  //! f_ice of its mass (booked in the global variable m_sublimated, registered here);
  //! the log-moment passenger `qm_slot` follows m -> (1 - f_ice) m, the others (phi) are
  //! kept per unit mass. Call before set-up ends.
  void set_snowline(StateLayout& layout, int face, double f_ice, int qm_slot);
  int sublimated_slot() const { return g_sub_; }

  //! Records the cumulative dust mass that crosses face `face` inward (spec §8, pebble
  //! flux) in a new global variable, in units of mass_unit(); returns its global slot.
  //! Face 0 is r_in, already booked as m_out_dust. Call before set-up ends.
  int add_monitor(StateLayout& layout, int face);

  std::string_view name() const override { return "dust_transport"; }
  void declare_pattern(PatternBuilder& pattern) const override;
  //! The range form of add_rhs() and add_jacobian() (CellRangeForm).
  void add_rhs_cells(double t, std::span<const double> y, std::span<double> ydot, int lo,
                     int hi) const;
  void add_jacobian_cells(double t, std::span<const double> y, JacobianValues& jac,
                          int lo, int hi) const;

  int sigma_slot() const { return slot_; }
  int m_out_slot() const { return g_out_; }
  //! A new global variable booking a dust mass `name` ("m_sublimated"; `what` describes
  //! it), in units of mass_unit() (the initial dust mass on the grid), in CVODE's error
  //! test at the absolute tolerance of Sigma_d over the disk, without a >= 0 constraint:
  //! the variable a sink of dust books what it removes in (physics/README.md, Adding a
  //! physical process). Before StateLayout::freeze(); returns its global slot.
  int add_booked_mass(StateLayout& layout, const std::string& name,
                      const std::string& what) const;
  //! The budget terms it books: the mass through r_in (m_out_inner) and the ice
  //! sublimated at the snow line (m_sublimated; 0 without a snow line) [g].
  std::vector<BudgetTerm> budget_terms() const override;
  //! sigma_d, v_r and mdot_d.
  std::vector<OutputField> output_fields() const override;
  double mass_out(std::span<const double> y) const;         //!< through r_in [g]
  double mass_sublimated(std::span<const double> y) const;  //!< at the snow line [g]
  double sigma_d(int cell, std::span<const double> y) const override {
    return y[layout_.index(cell, slot_)];
  }
  double mass_unit() const override { return mass_unit_; }
  std::vector<double> mass_flow(std::span<const double> y) const override;
  //! Dust radial velocity on every face [cm s^-1] (0 on the outer face). With
  //! `upwind_stokes`, v(St_a)^+ + v(St_b)^-: the speed of the dust that crosses (both
  //! terms are non-zero only on a face where the drift converges).
  std::vector<double> face_velocity(std::span<const double> y) const;

 private:
  static constexpr int kMaxVars = 8;
  //! Mass-like flows 2 pi r_f F through face f for every transported variable.
  //! ya, yb: states of the two cells of the stencil (f-1 and f; at f = 0: 0 and 1).
  //! y: the whole state, for the far upwind cell of the limited scheme (values only);
  //! d_far (if not null): d flows[k] / d y[far cell, transported k]; returns the far
  //! cell, or -1 when the flows do not depend on one.
  template <class T>
  int face_flows(int f, const T* ya, const T* yb, std::span<const double> y, T* flows,
                 double* d_far = nullptr) const;
  template <class T>
  T velocity(int f, const T* ya, const T* yb, const T& st) const;
  //! What the inner cell of face f receives of `flows` (all of it, except for inward
  //! flow through the snow line), and the mass flow that sublimates there.
  //! `inward`: the sign of the dust flow (it decides whether the ice sublimates), given
  //! apart so that the map can be applied to derivatives of the flows too.
  template <class T>
  void received_flows(int f, const T* flows, T* received, T& sublimated,
                      bool inward) const;

  const Grid& grid_;
  const GasColumn& gas_;
  const StokesModel& stokes_;
  DustFaceFlux flux_;  //!< the flux operator (spec §6.1), shared with SizeDistribution
  DustTransportOptions opt_;
  int slot_ = -1, g_out_ = -1;
  double mass_unit_ = 1.0;
  std::vector<int> transported_;
  int snow_face_ = -1, g_sub_ = -1, snow_qm_slot_ = -1;
  std::vector<int>
      monitor_slot_;  //!< per face: global slot of its cumulative flow, or -1
  double f_ice_ = 0.0;
};

}  // namespace panoptic
