#pragma once
//! The size distribution of every cell (spec §15; issue 35): on each radial cell the dust
//! surface density per mass bin, sigma_k [g cm^-2] on the log-spaced mass grid of
//! physics/coagulation/mass_grid.hpp, one state variable per bin. Every bin is
//! transported with its own Stokes number by the flux operator of the single-size model
//! (physics/modules/dust_face_flux.hpp: the same drift, diffusion, boundaries and the
//! booking of the mass through r_in, spec §6.1, §6.3), and coagulates in its cell by the
//! Smoluchowski equation of physics/coagulation/ (sticking with the two-bin split,
//! DustPy's fragmentation and cratering; with erosion on, either erosion.model, Krijt et
//! al.'s 2015 rule on the unequal pairs instead of cratering: spec §15.2,
//! coagulation::outcome_switches).
//!
//! The coefficients of a cell (kernel, fragmentation probabilities, each bin's St) depend
//! on the gas only (compact bins: spec §15.1 with phi = 1): they are computed once for a
//! static gas, and for an evolving gas from the gas at each refresh() (every snapshot,
//! Simulation::refresh_local_gas, as the single-size model's eta and v_r_gas; in between
//! they stay those of the last refresh). The Jacobian is then exact: the engine's dense
//! analytic block per cell, and the transport's face flows by AD over the two cells'
//! sigma_k and Sigma_g.
//!
//! Porous bins (growth.porosity): a second variable per bin and cell, psi_k = sigma_k
//! <1/phi>_m (Okuzumi, Tanaka & Sakagami 2009 volume averaging; spec §15.1), transported
//! by the same flux operator with the same face St as sigma_k: with first-order upwind
//! advection its flow is (psi/sigma)_upwind times sigma's, the tracer moment of spec §6.2
//! and §15.4, and a uniform psi/sigma stays uniform (the van Leer limiter is homogeneous
//! of degree one). The coefficients and the bins' St then depend on the state through
//! u_k = psi_k/sigma_k and are rebuilt from it at every right-hand side and Jacobian (the
//! gas of the last refresh, as compact). Jacobian: the engine's dense 2N x 2N block with
//! the derivatives of K, p_frag and the product porosity by ln u (cell_coefficients with
//! derivatives; forward differences of 1e-6), and the face flows' dependence on u through
//! St (d St/d ln u by the same forward difference), and the compaction floors' levels and
//! relaxation rates (cell_coefficients). A bin's u is bin_porosity()'s
//! (physics/coagulation/porosity.hpp), with the empty-bin scale
//! options.empty_bin_fraction of sigma_scale: the bins' absolute tolerance.
//!
//! Porosity on the track (options.porosity_track): no psi_k; each bin's filling factor
//! is the single-size porosity law's phi(m_k) at its cell's gas
//! (physics/coagulation/porosity_track.hpp), fixed between refreshes as the gas is, and
//! the coefficients and St are those of a compact distribution with these phi_k. Dust
//! crossing the snow line takes the track's phi of the bins it arrives in.
//!
//! Snow line (spec §1.7, §6.3, §15.4; set_snowline()): every cell coagulates with its
//! own monomer species (silicate inside r_snow, ice outside, as the single-size model),
//! on one mass grid for all cells. The mass of bin k that crosses the snow face inward
//! loses f_ice of its mass, m -> (1 - f_ice) m with phi kept (spec §11 #18): the inner
//! cell receives (1 - f_ice) of the flow at the mass (1 - f_ice) m_k, split between the
//! two bins around it as a sticking product (MassGrid::split_mass), psi_k with the same
//! weights; f_ice of the flow is booked in m_sublimated. Outward flows through the face
//! carry their dust unchanged (no condensation, as DustTransport). The Jacobian of these
//! flows is the same AD of the face flow, mapped to the rows that receive it.
//!
//! Planetesimal formation per bin: physics/modules/bin_planetesimals.hpp; erosion on the
//! pairs of bins: physics/coagulation/cell_coefficients.hpp. Not carried (refused by
//! src/model/scene_validation.cpp): bouncing.
#include <span>
#include <string>
#include <vector>

#include "disk/gas_column.hpp"
#include "physics/coagulation/cell_coefficients.hpp"
#include "physics/coagulation/porosity.hpp"
#include "physics/coagulation/smoluchowski.hpp"
#include "physics/drag.hpp"
#include "physics/growth_options.hpp"
#include "physics/modules/dust_face_flux.hpp"
#include "src/solver/physics_module.hpp"
#include "src/solver/state_layout.hpp"

