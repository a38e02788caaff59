#include "physics/modules/size_distribution.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "physics/coagulation/porosity_track.hpp"
#include "physics/modules/porous_growth.hpp"
#include "physics/particle.hpp"
#include "src/core/worker_threads.hpp"

namespace panoptic {

namespace coag = physics::coagulation;

SizeDistribution::SizeDistribution(StateLayout& layout, const Grid& grid,
                                   const GasDisk& disk, const GasColumn& gas,
                                   const ViscousStencil* viscous, const CellGas& cell_gas,
                                   const std::vector<physics::Species>& species,
                                   DustTransportOptions transport,
                                   SizeDistributionOptions options, double sigma_scale,
                                   double dust_mass)
    : layout_(layout),
      grid_(grid),
      gas_(gas),
      cell_gas_(cell_gas),
      species_(species),
      flux_(grid, disk, gas, viscous, transport),
      opt_(options),
      engine_(coag::MassGrid(first_bin_mass(options, species), options.m_max,
                             options.bins_per_decade),
              options.coagulation ? coag::fragmentation_model(options.growth)
                                  : coag::FragmentationModel{}),
      porous_(options.growth.porosity && !options.porosity_track),
      track_(options.growth.porosity && options.porosity_track),
      n_bins_(engine_.size()),
      mass_unit_(dust_mass),
      empty_scale_(options.empty_bin_fraction * sigma_scale) {
  layout.allow_wide_cells();
  for (int k = 0; k < n_bins_; ++k) {
    // no >= 0 constraint, as Sigma_d of the single-size model (dust_transport.cpp says
    // why): a bin's negative excursions are integration error held to atol
    const int slot = layout.add_cell_var(
        {"sigma_" + std::to_string(k), "g cm^-2",
         "dust surface density in mass bin " + std::to_string(k) + " (spec §15.1)",
         sigma_scale, false});
    if (k == 0) slot0_ = slot;
  }
  for (int k = 0; porous_ && k < n_bins_; ++k)  // psi_k >= sigma_k: the same scale
    layout.add_cell_var({"psi_" + std::to_string(k), "g cm^-2",
                         "volume measure of mass bin " + std::to_string(k) +
                             ", sigma_k <1/phi>_m (spec §15.1)",
                         sigma_scale, false});
  const double r_out = grid.r_f(grid.n_cells());
  g_out_ = layout.add_global_var(booked_mass_info(
      "m_out_dust", "dust mass that left through r_in", sigma_scale, r_out, dust_mass));
  const int n = grid.n_cells();
  coef_.resize(n);
  st_.resize(static_cast<std::size_t>(n) * n_bins_);
  if (track_) track_phi_.resize(st_.size());
  dst_dlnu_.assign(st_.size(), 0.0);
  for (int i = 0; i < n; ++i) {
    gas_now_.push_back(cell_gas.reference(i));
    build_cell(i, gas_now_[i]);
  }
}

double SizeDistribution::first_bin_mass(const SizeDistributionOptions& options,
                                        const std::vector<physics::Species>& species) {
  if (options.m_min > 0.0) return options.m_min;
  // One grid for all cells, from the lightest monomers on it (the icy ones, rho0 below
  // the silicates'): every cell's monomers then lie at or above the first bin, where its
  // dust starts (monomer_bin); a grid from the heavier monomers would start the lighter
  // species' dust above its monomer mass. Lighter still are the silicate cores of the
  // smallest icy grains after sublimation, (1 - f_ice) m0: they go into the first bin
  // (MassGrid::split_mass), keeping their mass.
  double m0 = species[0].m0;
  for (const physics::Species& sp : species) m0 = std::min(m0, sp.m0);
  return m0;
}

coag::CellModel SizeDistribution::cell_model(int cell) const {
  // DustPy's outcome model, with erosion Krijt et al.'s on the unequal pairs (spec §15.2)
  const physics::Species& sp = species_[cell];
  return {sp, opt_.growth, coag::outcome_switches(opt_.growth, sp), empty_scale_, {}};
}

void SizeDistribution::build_cell(int cell, const physics::LocalGas& gas) const {
  const int nb = n_bins_;
  const physics::Species& sp = species_[cell];
  std::vector<double> phi(nb, 1.0);
  coag::CellModel model = cell_model(cell);
  if (track_) {
    const std::span<double> track(&track_phi_[static_cast<std::size_t>(cell) * nb],
                                  static_cast<std::size_t>(nb));
    coag::track_filling_factors(engine_.grid().m, sp, gas, opt_.growth, track,
                                track_start_mass(cell));
    phi.assign(track.begin(), track.end());
    model.bin_phi = track;
  }
  const coag::BinProperties bins =
      coag::bin_properties(engine_.grid(), phi, sp.rho0, gas, opt_.growth.drag);
  std::copy(bins.St.begin(), bins.St.end(),
            st_.begin() + static_cast<std::ptrdiff_t>(cell) * nb);
  if (!opt_.coagulation || porous_) return;  // porous: update_porous()
  const std::vector<double> sigma(nb, 0.0);
  coef_[cell] = coag::cell_coefficients(engine_, sigma, {}, gas, model);
}

void SizeDistribution::refresh(std::span<const double> y) const {
  if (!gas_.evolves()) return;
  st_state_.clear();  // build_cell() sets the compact St of the new gas
  for (int i = 0; i < grid_.n_cells(); ++i)
    gas_now_[i] = cell_gas_.at(i, &y[layout_.index(i, 0)]);
  // each cell writes its own St and coefficients
  parallel_for(grid_.n_cells(), [&](int i, int) { build_cell(i, gas_now_[i]); });
}

double SizeDistribution::phi(int cell, int k, std::span<const double> y) const {
  if (track_) return track_phi_[static_cast<std::size_t>(cell) * n_bins_ + k];
  return porous_ ? porosity(cell, k, y).phi() : 1.0;
}

coag::BinPorosity SizeDistribution::porosity(int cell, int k,
                                             std::span<const double> y) const {
  // the engine's rule (cell_coefficients, Smoluchowski)
  return coag::bin_porosity(y[layout_.index(cell, bin_slot(k))],
                            y[layout_.index(cell, psi_slot(k))], empty_scale_);
}

std::vector<SizeDistribution::WorkerScratch>& SizeDistribution::workers() const {
  const auto n = static_cast<std::size_t>(worker_threads());
  while (workers_.size() < n) workers_.push_back({engine_, {}, {}, {}, {}, {}, {}});
  return workers_;
}

void SizeDistribution::update_stokes(int cell, std::span<const double> y,
                                     bool derivatives, WorkerScratch& w) const {
  const int nb = n_bins_;
  std::vector<double>& phi_k = w.phi;
  phi_k.resize(nb);
  const coag::BinProperties& bins = w.bins;
  const physics::LocalGas& gas = gas_now_[cell];
  const double rho0 = species_[cell].rho0;
  for (int k = 0; k < nb; ++k) phi_k[k] = phi(cell, k, y);
  coag::bin_properties(engine_.grid(), phi_k, rho0, gas, opt_.growth.drag, w.bins);
  const std::size_t off = static_cast<std::size_t>(cell) * nb;
  std::copy(bins.St.begin(), bins.St.end(),
            st_.begin() + static_cast<std::ptrdiff_t>(off));
  if (!derivatives) return;
  // d St / d ln u by the forward difference of cell_coefficients, on the perturbed bins
  // it is then given
  coag::perturbed_bins(engine_.grid().m, phi_k, rho0, gas, opt_.growth.drag, w.perturbed);
  for (int k = 0; k < nb; ++k)
    dst_dlnu_[off + k] = (w.perturbed.st[k] - bins.St[k]) / coag::kLnUStep;
}

void SizeDistribution::update_porous(std::span<const double> y, bool coefficients,
                                     bool derivatives) const {
  workspace_.resize(grid_.n_cells());
  if (opt_.coagulation) {
    // one table of the pairs' mass terms for every cell (the same grid)
    workspace_[0].set_grid(engine_.grid().m);
    for (auto& w : workspace_)
      if (w.masses != workspace_[0].masses) w.share_grid(workspace_[0]);
  }
  std::vector<WorkerScratch>& ws = workers();
  // the St of this state may have been computed already (bin_stokes_numbers); the
  // Jacobian's d St / d ln u are computed with them
  const bool stokes = derivatives || !std::ranges::equal(y, st_state_);
  // each cell writes its own St, d St / d ln u, workspace and coefficients
  parallel_for(grid_.n_cells(), [&](int i, int worker) {
    WorkerScratch& w = ws[static_cast<std::size_t>(worker)];
    if (stokes) update_stokes(i, y, derivatives, w);
    if (!coefficients || !opt_.coagulation) return;
    coef_[i] = porous_coefficients(i, y, false, w);
  });
  if (stokes) st_state_.assign(y.begin(), y.end());
}

const coag::CellCoefficients& SizeDistribution::porous_coefficients(
    int cell, std::span<const double> y, bool derivatives, WorkerScratch& w) const {
  const long base = layout_.index(cell, slot0_);
  // the Jacobian's forward differences run on the cell's perturbed bins
  // (update_stokes again: the same St and d St / d ln u as update_porous wrote)
  if (derivatives) update_stokes(cell, y, true, w);
  workspace_[cell].speeds_in = &w.pair_speeds;  // for this call (the worker's)
  w.coef = coag::cell_coefficients(
      engine_, y.subspan(base, n_bins_), y.subspan(base + n_bins_, n_bins_),
      gas_now_[cell], cell_model(cell), derivatives, &workspace_[cell], std::move(w.coef),
      derivatives ? &w.perturbed : nullptr);
  workspace_[cell].speeds_in = nullptr;
  return w.coef;
}

std::span<const double> SizeDistribution::bin_stokes_numbers(
    std::span<const double> y) const {
  if (porous_ && !std::ranges::equal(y, st_state_)) update_porous(y, false, false);
  return st_;
}

coag::CellCoefficients SizeDistribution::coefficients(int cell,
                                                      std::span<const double> y) const {
  if (porous_) update_porous(y, true, false);
  return coef_[cell];
}

std::vector<double> SizeDistribution::bin_radii(int cell) const {
  std::vector<double> a(n_bins_);
  for (int k = 0; k < n_bins_; ++k)
    a[k] = physics::radius(engine_.grid().m[k], 1.0, species_[cell].rho0);
  return a;
}

int SizeDistribution::monomer_bin(int cell) const {
  // 1e-9: the monomer mass that set the first bin is that bin, to round-off
  return std::max(0, engine_.grid().lower_bin(species_[cell].m0 * (1.0 + 1e-9)));
}

double SizeDistribution::track_start_mass(int cell) const {
  std::vector<double> bins(n_bins_);
  initial_cell(cell, 1.0, bins);
  double ln_m = 0.0;
  for (int k = 0; k < n_bins_; ++k) ln_m += bins[k] * std::log(engine_.grid().m[k]);
  return std::exp(ln_m);
}

void SizeDistribution::initial_cell(int cell, double sigma_d,
                                    std::span<double> bins) const {
  std::fill(bins.begin(), bins.end(), 0.0);
  const int k0 = monomer_bin(cell);
  if (!opt_.mrn) {
    bins[k0] = sigma_d;
    if (bins.size() > static_cast<std::size_t>(n_bins_)) bins[n_bins_ + k0] = sigma_d;
    return;
  }
  // n(a) ∝ a^-3.5: the mass per logarithmic bin ∝ a^4 n(a) ∝ a^(1/2) (DustPy's MRN
  // initial condition, distExp = -3.5); the monomer bin always holds some
  const std::vector<double> a = bin_radii(cell);
  double total = 0.0;
  for (int k = k0; k < n_bins_ && (k == k0 || a[k] <= opt_.a_max_init); ++k) {
    bins[k] = std::sqrt(a[k]);
    total += bins[k];
  }
  for (int k = 0; k < n_bins_; ++k) bins[k] *= sigma_d / total;
  // porous: compact at the start, psi_k = sigma_k (phi = 1)
  for (std::size_t k = n_bins_; k < bins.size(); ++k) bins[k] = bins[k - n_bins_];
}

double SizeDistribution::sigma_d(int cell, std::span<const double> y) const {
  const double* s = &y[layout_.index(cell, slot0_)];
  double sum = 0.0;
  for (int k = 0; k < n_bins_; ++k) sum += s[k];
  return sum;
}

int SizeDistribution::dominant_bin(int cell, std::span<const double> y) const {
  const double* s = &y[layout_.index(cell, slot0_)];
  return static_cast<int>(std::max_element(s, s + n_bins_) - s);
}

std::vector<double> SizeDistribution::dominant_st(std::span<const double> y) const {
  const std::span<const double> st_bins = bin_stokes_numbers(y);
  std::vector<double> st(grid_.n_cells());
  for (int i = 0; i < grid_.n_cells(); ++i)
    st[i] = st_bins[static_cast<std::size_t>(i) * n_bins_ + dominant_bin(i, y)];
  return st;
}

int SizeDistribution::add_booked_mass(StateLayout& layout, const std::string& name,
                                      const std::string& what) const {
  return layout.add_global_var(booked_mass_info(name, what,
                                                layout.cell_var(slot0_).abs_scale,
                                                grid_.r_f(grid_.n_cells()), mass_unit_));
}

int SizeDistribution::add_monitor(StateLayout& layout, int face) {
  if (face == 0) return g_out_;
  if (monitor_slot_.empty()) monitor_slot_.assign(grid_.n_cells(), -1);
  if (monitor_slot_[face] < 0)
    monitor_slot_[face] =
        add_booked_mass(layout, "m_through_" + std::to_string(face),
                        "dust mass that crossed a face inward (pebble flux, spec §8)");
  return monitor_slot_[face];
}

void SizeDistribution::set_snowline(StateLayout& layout, int face, double f_ice) {
  snow_face_ = face;
  f_ice_ = f_ice;
  g_sub_ =
      add_booked_mass(layout, "m_sublimated", "ice that sublimated at the snow line");
  // spec §6.3, §11 #18: bin k arrives as particles of (1 - f_ice) m_k, phi kept
  const coag::MassGrid& grid = engine_.grid();
  snow_split_.clear();
  for (int k = 0; k < n_bins_; ++k)
    snow_split_.push_back(grid.split_mass((1.0 - f_ice) * grid.m[k]));
}

double SizeDistribution::mass_sublimated(std::span<const double> y) const {
  return g_sub_ < 0 ? 0.0 : y[layout_.global_index(g_sub_)] * mass_unit_;
}

double SizeDistribution::mass_out(std::span<const double> y) const {
  return y[layout_.global_index(g_out_)] * mass_unit_;
}

std::pair<double, double> SizeDistribution::face_gas(int f,
                                                     std::span<const double> y) const {
  const int a = f > 0 ? f - 1 : 0, b = f > 0 ? f : 1;
  return {gas_.sigma(a, &y[layout_.index(a, 0)]), gas_.sigma(b, &y[layout_.index(b, 0)])};
}

void SizeDistribution::flow_targets(int f, int k, bool psi, bool inward,
                                    std::vector<FlowTarget>& targets) const {
  auto slot = [&](int bin) { return psi ? psi_slot(bin) : bin_slot(bin); };
  targets.clear();
  targets.push_back({layout_.index(f, slot(k)), 1.0, grid_.area(f)});
  if (f > 0 && f == snow_face_ && inward) {
    // spec §6.3, §11 #18: (1 - f_ice) of the flow arrives at (1 - f_ice) m_k over two
    // bins (psi with the same weights: phi kept), f_ice of it sublimates
    const double keep = 1.0 - f_ice_;
    const auto& split = snow_split_[k];
    targets.push_back(
        {layout_.index(f - 1, slot(split.lo)), -keep * split.to_lo, grid_.area(f - 1)});
    if (split.to_hi != 0.0)
      targets.push_back({layout_.index(f - 1, slot(split.lo + 1)), -keep * split.to_hi,
                         grid_.area(f - 1)});
    if (!psi) targets.push_back({layout_.global_index(g_sub_), -f_ice_, mass_unit_});
  } else if (f > 0) {
    targets.push_back({layout_.index(f - 1, slot(k)), -1.0, grid_.area(f - 1)});
  }
  if (psi) return;  // the volume measure is not booked
  if (f == 0) targets.push_back({layout_.global_index(g_out_), -1.0, mass_unit_});
  if (!monitor_slot_.empty() && monitor_slot_[f] >= 0)
    targets.push_back({layout_.global_index(monitor_slot_[f]), -1.0, mass_unit_});
}

void SizeDistribution::declare_pattern(PatternBuilder& p) const {
  const int n = grid_.n_cells(), nb = n_bins_;
  std::vector<FlowTarget> targets;
  for (int f = 0; f < n; ++f) {
    const int a = f > 0 ? f - 1 : 0, b = f > 0 ? f : 1;
    for (int k = 0; k < nb; ++k) {
      // porous: both flows of the bin depend on sigma_k and psi_k of the two cells
      // through St
      std::vector<int> slots{bin_slot(k)};
      if (porous_) slots.push_back(psi_slot(k));
      std::vector<long> cols;
      for (int slot : slots) {
        for (int c : {a, b}) cols.push_back(layout_.index(c, slot));
        // limited scheme: the far upwind cell on either side (the drift may turn)
        if (flux_.options().limited && flux_.options().drift && f > 0)
          for (int far : {f - 2, f + 1})
            if (far >= 0 && far < n) cols.push_back(layout_.index(far, slot));
      }
      if (gas_.evolves())
        for (int c : {a, b}) cols.push_back(layout_.index(c, gas_.slot));
      // the snow face: either way the flow may go (it may turn)
      for (int q = 0; q < static_cast<int>(slots.size()); ++q)
        for (bool inward : {false, true}) {
          if (inward && f != snow_face_) continue;
          flow_targets(f, k, q == 1, inward, targets);
          for (const FlowTarget& t : targets)
            for (long col : cols) p.add(t.row, col);
        }
    }
  }
  if (!opt_.coagulation) return;
  const int nv = cell_vars();
  for (int i = 0; i < n; ++i)  // the dense coagulation block of every cell
    for (int r = 0; r < nv; ++r)
      for (int c = 0; c < nv; ++c)
        p.add(layout_.index(i, slot0_ + r), layout_.index(i, slot0_ + c));
}

void SizeDistribution::add_transport(std::span<const double> y,
                                     std::span<double> ydot) const {
  if (porous_) update_porous(y, false, false);  // St; the coefficients in add_rhs
  const int n = grid_.n_cells(), nb = n_bins_;
  std::vector<FlowTarget> targets;
  for (int f = 0; f < n; ++f) {
    const int a = f > 0 ? f - 1 : 0, b = f > 0 ? f : 1;
    const auto [sg_a, sg_b] = face_gas(f, y);
    for (int k = 0; k < nb; ++k) {
      const std::size_t ka = static_cast<std::size_t>(a) * nb + k;
      const std::size_t kb = static_cast<std::size_t>(b) * nb + k;
      const auto face =
          flux_.face_terms(f, DustFaceFlux::face_stokes(f, st_[ka], st_[kb]), sg_a, sg_b);
      // sigma_k, then (porous) psi_k with the same face terms: its tracer moment, which
      // goes where sigma_k's flow goes
      bool inward = false;
      for (int q = 0; q < (porous_ ? 2 : 1); ++q) {
        const int slot = q == 0 ? bin_slot(k) : psi_slot(k);
        const double q_far = face.far >= 0 ? y[layout_.index(face.far, slot)] : 0.0;
        const double flow = flux_.flow(f, face, sg_a, sg_b, y[layout_.index(a, slot)],
                                       y[layout_.index(b, slot)], q_far, nullptr);
        if (q == 0) inward = flow < 0.0;
        flow_targets(f, k, q == 1, inward, targets);
        for (const FlowTarget& t : targets) ydot[t.row] += t.weight * flow / t.divisor;
      }
    }
  }
}

void SizeDistribution::add_rhs(double, std::span<const double> y,
                               std::span<double> ydot) const {
  add_transport(y, ydot);  // porous: the bins' St from y
  if (!opt_.coagulation) return;
  const int nb = n_bins_, nv = cell_vars();
  std::vector<WorkerScratch>& ws = workers();
  parallel_for(grid_.n_cells(), [&](int i, int worker) {
    WorkerScratch& w = ws[static_cast<std::size_t>(worker)];
    w.out.resize(nv);
    const std::span<double> out(w.out);
    const long base = layout_.index(i, slot0_);
    const coag::CellCoefficients& c =
        porous_ ? porous_coefficients(i, y, false, w) : coef_[i];
    w.engine.rhs(c, y.subspan(base, nb),
                 porous_ ? y.subspan(base + nb, nb) : std::span<const double>{},
                 out.first(nb), porous_ ? out.subspan(nb) : std::span<double>{});
    for (int k = 0; k < nv; ++k) ydot[base + k] += out[k];
  });
}

void SizeDistribution::add_jacobian(double, std::span<const double> y,
                                    JacobianValues& jac) const {
  // porous: every cell's St and d St / d ln u for the transport's terms; the cells'
  // coefficients with their derivatives come cell by cell below
  if (porous_) update_porous(y, false, true);
  const int n = grid_.n_cells(), nb = n_bins_;
  std::vector<FlowTarget> targets;
  for (int f = 0; f < n; ++f) {
    const int a = f > 0 ? f - 1 : 0, b = f > 0 ? f : 1;
    const auto [sg_a, sg_b] = face_gas(f, y);
    // local directions: the quantity of cells a and b, then (evolving gas) their Sigma_g
    const bool ev = gas_.evolves();
    const ADCell ga = ev ? ad_seed<ADCell>(sg_a, 2) : ADCell(sg_a);
    const ADCell gb = ev ? ad_seed<ADCell>(sg_b, 3) : ADCell(sg_b);
    for (int k = 0; k < nb; ++k) {
      const std::size_t ka = static_cast<std::size_t>(a) * nb + k;
      const std::size_t kb = static_cast<std::size_t>(b) * nb + k;
      const ADCell st(DustFaceFlux::face_stokes(f, st_[ka], st_[kb]));
      const auto face = flux_.face_terms(f, st, ga, gb);
      // porous: the face terms by the two cells' St (directions 0 and 1), chained below
      // to sigma_k and psi_k through u = psi/sigma
      DustFaceFlux::FaceTerms<ADCell> face_st{ADCell(0.0), ADCell(0.0), -1};
      if (porous_)
        face_st =
            flux_.face_terms(f,
                             DustFaceFlux::face_stokes(f, ad_seed<ADCell>(st_[ka], 0),
                                                       ad_seed<ADCell>(st_[kb], 1)),
                             ADCell(sg_a), ADCell(sg_b));
      bool inward = false;
      for (int q = 0; q < (porous_ ? 2 : 1); ++q) {
        const int slot = q == 0 ? bin_slot(k) : psi_slot(k);
        const long col_a = layout_.index(a, slot), col_b = layout_.index(b, slot);
        const double q_far = face.far >= 0 ? y[layout_.index(face.far, slot)] : 0.0;
        double d_far = 0.0;
        const ADCell flow = flux_.flow(f, face, ga, gb, ad_seed<ADCell>(y[col_a], 0),
                                       ad_seed<ADCell>(y[col_b], 1), q_far, &d_far);
        const long cols[4] = {col_a, col_b, ev ? layout_.index(a, gas_.slot) : -1,
                              ev ? layout_.index(b, gas_.slot) : -1};
        double d_st[2] = {0.0, 0.0};
        if (porous_) {
          const ADCell flow_st =
              flux_.flow(f, face_st, ADCell(sg_a), ADCell(sg_b), ADCell(y[col_a]),
                         ADCell(y[col_b]), q_far, nullptr);
          d_st[0] = flow_st.derivatives()[0];
          d_st[1] = flow_st.derivatives()[1];
        }
        if (q == 0) inward = flow.value() < 0.0;
        flow_targets(f, k, q == 1, inward, targets);
        for (const FlowTarget& t : targets) {
          const double scale = t.weight / t.divisor;
          for (int j = 0; j < (ev ? 4 : 2); ++j)
            if (flow.derivatives()[j] != 0.0)
              jac.add(t.row, cols[j], scale * flow.derivatives()[j]);
          if (d_far != 0.0) jac.add(t.row, layout_.index(face.far, slot), scale * d_far);
          for (int side = 0; side < 2; ++side) {
            // St of the cell by ln u (bin_porosity's derivatives)
            const int c = side == 0 ? a : b;
            const double g = dst_dlnu_[static_cast<std::size_t>(c) * nb + k];
            if (d_st[side] == 0.0 || g == 0.0) continue;
            const coag::BinPorosity u = porosity(c, k, y);
            jac.add(t.row, layout_.index(c, bin_slot(k)),
                    scale * d_st[side] * g * u.dlnu_dsigma);
            jac.add(t.row, layout_.index(c, psi_slot(k)),
                    scale * d_st[side] * g * u.dlnu_dpsi);
          }
        }
      }
    }
  }
  if (!opt_.coagulation) return;
  const int nv = cell_vars();
  std::vector<WorkerScratch>& ws = workers();
  // each cell's block goes to its own entries of jac
  parallel_for(n, [&](int i, int worker) {
    WorkerScratch& w = ws[static_cast<std::size_t>(worker)];
    w.out.resize(static_cast<std::size_t>(nv) * nv);
    const long base = layout_.index(i, slot0_);
    const coag::CellCoefficients& c =
        porous_ ? porous_coefficients(i, y, true, w) : coef_[i];
    w.engine.jacobian(c, y.subspan(base, nb),
                      porous_ ? y.subspan(base + nb, nb) : std::span<const double>{},
                      w.out);
    jac.add_dense_block(base, nv, w.out);
  });
}

std::vector<double> SizeDistribution::mass_flow(std::span<const double> y) const {
  const int n = grid_.n_cells(), nb = n_bins_;
  std::vector<double> out(n + 1, 0.0);
  for (int f = 0; f < n; ++f) {
    const int a = f > 0 ? f - 1 : 0, b = f > 0 ? f : 1;
    const auto [sg_a, sg_b] = face_gas(f, y);
    for (int k = 0; k < nb; ++k) {
      const double st =
          DustFaceFlux::face_stokes(f, st_[static_cast<std::size_t>(a) * nb + k],
                                    st_[static_cast<std::size_t>(b) * nb + k]);
      const auto face = flux_.face_terms(f, st, sg_a, sg_b);
      out[f] += flux_.flow(f, face, sg_a, sg_b, y[layout_.index(a, bin_slot(k))],
                           y[layout_.index(b, bin_slot(k))],
                           face.far >= 0 ? y[layout_.index(face.far, bin_slot(k))] : 0.0,
                           nullptr);
    }
  }
  return out;
}

std::vector<BudgetTerm> SizeDistribution::budget_terms() const {
  return outflow_budget_terms(
      [this](std::span<const double> y) { return mass_out(y); },
      [this](std::span<const double> y) { return mass_sublimated(y); });
}

double SizeDistribution::top_bin_fraction(int cell, std::span<const double> y) const {
  const double sum = sigma_d(cell, y);
  return sum > 0.0 ? y[layout_.index(cell, bin_slot(n_bins_ - 1))] / sum : 0.0;
}

std::vector<OutputField> SizeDistribution::output_fields() const {
  const int n = grid_.n_cells(), nb = n_bins_;
  const std::size_t cells = static_cast<std::size_t>(n);
  auto per_cell = [this, n](auto value) {
    return [this, n, value](std::span<const double> y) {
      std::vector<double> out(n);
      for (int i = 0; i < n; ++i) out[i] = value(i, y);
      return out;
    };
  };
  // a field (r, m): cell by cell, the bins of /grid/m_bins in each
  auto per_bin = [n, nb](auto value) {
    return [n, nb, value](std::span<const double> y) {
      std::vector<double> out(static_cast<std::size_t>(n) * nb);
      for (int i = 0; i < n; ++i)
        for (int k = 0; k < nb; ++k)
          out[static_cast<std::size_t>(i) * nb + k] = value(i, k, y);
      return out;
    };
  };
  std::vector<OutputField> fields{
      {"sigma", cells * nb, "g cm^-2",
       "dust surface density per mass bin, sigma(r, m): cell by cell, the bins of "
       "/grid/m_bins in each (spec §15.1)",
       per_bin([this](int i, int k, std::span<const double> y) {
         return y[layout_.index(i, bin_slot(k))];
       })},
      {"sigma_d", cells, "g cm^-2", "dust surface density (sum of the bins)",
       per_cell([this](int i, std::span<const double> y) { return sigma_d(i, y); })},
      {"m", cells, "g", "mass of the mass-dominating bin (argmax sigma_k, spec §15.4)",
       per_cell([this](int i, std::span<const double> y) {
         return engine_.grid().m[dominant_bin(i, y)];
       })},
      // <m> = sum_k sigma_k m_k / sum_k sigma_k = M2/M1 of the number distribution. For a
      // narrow distribution d<m>/dt = rho_d K (d M2/dt = sum_ij K n_i n_j m_i m_j), the
      // single-size model's growth law (spec §4.1): what its m is compared with. The
      // mass-dominating bin is not, where the distribution splits into a bulk and a
      // runaway tail (tests/bench/results/porous_mmsn.md, "Why the distribution grows
      // unlike the single size").
      {"m_mean", cells, "g",
       "mass-weighted mean mass sum_k sigma_k m_k / sum_k sigma_k (the single-size "
       "model's m is this moment; 0 in a cell without dust)",
       per_cell([this](int i, std::span<const double> y) {
         const double sum = sigma_d(i, y);
         if (!(sum > 0.0)) return 0.0;
         const double* s = &y[layout_.index(i, slot0_)];
         const std::vector<double>& m = engine_.grid().m;
         double sum_m = 0.0;
         for (int k = 0; k < n_bins_; ++k) sum_m += s[k] * m[k];
         return sum_m / sum;
       })},
      {"a", cells, "cm", "radius of the mass-dominating bin (DustPy's a_rep)",
       per_cell([this](int i, std::span<const double> y) {
         const int k = dominant_bin(i, y);
         return physics::radius(engine_.grid().m[k], phi(i, k, y), species_[i].rho0);
       })},
      {"mdot_d", cells + 1, "g s^-1",
       "dust mass flow through the faces, positive outward",
       [this](std::span<const double> y) { return mass_flow(y); }},
      {kTopBinFractionField, cells, "",
       "fraction of the cell's dust in the mass grid's top bin (the last of "
       "/grid/m_bins; 0 in a cell without dust): products beyond it do not stick, so "
       "where this is not small the largest aggregates are missing; raise "
       "model.m_max_g",
       per_cell(
           [this](int i, std::span<const double> y) { return top_bin_fraction(i, y); })},
      {"st_bins", cells * nb, "",
       "Stokes number per mass bin, St(r, m), as the transport and coagulation use it: "
       "cell by cell, the bins of /grid/m_bins in each (spec §2, §15.1)",
       [this](std::span<const double> y) {
         const std::span<const double> st = bin_stokes_numbers(y);
         return std::vector<double>(st.begin(), st.end());
       }},
  };
  if (!porous_ && !track_) return fields;
  // porous: phi(r, m) and the mass-dominating bin's phi and internal density, named as
  // the single-size model's fields (spec §15.4)
  fields.push_back({"phi_bins", cells * nb, "",
                    "filling factor per mass bin, phi(r, m): sigma_k/psi_k (1 in an "
                    "empty bin; spec §15.1), or with porosity.bins = \"track\" the "
                    "single-size law's phi(m_k) at the cell's gas; cell by cell, the "
                    "bins of /grid/m_bins in each",
                    per_bin([this](int i, int k, std::span<const double> y) {
                      return phi(i, k, y);
                    })});
  fields.push_back({"phi", cells, "", "filling factor of the mass-dominating bin",
                    per_cell([this](int i, std::span<const double> y) {
                      return phi(i, dominant_bin(i, y), y);
                    })});
  fields.push_back({"rho_int", cells, "g cm^-3",
                    "internal density of the mass-dominating bin, phi rho0",
                    per_cell([this](int i, std::span<const double> y) {
                      return phi(i, dominant_bin(i, y), y) * species_[i].rho0;
                    })});
  return fields;
}

}  // namespace panoptic
