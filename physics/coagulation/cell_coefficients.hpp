#pragma once
//! The coefficients of one disk cell for the coagulation engine (spec §15.2-§15.3): the
//! bins' radii, Stokes numbers and scale heights from their filling factors (spec §2),
//! the pair speeds (spec §3), the kernel, the fragmentation probabilities, the porosity
//! of sticking products and the compaction floors (spec §4.3-§4.4 per bin), from the
//! local gas and the monomer species. Used by the distribution mode on the grid
//! (physics/modules/size_distribution.cpp), the tests and
//! tests/bench/bench_coagulation.cpp.
#include <algorithm>
#include <cmath>
#include <memory>
#include <span>
#include <vector>

#include "disk/local_gas.hpp"
#include "physics/coagulation/collision_kernel.hpp"
#include "physics/coagulation/compact_pair_table.hpp"
#include "physics/coagulation/pair_speed_evaluator.hpp"
#include "physics/coagulation/porosity.hpp"
#include "physics/coagulation/smoluchowski.hpp"
#include "physics/compaction.hpp"
#include "physics/growth_options.hpp"

namespace panoptic::physics::coagulation {

//! What a cell's coefficients depend on besides the gas and the state.
struct CellModel {
  Species species;           //!< monomers (a0, rho0, m0, E_roll)
  GrowthOptions growth;      //!< drag law, b, phi_max, floors on/off, turbulence
  OutcomeSwitches outcomes;  //!< fragmentation and cratering switches and speeds
  //! e of bin_porosity() [g cm^-2]; the default, below any state of the tests, keeps u =
  //! psi/sigma to the last bit (the distribution mode sets its bins' absolute tolerance,
  //! porosity.hpp)
  double empty_scale = kTinyEmptyScale;
  //! Compact engine (no psi): each bin's filling factor, fixed for the call (the track
  //! mode's, porosity_track.hpp); empty: phi = 1.
  std::span<const double> bin_phi;
};

//! The outcomes of a cell's pairs under the scene's switches (spec §15.2):
//! * fragmentation on, erosion off: DustPy's default model; similar pairs fragment and
//!   pairs beyond its mass ratio (FragmentationModel::erosion_mass_ratio) crater, both
//!   with the Maxwell-Boltzmann probability at the species' v_frag.
//! * erosion on (any erosion.model: in a distribution the pairs themselves carry the
//!   rule that the single-size closures E1 and E2 of spec §5.2 approximate): the unequal
//!   pairs, m_j/m_i < R_crit = 1/erosion_mass_ratio = 0.1 in whole bins (DustPy's
//!   cratering threshold, dustpy/std/dust.f90 coagulation_parameters), follow Krijt et
//!   al.'s (2015) rule instead: the target loses eps_eros m_j above v_eros and the
//!   projectile sticks below (spec §5.1, §15.2), for every species and whether
//!   fragmentation is on or off. With fragmentation on too, an unequal pair has only this
//!   outcome and the similar pairs only fragmentation at v_frag: the two rules split the
//!   pairs by mass ratio at the same threshold as DustPy's fragmentation and cratering
//!   (Stammler & Birnstiel 2022; Krijt et al. 2015 model collisions with projectiles
//!   much smaller than the target).
inline OutcomeSwitches outcome_switches(const GrowthOptions& o, const Species& sp) {
  OutcomeSwitches s;
  s.fragmentation = o.fragmentation && sp.fragments;
  s.v_frag = sp.v_frag;
  if (o.eroding()) {
    s.cratering = true;
    s.v_eros = o.v_eros;
    s.w_eros = o.w_eros;
  } else {
    s.cratering = s.fragmentation;
    s.v_eros = sp.v_frag;
  }
  return s;
}

//! The engine's fragment model under the scene's switches: DustPy's (excavated mass 1
//! projectile mass), with erosion on Krijt et al.'s eps_eros (spec §5.1). The fragments
//! of an eroding pair, eps_eros m_j + m_j, follow DustPy's cratering distribution, n(m) ∝
//! m^-11/6 up to the projectile's mass: what the target loses is of the order of the
//! projectile's mass, and Krijt et al. (2015) track it as small particles.
inline FragmentationModel fragmentation_model(const GrowthOptions& o) {
  FragmentationModel f;
  if (o.eroding()) f.excavated_mass = o.eps_eros;
  return f;
}

//! The step in ln u of the porous Jacobian's forward differences [-].
inline constexpr double kLnUStep = 1e-6;

//! The bins that the porous Jacobian's forward differences evaluate: each bin's radius
//! and Stokes number (spec §2) at u e^kLnUStep, i.e. phi e^-kLnUStep.
struct PerturbedBins {
  std::vector<double> a;   //!< radius [cm]
  std::vector<double> st;  //!< Stokes number [-]
};

//! The PerturbedBins of the bins of masses m [g] and filling factors phi of monomers of
//! density rho0 [g cm^-3] in the gas `gas`, into `out` (its storage reused).
inline void perturbed_bins(std::span<const double> m, std::span<const double> phi,
                           double rho0, const LocalGas& gas, DragLaw drag,
                           PerturbedBins& out) {
  const std::size_t n = m.size();
  out.a.resize(n);
  out.st.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double phi_k = phi[k] * std::exp(-kLnUStep);
    out.a[k] = radius(m[k], phi_k, rho0);
    out.st[k] = stokes_number_of_radius(out.a[k], phi_k, rho0, gas, drag);
  }
}