namespace panoptic {

class CellGas;

struct SizeDistributionOptions {
  double m_min = 0.0;             //!< first bin [g]; 0: the monomer mass
  double m_max = 1e5;             //!< the grid reaches the first bin at or above [g]
  double bins_per_decade = 7.0;   //!< [-]
  bool coagulation = true;        //!< Smoluchowski coagulation on (growth.enabled)
  bool mrn = true;                //!< initial MRN distribution, else monomers
  double a_max_init = 1e-4;       //!< MRN: largest initial radius [cm]
  physics::GrowthOptions growth;  //!< drag law, turbulence, fragmentation switch
  //! the empty-bin scale e of bin_porosity() in units of sigma_scale: the bins' absolute
  //! tolerance, solver.atol_sigma (physics/coagulation/porosity.hpp says why) [-]
  double empty_bin_fraction = physics::coagulation::kPorousEmptyBinFraction;
  //! growth.porosity: the bins' filling factors on the single-size law's track at each
  //! cell's gas (porosity.bins = "track", physics/coagulation/porosity_track.hpp)
  //! instead of a volume moment psi_k per bin
  bool porosity_track = false;
};

class SizeDistribution : public PhysicsModule, public DustCarrier {
 public:
  //! Registers sigma_0 ... sigma_{N-1} (cell) and m_out_dust (global). `viscous` is null
  //! for static gas; `species` per cell (the monomers each cell coagulates with; the
  //! mass grid starts at the smallest m0 of them unless options.m_min is set);
  //! `sigma_scale` [g cm^-2] sets CVODE's absolute tolerance scale of every bin;
  //! `dust_mass` [g] is the unit of the booked masses.
  SizeDistribution(StateLayout& layout, const Grid& grid, const GasDisk& disk,
                   const GasColumn& gas, const ViscousStencil* viscous,
                   const CellGas& cell_gas, const std::vector<physics::Species>& species,
                   DustTransportOptions transport, SizeDistributionOptions options,
                   double sigma_scale, double dust_mass);

  //! The first bin's mass [g]: options.m_min, or the smallest monomer mass of `species`.
  static double first_bin_mass(const SizeDistributionOptions& options,
                               const std::vector<physics::Species>& species);
  const physics::coagulation::MassGrid& mass_grid() const { return engine_.grid(); }
  const physics::coagulation::Smoluchowski& engine() const { return engine_; }
  int n_bins() const { return n_bins_; }
  int bin_slot(int k) const { return slot0_ + k; }
  //! psi_k per bin (porosity evolved; the track mode has none).
  bool porous() const { return porous_; }
  //! The bins' filling factors on the track (options.porosity_track).
  bool porosity_track() const { return track_; }
  //! Variables per cell, from bin_slot(0) on: sigma_k, then (porous) psi_k.
  int cell_vars() const { return porous_ ? 2 * n_bins_ : n_bins_; }
  //! Slot of psi_k (porous only).
  int psi_slot(int k) const { return slot0_ + n_bins_ + k; }
  //! Filling factor of bin k of `cell`: sigma_k/psi_k by the rule of bin_porosity()
  //! (1 for an empty bin or compact), or the track's [-].
  double phi(int cell, int k, std::span<const double> y) const;
  //! u = 1/phi of bin k of `cell` with its derivatives by sigma_k and psi_k
  //! (physics/coagulation/porosity.hpp, bin_porosity; porous only).
  physics::coagulation::BinPorosity porosity(int cell, int k,
                                             std::span<const double> y) const;
  //! The coagulation coefficients of `cell` at state y (as the right-hand side uses
  //! them).
  physics::coagulation::CellCoefficients coefficients(int cell,
                                                      std::span<const double> y) const;
  //! The monomers `cell` coagulates with.
  const physics::Species& species(int cell) const { return species_[cell]; }
  //! The gas of `cell` that the bins' St are taken with: that of the last refresh().
  const physics::LocalGas& bin_gas(int cell) const { return gas_now_[cell]; }
  //! St of every bin of every cell at state y, [cell * N + k], as the transport and the
  //! coagulation take them (spec §15.1): compact, of the gas of the last refresh();
  //! porous, by the drag law at each bin's radius and phi at y (bin_properties).
  //! Computed once per state: after the size distribution's own right-hand side at y,
  //! or a reader's call at y (BinPlanetesimals, evaluated before it), they are read, not
  //! computed again.
  std::span<const double> bin_stokes_numbers(std::span<const double> y) const;
  //! St of bin k of `cell` with filling factor phi by the law of bin_stokes_numbers
  //! (compact or on the track, the cached St, whatever phi), for AutoDiff: the
  //! derivatives by phi.
  template <class T>
  T bin_stokes(int cell, int k, const T& phi) const {
    if (!porous_) return T(st_[static_cast<std::size_t>(cell) * n_bins_ + k]);
    return physics::stokes_number(T(engine_.grid().m[k]), phi, species_[cell].rho0,
                                  gas_now_[cell], opt_.growth.drag);
  }
  //! Radius of every bin [cm] (compact, the monomer density of `cell`'s species).
  std::vector<double> bin_radii(int cell = 0) const;
  //! The bin of `cell`'s monomers: the last at or below their mass m0 (0 when the grid
  //! starts above it).
  int monomer_bin(int cell) const;