//! What cell_coefficients keeps from call to call for one cell: its buffers, the pair
//! speeds' per-pair Brownian terms (PairSpeedEvaluator, rebuilt when the gas temperature
//! changes), the product rules' mass terms of every pair of the grid and the
//! coefficients of the pairs of compact bins (CompactPairTable, rebuilt when the gas
//! changes).
struct CoefficientWorkspace {
  PairSpeedEvaluator speeds;
  std::vector<double> phi, u;        //!< per bin [-]
  std::vector<char> compact;         //!< per bin: u = 1 exactly
  CompactPairTable compact_pairs;    //!< porous: the pairs of two compact bins
  BinProperties bins;                //!< per bin, at phi
  std::vector<BinSpeedTerms> terms;  //!< per bin, at St
  //! The pair speeds dv (N x N [cm s^-1]) and, for the Jacobian, dv_step (with one bin
  //! perturbed: at (i, j), bin i). A call reads them only while it runs, so a caller
  //! that keeps a workspace per cell may point `speeds_in` at storage of its worker
  //! thread's for the call (SizeDistribution): then no cell keeps them.
  struct PairSpeedScratch {
    std::vector<double> dv, dv_step;
  };
  PairSpeedScratch own_speeds;
  PairSpeedScratch* speeds_in = nullptr;
  PairSpeedScratch& pair_speeds() {
    return speeds_in != nullptr ? *speeds_in : own_speeds;
  }
  //! Jacobian: the perturbed bins (when the caller passes none), the pair speeds with
  //! one bin perturbed (at (i, j): bin i) and the targets' compression slopes, plain
  //! and perturbed
  PerturbedBins perturbed;
  std::vector<double> s_c, s_c_step;
  //! The mass terms of every pair of a grid: at (i, j), j <= i, pair_masses(m_i, m_j).
  //! They depend on the grid alone, so the cells of a disk share one table.
  struct PairMassTable {
    std::vector<double> of;  //!< the grid's masses [g]
    std::vector<PairMasses> pairs;
  };
  std::shared_ptr<const PairMassTable> masses;
  //! per bin: fragment_u_ceiling(m_k, m0) of the grid `cap_of` and monomer mass `cap_m0`
  std::vector<double> fragment_u_cap, cap_of;
  double cap_m0 = -1.0;  //!< [g]

  //! The mass terms of every pair of `m` (kept while the grid stays the same).
  void set_grid(std::span<const double> m) {
    if (masses != nullptr && std::ranges::equal(m, masses->of)) return;
    const std::size_t n = m.size();
    auto t = std::make_shared<PairMassTable>();
    t->of.assign(m.begin(), m.end());
    t->pairs.assign(n * n, PairMasses{});
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j <= i; ++j) t->pairs[i * n + j] = pair_masses(m[i], m[j]);
    masses = std::move(t);
  }
  //! Takes the pair mass terms of `other` (a cell of the same grid), without a copy.
  void share_grid(const CoefficientWorkspace& other) { masses = other.masses; }

  //! The fragments' ceiling of every bin of `m` for monomers of mass m0 [g] (kept while
  //! the grid and m0 stay the same): it depends on neither the gas nor the state.
  const std::vector<double>& fragment_ceiling(std::span<const double> m, double m0) {
    if (m0 == cap_m0 && std::ranges::equal(m, cap_of)) return fragment_u_cap;
    cap_m0 = m0;
    cap_of.assign(m.begin(), m.end());
    fragment_u_cap.resize(m.size());
    for (std::size_t k = 0; k < m.size(); ++k)
      fragment_u_cap[k] = fragment_u_ceiling(m[k], m0);
    return fragment_u_cap;
  }
};