  //! Where the porosity track of `cell` starts, compact [g]: the initial dust's
  //! mass-weighted mean of ln m_k (initial_cell), the mass of the particle that
  //! represents it in the single-size model (spec §6.2); the monomer mass for
  //! model.init = "monomers". Its sticking products are the track's first aggregates.
  double track_start_mass(int cell) const;
  //! The initial bins of `cell` holding sigma_d [g cm^-2], from its monomer bin up: MRN,
  //! sigma_k ∝ a_k^(1/2) for a_k <= a_max_init (n(a) ∝ a^-3.5 per log bin, as DustPy),
  //! or all in the monomer bin; porous (bins holds cell_vars()): psi_k = sigma_k,
  //! compact aggregates.
  void initial_cell(int cell, double sigma_d, std::span<double> bins) const;
  double sigma_d(int cell,
                 std::span<const double> y) const override;  //!< sum of the bins
  //! The mass-dominating bin of the cell: argmax sigma_k (DustPy's a_rep).
  int dominant_bin(int cell, std::span<const double> y) const;
  //! St of the mass-dominating bin of every cell.
  std::vector<double> dominant_st(std::span<const double> y) const;
  //! Recomputes the coefficients from the gas at state y (evolving gas; no-op static).
  void refresh(std::span<const double> y) const;

  //! Books the cumulative dust mass that crosses face `face` inward (spec §8) in a new
  //! global variable in units of mass_unit(); face 0 is m_out_dust. Before set-up ends.
  int add_monitor(StateLayout& layout, int face);
  int m_out_slot() const { return g_out_; }
  //! Snow line at face `face` (spec §6.3): the dust of every bin crossing it inward
  //! loses f_ice of its mass, booked in the global variable m_sublimated (registered
  //! here, before set-up ends).
  void set_snowline(StateLayout& layout, int face, double f_ice);
  int sublimated_slot() const { return g_sub_; }            //!< -1 without a snow line
  double mass_sublimated(std::span<const double> y) const;  //!< at the snow line [g]
  double mass_unit() const override { return mass_unit_; }
  double mass_out(std::span<const double> y) const;  //!< through r_in [g]
  std::vector<double> mass_flow(std::span<const double> y) const override;

  std::string_view name() const override { return "size_distribution"; }
  //! m_out_inner and m_sublimated (0 without a snow line) [g].
  std::vector<BudgetTerm> budget_terms() const override;
  //! sigma (r, m), sigma_d, the mass-dominating bin's m and a, the mass-weighted mean
  //! mass m_mean, mdot_d, St (r, m) (st_bins), the fraction of each cell's dust in the
  //! top bin (kTopBinFractionField); porous or on the track: phi (r, m), the
  //! mass-dominating bin's phi and rho_int.
  std::vector<OutputField> output_fields() const override;
  //! The fraction of a cell's dust in the mass grid's top bin [-], 0 in a cell without
  //! dust. Products beyond the top bin do not stick
  //! (physics/coagulation/smoluchowski.hpp, as in DustPy), so where it is not small the
  //! largest aggregates are missing and their parents pile up there: RunDiagnostics keeps
  //! its largest value and warns.
  double top_bin_fraction(int cell, std::span<const double> y) const;
  //! The snapshot field of top_bin_fraction, per cell.
  static constexpr const char* kTopBinFractionField = "top_bin_fraction";
  //! Transport: the face flows of every bin; coagulation: the dense block of every cell.
  void declare_pattern(PatternBuilder& pattern) const override;
  //! The transport part of add_rhs: the face flows of every bin (and psi_k) added to
  //! ydot (porous: the bins' St from y).
  void add_transport(std::span<const double> y, std::span<double> ydot) const;
  void add_rhs(double t, std::span<const double> y,
               std::span<double> ydot) const override;
  void add_jacobian(double t, std::span<const double> y,
                    JacobianValues& jac) const override;

 private:
  //! What one worker thread (src/core/worker_threads.hpp) works on a cell with.
  struct WorkerScratch {
    //! a copy of engine_, for its own buffers (the engine's are not shared)
    physics::coagulation::Smoluchowski engine;
    std::vector<double> out;                        //!< the engine's rates or block
    std::vector<double> phi;                        //!< porous, per bin
    physics::coagulation::BinProperties bins;       //!< porous, per bin
    physics::coagulation::PerturbedBins perturbed;  //!< porous Jacobian
    //! porous: the coefficients of the cell at hand (porous_coefficients), so that no
    //! cell keeps their N x N matrices
    physics::coagulation::CellCoefficients coef;
    //! porous: the pair speeds of the cell at hand (CoefficientWorkspace::speeds_in)
    physics::coagulation::CoefficientWorkspace::PairSpeedScratch pair_speeds;
  };

  //! The coefficients and St of every bin of `cell` from its gas (compact; with
  //! track_, the track's filling factors first).
  void build_cell(int cell, const physics::LocalGas& gas) const;
  //! The outcome model of `cell`'s species (DustPy's, with erosion Krijt et al.'s on the
  //! unequal pairs: spec §15.2).
  physics::coagulation::CellModel cell_model(int cell) const;
  //! Porous: St and (with `derivatives`) d St/d ln u of every bin of every cell from
  //! state y, and with `coefficients` every cell's coefficients into coef_ (for
  //! coefficients()). St are not computed again for the state of st_state_ (without
  //! `derivatives`). The right-hand side and the Jacobian build the coefficients cell by
  //! cell where they read them (porous_coefficients), and no cell keeps them.
  void update_porous(std::span<const double> y, bool coefficients,
                     bool derivatives) const;
  //! Porous: the coefficients of `cell` at state y, with `derivatives` also by ln u
  //! (after update_stokes with derivatives for the cell's perturbed bins), in the
  //! worker's storage w.coef: valid until the worker's next call.
  const physics::coagulation::CellCoefficients& porous_coefficients(
      int cell, std::span<const double> y, bool derivatives, WorkerScratch& w) const;
  //! Porous: St (and with `derivatives` d St/d ln u, and the perturbed bins in
  //! w.perturbed) of the bins of `cell` at state y.
  void update_stokes(int cell, std::span<const double> y, bool derivatives,
                     WorkerScratch& w) const;

  //! A row that the flow through a face feeds: ydot[row] += weight * flow / divisor.
  struct FlowTarget {
    long row;
    double weight, divisor;
  };
  //! Where the flow of bin k's sigma_k (or with `psi` its psi_k) through face f goes:
  //! the cell right of the face gains it, the cell left of it and the booked masses
  //! (m_out_dust at f = 0, a monitor; not for psi) lose it (an outflow, < 0, books +).
  //! `inward` (sigma_k's flow < 0) through the snow face: the inner cell receives
  //! (1 - f_ice) of it over the two bins of (1 - f_ice) m_k, m_sublimated the rest.
  void flow_targets(int f, int k, bool psi, bool inward,
                    std::vector<FlowTarget>& targets) const;
  //! A new global variable booking a dust mass in units of mass_unit() (DustTransport's
  //! add_booked_mass); before set-up ends.
  int add_booked_mass(StateLayout& layout, const std::string& name,
                      const std::string& what) const;
  //! The Sigma_g of the cells of face f's stencil at state y.
  std::pair<double, double> face_gas(int f, std::span<const double> y) const;

  const StateLayout& layout_;
  const Grid& grid_;
  const GasColumn& gas_;
  const CellGas& cell_gas_;
  const std::vector<physics::Species>& species_;
  DustFaceFlux flux_;
  SizeDistributionOptions opt_;
  physics::coagulation::Smoluchowski engine_;
  bool porous_ = false;
  bool track_ = false;  //!< options.porosity_track with growth.porosity
  int n_bins_ = 0, slot0_ = -1, g_out_ = -1;
  double mass_unit_ = 1.0;
  double empty_scale_ = 0.0;       //!< e of bin_porosity() [g cm^-2]
  std::vector<int> monitor_slot_;  //!< per face: global slot of its booking, or -1
  int snow_face_ = -1, g_sub_ = -1;
  double f_ice_ = 0.0;
  //! per bin k: the two bins of (1 - f_ice) m_k (MassGrid::split_mass)
  std::vector<physics::coagulation::MassGrid::MassSplit> snow_split_;
  // per cell: the coagulation coefficients and the bins' St (refresh())
  mutable std::vector<physics::coagulation::CellCoefficients> coef_;
  mutable std::vector<double> st_;  //!< [cell * N + k]
  //! track_: each bin's filling factor at the gas of the last refresh [cell * N + k]
  mutable std::vector<double> track_phi_;
  //! porous: the state st_ was computed at (empty: none since the last refresh())
  mutable std::vector<double> st_state_;
  //! porous, Jacobian: d St / d ln u of every bin [cell * N + k]
  mutable std::vector<double> dst_dlnu_;
  mutable std::vector<physics::LocalGas> gas_now_;  //!< per cell, of the last refresh
  //! porous, per cell: what cell_coefficients reuses from call to call
  mutable std::vector<physics::coagulation::CoefficientWorkspace> workspace_;
  mutable std::vector<WorkerScratch> workers_;
  //! workers_, one per worker thread
  std::vector<WorkerScratch>& workers() const;
};

}  // namespace panoptic