//! Empties the matrices of c that a call refills with zeros or leaves empty, keeping
//! their storage for reuse. The kernel, p_frag and dlnk_dlnu keep their size: where
//! they are used every entry is written, and a resize from 0 would fill them first.
inline void clear_coefficients(CellCoefficients& c) {
  for (std::vector<double>* v :
       {&c.ln_u_ratio, &c.ln_phi_floor, &c.relax_rate, &c.dp_dlnu, &c.dd_dlnu_i,
        &c.dd_dlnu_j, &c.dlnfloor_dlnu, &c.drelax_dgrowth})
    v->clear();
}

//! Coefficients of the cell with bin masses sigma and, for porous aggregates, psi (empty:
//! compact, phi = 1 or model.bin_phi). Each bin's u by bin_porosity() (porosity.hpp): an
//! empty bin is compact and enters only through the rate of its first collisions. With
//! `derivatives` (porous, for the Jacobian) also d ln K_ij, d p_ij and d d_ij by ln u of
//! each partner, by forward differences of 1e-6 in ln u (about twice the cost; the
//! right-hand side needs none), and those of the floors and relaxation rates. A caller
//! that evaluates a cell repeatedly passes its `workspace` and the cell's previous
//! coefficients as `c` (moved in): their storage is reused, and nothing is allocated once
//! the sizes are set. A caller that has the perturbed_bins of the same filling factors
//! (for d St / d ln u of its own) passes them as `perturbed`, so that they are computed
//! once; without them they are computed here.
inline CellCoefficients cell_coefficients(
    const Smoluchowski& engine, std::span<const double> sigma,
    std::span<const double> psi, const LocalGas& gas, const CellModel& model,
    bool derivatives = false, CoefficientWorkspace* workspace = nullptr,
    CellCoefficients c = {}, const PerturbedBins* perturbed = nullptr) {
  CoefficientWorkspace local;
  CoefficientWorkspace& ws = workspace != nullptr ? *workspace : local;
  const MassGrid& grid = engine.grid();
  const int n = grid.size();
  const std::size_t nn = static_cast<std::size_t>(n) * n;
  const bool porous = !psi.empty();
  std::vector<double>& phi = ws.phi;
  std::vector<double>& u = ws.u;
  if (!porous && !model.bin_phi.empty())
    phi.assign(model.bin_phi.begin(), model.bin_phi.end());
  else
    phi.assign(n, 1.0);
  u.assign(n, 1.0);
  ws.compact.assign(n, 1);
  int n_compact = n;
  if (porous)
    for (int k = 0; k < n; ++k) {
      const BinPorosity b = bin_porosity(sigma[k], psi[k], model.empty_scale);
      u[k] = b.u;
      phi[k] = b.phi();
      ws.compact[k] = u[k] == 1.0;
      n_compact -= u[k] == 1.0 ? 0 : 1;
    }
  const Species& sp = model.species;
  const GrowthOptions& o = model.growth;
  const OutcomeSwitches& s = model.outcomes;
  const double e_threshold = 3.0 * o.b * sp.e_roll;  // spec §4.2
  c.empty_scale = model.empty_scale;
  const auto& m = grid.m;
  bin_properties(grid, phi, sp.rho0, gas, o.drag, ws.bins);
  const BinProperties& bins = ws.bins;
  ws.speeds.set_gas(gas, m, o.turbulence);
  ws.terms.resize(n);
  for (int k = 0; k < n; ++k) ws.terms[k] = ws.speeds.bin_terms(bins.St[k]);
  if (porous) ws.set_grid(m);
  // porous: the pairs of two compact bins from the table of the gas, where they are
  // enough (about N / 2 pairs or more) to pay for its build at each change of the gas
  const CompactPairTable* table = nullptr;
  if (porous && n_compact * n_compact >= n) {
    ws.compact_pairs.set(
        grid, ws.masses->pairs, ws.speeds,
        {gas, sp.rho0, e_threshold, o.drag, o.turbulence, s, engine.crater_bins()});
    table = &ws.compact_pairs;
  }
  const auto from_table = [&](int i, int j) {
    return table != nullptr && ws.compact[i] && ws.compact[j];
  };
  clear_coefficients(c);
  // the pair speeds (spec §3), the kernel (spec §15.2) and the outcome probabilities
  // (pair_loss_probability: fragmentation and cratering, spec §15.2)
  const bool losses = s.fragmentation || s.cratering;
  CoefficientWorkspace::PairSpeedScratch& pair = ws.pair_speeds();
  pair.dv.resize(nn);
  c.kernel.resize(nn);
  if (losses)
    c.p_frag.resize(nn);
  else
    c.p_frag.clear();
  if (table != nullptr) table->fill_rates(ws.compact, pair.dv, c.kernel, c.p_frag);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j <= i; ++j) {
      const std::size_t ij = static_cast<std::size_t>(i) * n + j;
      const std::size_t ji = static_cast<std::size_t>(j) * n + i;
      if (from_table(i, j)) continue;
      // pair_rates (compact_pair_table.hpp) written out: the same bits, and the
      // compiler inlines the pair's functions here as without the table
      const double v = ws.speeds.dv(ws.terms[i], ws.terms[j], i, j);
      pair.dv[ij] = pair.dv[ji] = v;
      c.kernel[ij] = c.kernel[ji] =
          pair_kernel(bins.a[i], bins.a[j], bins.h_d[i], bins.h_d[j], v);
      if (losses)
        c.p_frag[ij] = c.p_frag[ji] =
            pair_loss_probability(v, i - j > engine.crater_bins(), s);
    }
  if (!derivatives) c.dlnk_dlnu.clear();
  if (!porous) return c;
  const std::vector<double>& dv = pair.dv;

  // for the Jacobian: d ln K_ij / d ln u_i, a forward difference in bin i's filling
  // factor through its radius, St, h_d and every pair speed (the kernel is the part of
  // the coefficients that moves most with the porosity)
  const double step = kLnUStep;
  if (derivatives) {
    c.dlnk_dlnu.resize(nn);
    if (losses) c.dp_dlnu.assign(nn, 0.0);
    pair.dv_step.resize(nn);
    if (perturbed == nullptr) {
      perturbed_bins(m, phi, sp.rho0, gas, o.drag, ws.perturbed);
      perturbed = &ws.perturbed;
    }
  }
  for (int i = 0; derivatives && i < n; ++i) {
    const double a_i = perturbed->a[i];
    const double st_i = perturbed->st[i];
    const double h_i = dust_scale_height(st_i, gas);
    const BinSpeedTerms terms_i = ws.speeds.bin_terms(st_i);
    for (int j = 0; j < n; ++j) {
      const bool self = j == i;
      const double v = ws.speeds.dv(terms_i, self ? terms_i : ws.terms[j], i, j);  // §3
      const double k = pair_kernel(a_i, self ? a_i : bins.a[j], h_i,
                                   self ? h_i : bins.h_d[j], v);  // spec §15.2
      const std::size_t ij = static_cast<std::size_t>(i) * n + j;
      pair.dv_step[ij] = v;
      c.dlnk_dlnu[ij] = std::log(k / c.kernel[ij]) / step;
      if (losses) {
        const int hi = i > j ? i : j, lo = i > j ? j : i;
        const bool crater = hi - lo > engine.crater_bins();
        // the erosion step (width w_eros ~ 0.01 in dv/v_eros) by the chain rule through
        // the difference of dv: its own forward difference would carry an error of
        // step / w^2 (4e-5 of the Jacobian on the test's state)
        if (crater && s.cratering && s.w_eros > 0.0)
          c.dp_dlnu[ij] =
              erosion_probability_slope(dv[ij], s.v_eros, s.w_eros) * (v - dv[ij]) / step;
        else if (crater ? s.cratering : s.fragmentation)
          c.dp_dlnu[ij] = (pair_loss_probability(v, crater, s) - c.p_frag[ij]) / step;
      }
    }
  }
  c.ln_u_ratio.assign(nn, 0.0);
  if (table != nullptr) table->fill_ln_u_ratio(ws.compact, c.ln_u_ratio);
  if (derivatives) {
    c.dd_dlnu_i.assign(nn, 0.0);
    c.dd_dlnu_j.assign(nn, 0.0);
  }
  ws.s_c.resize(n);
  ws.s_c_step.resize(n);
  for (int i = 0; i < n; ++i) {
    ws.s_c[i] = compression_slope_of_target(bins.a[i], bins.St[i], gas, o.drag);
    ws.s_c_step[i] = derivatives ? compression_slope_of_target(
                                       perturbed->a[i], perturbed->st[i], gas, o.drag)
                                 : ws.s_c[i];
  }
  for (int i = 0; i < n; ++i) {
    const double s_c = ws.s_c[i];
    for (int j = 0; j <= i; ++j) {
      const std::size_t ij = static_cast<std::size_t>(i) * n + j;
      const PairMasses& pm = ws.masses->pairs[ij];
      if (!from_table(i, j)) {
        const double e_imp = impact_energy(pm, dv[ij]);  // spec §15.3
        c.ln_u_ratio[ij] = product_ln_u_ratio(pm, u[i], u[j], e_imp, e_threshold, s_c);
      }
      if (!derivatives) continue;
      // for the Jacobian: d by ln u_i and ln u_j, through the volumes, the impact
      // energy and (u_i) the target's compression slope
      const double ue = std::exp(step);
      const double e_i = impact_energy(pm, pair.dv_step[ij]);
      const double u_j_step = i == j ? u[j] * ue : u[j];
      c.dd_dlnu_i[ij] =
          (product_ln_u_ratio(pm, u[i] * ue, u_j_step, e_i, e_threshold, ws.s_c_step[i]) -
           c.ln_u_ratio[ij]) /
          step;
      if (i != j) {
        const double e_j =
            impact_energy(pm, pair.dv_step[static_cast<std::size_t>(j) * n + i]);
        c.dd_dlnu_j[ij] =
            (product_ln_u_ratio(pm, u[i], u[j] * ue, e_j, e_threshold, s_c) -
             c.ln_u_ratio[ij]) /
            step;
      }
    }
  }
  // fragments no fluffier than the fluffiest aggregate of their mass (porosity.hpp)
  if (porous && losses) {
    const std::vector<double>& cap = ws.fragment_ceiling(m, sp.m0);
    c.fragment_u_cap.assign(cap.begin(), cap.end());
  } else {
    c.fragment_u_cap.clear();
  }
  if (!o.gas_compaction && !o.self_gravity) return c;
  c.ln_phi_floor.resize(n);
  c.relax_rate.resize(n);
  if (derivatives) {
    c.dlnfloor_dlnu.resize(n);
    c.drelax_dgrowth.resize(n);
  }
  for (int k = 0; k < n; ++k) {
    // spec §4.3 floors of the bin's mass and St (physics/compaction.hpp)
    c.ln_phi_floor[k] = ln_compaction_floor(m[k], bins.St[k], gas, sp, o);
    if (derivatives)  // the gas floor moves with St, so with u (forward difference)
      c.dlnfloor_dlnu[k] =
          (ln_compaction_floor(m[k], perturbed->st[k], gas, sp, o) - c.ln_phi_floor[k]) /
          step;
    // spec §4.4 with physics/compaction.hpp's constants: t_relax = kRelaxFraction
    // min(t_grow, kRelaxCapOmega/Omega), t_grow the bin's own growth time, its sticking
    // gain of mass per unit mass from partners no more massive than itself,
    // sum_{j <= k} K_kj (1 - p_kj) n_j m_j / m_k [C] (the single size's t_grow, from
    // partners eps m, eps < 1, net of fragmentation and erosion as there,
    // physics/growth_rates.hpp: collisions that fragment or crater the bin's particle do
    // not grow it; counted, they stiffened the push of the sparse bins above the
    // fragmentation barrier, tests/bench/results/porous_cost.md). A larger partner
    // carries the bin's particle off rather than growing it, and leaves the bin's u as it
    // is; counted, it made t_relax of small bins among giants m_j/m_k shorter, its push's
    // tail held their phi up to 19 % above the floor and Newton stalled there
    // (tests/bench/results/porous_newton.md, last section). Only bins that hold mass
    // count (a slightly negative bin, integration error, would make t_relax negative: an
    // unstable push).
    double growth = 0.0;
    for (int j = 0; j <= k; ++j)
      if (sigma[j] > 0.0)
        growth +=
            c.sticking_kernel(static_cast<std::size_t>(k) * n + j) * sigma[j] / m[k];
    const double t_grow = 1.0 / (growth + 1e-30);
    const double t_soft = soft_min(t_grow, kRelaxCapOmega / gas.omega_k);
    c.relax_rate[k] = 1.0 / (kRelaxFraction * t_soft);
    // d r / d growth = r t_grow (t_soft / t_grow)^p: soft_min = (a^-p + b^-p)^(-1/p)
    // has d/da = (soft_min / a)^(p + 1), and d t_grow / d growth = -t_grow^2
    if (derivatives)
      c.drelax_dgrowth[k] =
          c.relax_rate[k] * t_grow * std::pow(t_soft / t_grow, kSoftMaxPower);
  }
  return c;
}

}  // namespace panoptic::physics::coagulation
