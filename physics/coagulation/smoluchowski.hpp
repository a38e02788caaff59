#pragma once
//! The Smoluchowski coagulation equation of one cell on the mass grid (spec §15.2):
//!   d sigma_k/dt = sum over pairs (i >= j) of [mass gained by bin k - mass lost by bin
//!                  k] * R_ij,   R_ij = c_ij K_ij n_i n_j,  n_i = sigma_i / m_i,
//! c_ij = 1/2 for i = j (each pair of particles counted once), 1 otherwise. K_ij [cm^2
//! s^-1] is supplied per cell (physics/coagulation/collision_kernel.hpp for the disk's
//! kernel; any symmetric matrix, e.g. the analytic kernels of the tests), and so is the
//! probability p_ij that the pair fragments rather than sticks.
//!
//! Outcomes of a pair (larger partner i, smaller j), after DustPy's default model
//! (Stammler & Birnstiel 2022; dustpy/std/dust.f90, coagulation_parameters and s_coag,
//! read for its rules, not copied):
//! * sticking (rate (1 - p) R): the product m_i + m_j lies between two bins k, k+1 and
//!   is replaced by eps particles of m_k and 1 - eps of m_{k+1}, eps = (m_{k+1} - m_i -
//!   m_j)/(m_{k+1} - m_k), which conserves number and mass (Kovetz & Olund 1969; Brauer,
//!   Dullemond & Henning 2008, appendix A.1). Where the product falls into the target's
//!   own bin (k = i, m_j < m_{i+1} - m_i) the net change of bin i, -(1 - eps) m_i =
//!   -m_i m_j/(m_{i+1} - m_i), is written without the cancelling terms (Brauer et al.
//!   2008, appendix A.2): mass stays conserved to round-off for any mass ratio, also
//!   where m_i + m_j rounds to m_i. Products beyond the last bin do not stick (as in
//!   DustPy): the grid must reach beyond the largest mass of interest.
//! * full fragmentation (rate p R, m_i / m_j up to erosion_mass_ratio bins apart): both
//!   partners turn into fragments of total mass m_i + m_j, distributed as n(m) ∝
//!   m^fragment_slope (DustPy and Birnstiel et al. 2010: -11/6) up to the larger
//!   partner's bin: the mass fraction of bin k <= q is m_k^(2 + slope) / Z_q.
//! * cratering (rate p R, mass ratio beyond erosion_mass_ratio): the target keeps m_i -
//!   eps_c m_j (split between two bins like a sticking product), and (1 + eps_c) m_j
//!   go into fragments up to the projectile's bin (DustPy's "excavated mass" eps_c = 1;
//!   the target loses eps_eros m_proj of Krijt et al. 2015, spec §5.1, §15.2).
//!
//! With porosity each bin also carries psi_k = sigma_k <1/phi>_m [g cm^-2], rho0 times
//! the volume of its aggregates per unit area: the volume-averaging method of Okuzumi,
//! Tanaka & Sakagami (2009), whose bins carry mass and the mass-weighted mean volume
//! measure (spec §15.1). u_k = psi_k / sigma_k = <1/phi>_m of the bin.
//! * Each partner of a collision carries its bin's own volume, psi_k in proportion to the
//!   mass it takes away: c_ij K_ij (psi_i / m_i) n_j per unit of m_i, the rate R_ij with
//!   n_i replaced by psi_i / m_i (the upwind booking of an extensive quantity). This is
//!   linear in psi and finite where sigma_k = 0, so a bin's psi leaves at its mass's
//!   fractional rate whatever its sign: the psi < 0 that integration error leaves in
//!   nearly empty bins decays (booked as u = |psi|/sigma times the mass lost, it grew at
//!   the bin's collision rate: tests/bench/results/porous_newton.md).
//! * A sticking product gains its partners' volumes plus the voids of its rule, m_p u_p -
//!   m_i u_i - m_j u_j with u_p = u_i e^d (d_ij = ln(u_p / u_i), porosity.hpp) at the
//!   bins' u. Inside the physical cone psi >= sigma >= 0 (u = psi/sigma) that is the
//!   product's volume m_p u_p.
//! * The product's mass is split between its two bins (above), and its volume so that
//!   each part carries the specific volume of the product's own growth step extended to
//!   that bin's mass: the part of mass fraction f in bin b gets f (m_b / m_p)^s m_p u_p,
//!   s = d / ln(m_p / m_i) the step's slope d ln u / d ln m, |s| <= kMaxSplitSlope [C:
//!   ours, departing from spec §15.2, which asks the split to conserve the volume
//!   measure]. Like the mass split, which conserves mass and number but not the higher
//!   moments, this does not conserve the volume: it adds (f_lo (m_k/m_p)^s + f_hi
//!   (m_{k+1}/m_p)^s - 1) m_p u_p, of first order in the bins' width. Splitting the
//!   volume in proportion to mass instead (u_p in both bins, which conserves it) gives
//!   the mass that the split moves up the grid (its mass-weighted ln m gains about
//!   ln(m_{k+1}/m_k)/2 per unit of ln m grown: the scheme's numerical diffusion) no
//!   growth of its volume. That error accumulates along the mass axis: with a constant
//!   hit-and-stick slope, where the exact phi is (m/m0)^-0.58, phi came out ~100x too
//!   dense at 1e-4 g on 7 bins per decade, and a normalised split (parts on the step,
//!   total conserved) still accumulates a first-order error. With a constant slope this
//!   split is exact (CoagulationVolumeSplit.*; tests/bench/results/porosity_split.md).
//! * Remnants keep their parents' specific volume, and so do fragments (spec §15.3) up to
//!   the fluffiest u of the bin they land in (fragment_u_ceiling, porosity.hpp): psi is
//!   conserved where that ceiling does not bind, and only removed where it does.
//! * A relaxation up to the static compaction floor per bin (spec §4.3-§4.4, §15.3) may
//!   be added.
//! So psi changes only by the voids, the split, the ceiling and the floors.
//!
//! A bin's u (the kernel, the product rule, the floors) follows the state by the one rule
//! of bin_porosity() (porosity.hpp), with the coefficients' empty-bin scale. The Jacobian
//! is analytic and dense per cell, with K, p, d and the floors' levels and rates held
//! fixed (they depend on the state through the filling factors and, the relaxation
//! rates, the bins' sigma) unless their derivatives are given (cell_coefficients computes
//! them all).
//! For the compact model it is exact. Rows and columns are ordered (sigma_0 ...
//! sigma_{N-1}[, psi_0 ...]), row-major.
#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <span>
#include <stdexcept>
#include <utility>
#include <vector>

#include "physics/coagulation/mass_grid.hpp"
#include "physics/coagulation/porosity.hpp"
#include "physics/smooth_switches.hpp"

namespace panoptic::physics::coagulation {

//! Outcome model of fragmenting pairs (DustPy's defaults: dustpy/simulation.py,
//! ini.dust.erosionMassRatio, excavatedMass, fragmentDistribution).
struct FragmentationModel {
  //! Pairs whose mass ratio exceeds this (measured in whole bins, as DustPy) crater
  //! instead of fragmenting fully [-].
  double erosion_mass_ratio = 10.0;
  //! Target mass excavated per projectile mass in cratering (eps_eros of spec §5.1) [-].
  double excavated_mass = 1.0;
  //! Fragment distribution n(m) ∝ m^slope [-].
  double fragment_slope = -11.0 / 6.0;
};

//! What the engine needs of one cell: the kernel and, optionally, the fragmentation
//! probability, the porosity of sticking products and the compaction floors. Pair
//! matrices are N x N, row-major, read at (i, j) with i >= j.
struct CellCoefficients {
  std::vector<double> kernel;      //!< K_ij [cm^2 s^-1] (rate per area K n_i n_j)
  std::vector<double> p_frag;      //!< fragmentation probability [-]; empty: all stick
  std::vector<double> ln_u_ratio;  //!< porous: ln(u_p / u_i) of the product [-]; empty: 0
  std::vector<double> ln_phi_floor;  //!< porous, per bin: ln of the compaction floor
  std::vector<double> relax_rate;    //!< porous, per bin: 1 / t_relax [s^-1]
  //! porous with fragments, per bin: the largest u a fragment landing in the bin may
  //! carry (fragment_u_ceiling, porosity.hpp); empty: fragments keep their parents' u
  std::vector<double> fragment_u_cap;
  //! porous: the empty-bin scale e of bin_porosity() [g cm^-2] (CellModel's)
  double empty_scale = kTinyEmptyScale;
  //! porous, Jacobian only: d ln K_ij / d ln u_i at (i, j) (for i = j the derivative of
  //! K_ii by its bin's u); empty: K held fixed [-]
  std::vector<double> dlnk_dlnu;
  //! porous, Jacobian only: d p_ij / d ln u_i at (i, j) (as dlnk_dlnu) [-]
  std::vector<double> dp_dlnu;
  //! porous, Jacobian only: d d_ij / d ln u_i and d d_ij / d ln u_j at (i, j), i >= j
  //! (for i = j the first holds the derivative by the bin's u, the second 0) [-]
  std::vector<double> dd_dlnu_i, dd_dlnu_j;
  //! porous, Jacobian only, per bin: d ln floor_k / d ln u_k (through St_k) [-] and
  //! d relax_rate_k / d growth_k, growth_k = sum_{j <= k} K_kj (1 - p_kj) sigma_j / m_k
  //! [-] (spec §4.4)
  std::vector<double> dlnfloor_dlnu, drelax_dgrowth;

  //! The kernel of the pair at ij that sticks, K_ij (1 - p_ij) (K_ij where nothing is
  //! lost) [cm^2 s^-1]: the collisions that grow a bin, growth_k above, in the floors'
  //! relaxation rate (cell_coefficients) and its Jacobian (floor_jacobian).
  double sticking_kernel(std::size_t ij) const {
    return p_frag.empty() ? kernel[ij] : kernel[ij] * (1.0 - p_frag[ij]);
  }
};

//! Largest |slope| d ln u / d ln m of a sticking product's growth step along which its
//! volume is split between its two bins (Smoluchowski::volume_split) [-]: the physical
//! slopes lie within it (hit-and-stick 0.58 and compression 1/8 to 1/5, spec §4.3;
//! -1 for a fluffy target sweeping up compact grains); steeper ones come from partners
//! of very different porosity, where extending the step over a bin is not meaningful.
inline constexpr double kMaxSplitSlope = 1.0;

//! Softplus sharpness of the push up to the floor (as physics/compaction.hpp) [-].
inline constexpr double kFloorSharpness = 100.0;

class Smoluchowski {
 public:
  explicit Smoluchowski(MassGrid grid, FragmentationModel frag = {})
      : grid_(std::move(grid)), frag_(frag), n_(grid_.size()) {
    const auto& m = grid_.m;
    if (frag_.excavated_mass >= frag_.erosion_mass_ratio)
      throw std::invalid_argument(
          "Smoluchowski: excavated_mass must be < erosion_mass_ratio");
    // pairs more than crater_bins_ bins apart crater (DustPy: p = floor(log10(ratio)/a))
    crater_bins_ = static_cast<int>(
        std::floor(std::log10(frag_.erosion_mass_ratio) * grid_.bins_per_decade + 1e-9));
    pairs_.resize(static_cast<std::size_t>(n_) * (n_ + 1) / 2);
    for (int i = 0; i < n_; ++i) {
      for (int j = 0; j <= i; ++j) {
        Pair& p = pairs_[pair_index(i, j)];
        const double mp = m[i] + m[j];
        if (mp < m[n_ - 1]) {
          int k = lower_bin(mp);
          if (k < i) k = i;  // m_i + m_j rounded to m_i: the product is in bin i
          p.k = k;
          if (k == i) {  // Brauer et al. 2008, A.2: no cancelling terms
            const double delta = m[i + 1] - m[i];
            p.loss_i = -m[i] * m[j] / delta;  // -(1 - eps) m_i
            p.gain_lo = m[i] + p.loss_i;      // eps m_i (psi only)
            p.gain_hi = m[j] * m[i + 1] / delta;
          } else {  // Brauer et al. 2008, A.1
            const double eps = (m[k + 1] - mp) / (m[k + 1] - m[k]);
            p.loss_i = -m[i];
            p.gain_lo = eps * m[k];
            p.gain_hi = (1.0 - eps) * m[k + 1];
          }
        }
        p.frac_lo = p.gain_lo / mp;
        p.frac_hi = p.gain_hi / mp;
        if (p.k >= 0) {
          p.ln_step = std::log1p(m[j] / m[i]);
          p.ln_lo = p.k == i ? -p.ln_step : std::log(m[p.k] / mp);
          p.ln_hi = std::log(m[p.k + 1] / mp);
        }
        if (i - j > crater_bins_) {  // cratering: remnant m_i - x, fragments (1 + e) m_j
          p.crater = true;
          const double x = frag_.excavated_mass * m[j];
          p.excavated = x;
          p.frag_mass = m[j] + x;
          p.frag_bin = j;
          if (x <= m[i] - m[i - 1]) {  // remnant in (m_{i-1}, m_i]: no cancelling terms
            const double delta = m[i] - m[i - 1];
            p.rem_bin = i - 1;
            p.rem_same = true;
            p.target_net = -m[i] * x / delta;
            p.rem_lo = m[i - 1] * x / delta;
          } else {
            const double mrm = m[i] - x;
            const int r = lower_bin(mrm);
            if (r < 0)
              throw std::invalid_argument("Smoluchowski: remnant below the grid");
            const double e = (m[r + 1] - mrm) / (m[r + 1] - m[r]);
            p.rem_bin = r;
            p.target_net = -m[i];
            p.rem_lo = e * m[r];
            p.rem_hi = (1.0 - e) * m[r + 1];
          }
        } else {
          p.frag_mass = m[i] + m[j];
          p.frag_bin = i;
        }
      }
    }
    // fragment distribution: mass fraction of bin k <= q is w_k / Z_q (DustPy phiFrag)
    weight_.resize(n_);
    inv_z_.resize(n_);
    double z = 0.0;
    for (int k = 0; k < n_; ++k) {
      weight_[k] = std::pow(m[k] / m[0], 2.0 + frag_.fragment_slope);
      z += weight_[k];
      inv_z_[k] = 1.0 / z;
    }
  }

  const MassGrid& grid() const { return grid_; }
  int size() const { return n_; }
  const FragmentationModel& fragmentation() const { return frag_; }

  //! Bins apart beyond which a pair craters [-].
  int crater_bins() const { return crater_bins_; }

  //! d sigma/dt (and d psi/dt if psi is not empty) [g cm^-2 s^-1]. Overwrites the
  //! outputs. Not thread-safe (scratch).
  void rhs(const CellCoefficients& c, std::span<const double> sigma,
           std::span<const double> psi, std::span<double> dsigma,
           std::span<double> dpsi) const {
    const int n = n_;
    const auto& m = grid_.m;
    const bool porous = !psi.empty();
    const bool frag = !c.p_frag.empty();
    const bool has_d = porous && !c.ln_u_ratio.empty();
    std::fill(dsigma.begin(), dsigma.end(), 0.0);
    if (porous) std::fill(dpsi.begin(), dpsi.end(), 0.0);
    num_.resize(n);
    frag_mass_.assign(n, 0.0);
    frag_psi_.assign(n, 0.0);
    for (int k = 0; k < n; ++k) num_[k] = sigma[k] / m[k];
    porosities(c, sigma, psi);
    // a bin takes part where it holds mass, or volume (psi, which its partners'
    // collisions move on even where sigma = 0)
    auto idle = [&](int k) { return num_[k] == 0.0 && (!porous || w_[k] == 0.0); };
    for (int i = 0; i < n; ++i) {
      if (idle(i)) continue;
      for (int j = 0; j <= i; ++j) {
        if (idle(j)) continue;
        const Pair& p = pairs_[pair_index(i, j)];
        const std::size_t ij = static_cast<std::size_t>(i) * n + j;
        const double kk = (i == j ? 0.5 : 1.0) * c.kernel[ij];
        const double rate = kk * num_[i] * num_[j];
        const double pf = frag ? c.p_frag[ij] : 0.0;
        const double f_stick = (1.0 - pf) * kk, r_stick = (1.0 - pf) * rate;
        if (p.k >= 0 && f_stick != 0.0) {
          dsigma[j] -= m[j] * r_stick;
          dsigma[i] += p.loss_i * r_stick;
          if (p.k != i) dsigma[p.k] += p.gain_lo * r_stick;
          dsigma[p.k + 1] += p.gain_hi * r_stick;
          if (porous) {
            // the partners' own volumes m_i vt, m_j vj (header); the product adds the
            // voids of its rule
            const double vt = f_stick * w_[i] * num_[j], vj = f_stick * num_[i] * w_[j];
            const double d = has_d ? c.ln_u_ratio[ij] : 0.0;
            const double voids = r_stick * product_voids(m[i], m[j], u_[i].u, u_[j].u, d);
            const double moved_j = m[j] * vj + voids;
            const VolumeSplit g = volume_split(p, d);
            dpsi[j] -= m[j] * vj;
            if (p.k == i) {
              dpsi[i] += g.lo * moved_j - g.lo_left * m[i] * vt;
            } else {
              dpsi[i] -= m[i] * vt;
              dpsi[p.k] += g.lo * (m[i] * vt + moved_j);
            }
            dpsi[p.k + 1] += g.hi * (m[i] * vt + moved_j);
          }
        }
        const double f_frag = pf * kk, r_frag = pf * rate;
        if (f_frag == 0.0) continue;
        dsigma[j] -= m[j] * r_frag;
        frag_mass_[p.frag_bin] += p.frag_mass * r_frag;
        if (p.crater) {
          dsigma[i] += p.target_net * r_frag;
          dsigma[p.rem_bin] += p.rem_lo * r_frag;
          if (!p.rem_same) dsigma[p.rem_bin + 1] += p.rem_hi * r_frag;
        } else {
          dsigma[i] -= m[i] * r_frag;
        }
        if (porous) {
          // remnants and fragments carry their parents' volume per mass (as sticking)
          const double vt = f_frag * w_[i] * num_[j], vj = f_frag * num_[i] * w_[j];
          dpsi[j] -= m[j] * vj;
          if (p.crater) {
            dpsi[i] += p.target_net * vt;
            dpsi[p.rem_bin] += p.rem_lo * vt;
            if (!p.rem_same) dpsi[p.rem_bin + 1] += p.rem_hi * vt;
            frag_psi_[p.frag_bin] += m[j] * vj + p.excavated * vt;
          } else {
            dpsi[i] -= m[i] * vt;
            frag_psi_[p.frag_bin] += m[i] * vt + m[j] * vj;
          }
        }
      }
    }
    if (frag) {
      spread_fragments(frag_mass_, dsigma);
      if (porous) spread_fragment_volume(c.fragment_u_cap, dpsi);
    }
    if (porous && !c.ln_phi_floor.empty()) {
      for (int k = 0; k < n; ++k) {
        // spec §4.4: d ln phi/dt = softplus_100(ln floor - ln phi) / t_relax, i.e.
        // d psi/dt = -psi d ln phi/dt at fixed sigma; ln phi = -ln u (bin_porosity)
        const double z = c.ln_phi_floor[k] + std::log(u_[k].u);
        dpsi[k] -= psi[k] * softplus(z, kFloorSharpness) * c.relax_rate[k];
      }
    }
  }

  //! The dense Jacobian d(dsigma, dpsi)/d(sigma, psi), row-major, nv x nv with nv = N
  //! (compact, psi empty) or 2N; the coefficients fixed where their derivatives are not
  //! given. Overwrites jac.
  void jacobian(const CellCoefficients& c, std::span<const double> sigma,
                std::span<const double> psi, std::span<double> jac) const {
    const int n = n_;
    const auto& m = grid_.m;
    const bool porous = !psi.empty();
    const int nv = porous ? 2 * n : n;
    const bool frag = !c.p_frag.empty();
    const bool has_d = porous && !c.ln_u_ratio.empty();
    const bool has_dk = porous && !c.dlnk_dlnu.empty();
    std::fill(jac.begin(), jac.end(), 0.0);
    num_.resize(n);
    for (int k = 0; k < n; ++k) num_[k] = sigma[k] / m[k];
    porosities(c, sigma, psi);
    // fragments per column and largest-fragment bin, spread at the end
    g_mass_.assign(static_cast<std::size_t>(nv) * n, 0.0);
    if (porous) g_psi_.assign(static_cast<std::size_t>(nv) * n, 0.0);
    // the fragments' mass and volume rates themselves, for the capped volume's slopes
    const bool capped = porous && frag && !c.fragment_u_cap.empty();
    frag_mass_.assign(n, 0.0);
    frag_psi_.assign(n, 0.0);
    auto at = [&](int row, int col) -> double& {
      return jac[static_cast<std::size_t>(row) * nv + col];
    };
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j <= i; ++j) {
        if (num_[i] == 0.0 && num_[j] == 0.0 &&
            (!porous || (w_[i] == 0.0 && w_[j] == 0.0)))
          continue;
        const Pair& p = pairs_[pair_index(i, j)];
        const std::size_t ij = static_cast<std::size_t>(i) * n + j;
        const double kk = (i == j ? 0.5 : 1.0) * c.kernel[ij];
        const double pf = frag ? c.p_frag[ij] : 0.0;
        // K_ij through u_i and u_j: a term T ∝ K adds g_i T d ln u_i (d ln u_i by sigma_i
        // and psi_i from bin_porosity, bounded in nearly empty bins), and the same for j
        // (once for i = j)
        double gk_i = 0.0, gk_j = 0.0, gp_i = 0.0, gp_j = 0.0, gd_i = 0.0, gd_j = 0.0;
        if (has_dk) {
          const std::size_t ji = static_cast<std::size_t>(j) * n + i;
          gk_i = c.dlnk_dlnu[ij];
          if (i != j) gk_j = c.dlnk_dlnu[ji];
          if (frag && !c.dp_dlnu.empty()) {
            gp_i = c.dp_dlnu[ij];
            if (i != j) gp_j = c.dp_dlnu[ji];
          }
          if (!c.dd_dlnu_i.empty()) {
            gd_i = c.dd_dlnu_i[ij];
            gd_j = c.dd_dlnu_j[ij];
          }
        }
        double gi = 0.0, gj = 0.0;  // d ln T / d ln u of the current terms
        // the term T's derivatives through u_i and u_j into `row`, or into the fragments'
        // column sums `g` (a column's entry of bin q at g(col))
        auto u_terms = [&](auto&& book, double t) {
          const BinPorosity &pi = u_[i], &pj = u_[j];
          book(n + i, gi * t * pi.dlnu_dpsi);
          book(i, gi * t * pi.dlnu_dsigma);
          book(n + j, gj * t * pj.dlnu_dpsi);
          book(j, gj * t * pj.dlnu_dsigma);
        };
        auto kernel_terms = [&](int row, double t) {
          u_terms([&](int col, double v) { at(row, col) += v; }, t);
        };
        for (int outcome = 0; outcome < 2; ++outcome) {
          const double f = outcome == 0 ? 1.0 - pf : pf;
          if (f == 0.0) continue;
          if (outcome == 0 && p.k < 0) continue;
          // T ∝ f K: d ln T / d ln u = d ln K / d ln u -+ (dp / d ln u) / f
          if (has_dk) {
            const double sign = outcome == 0 ? -1.0 : 1.0;
            gi = gk_i + sign * gp_i / f;
            gj = gk_j + sign * gp_j / f;
          }
          // R = f kk n_i n_j: dR/dsigma_i, dR/dsigma_j
          const double dri = f * kk * num_[j] / m[i];
          const double drj = f * kk * num_[i] / m[j];
          const double rate = f * kk * num_[i] * num_[j];
          auto mass = [&](int row, double coef) {
            at(row, i) += coef * dri;
            at(row, j) += coef * drj;
            if (has_dk) kernel_terms(row, coef * rate);
          };
          // the partners' volume rates V_t = f kk w_i n_j and V_j = f kk n_i w_j (w =
          // psi/m, rhs()); the term c_t V_t + c_j V_j booked by `book(col, derivative)`
          const double vt = porous ? f * kk * w_[i] * num_[j] : 0.0;
          const double vj = porous ? f * kk * num_[i] * w_[j] : 0.0;
          auto vol = [&](auto&& book, double c_t, double c_j) {
            book(i, c_j * f * kk * w_[j] / m[i]);
            book(j, c_t * f * kk * w_[i] / m[j]);
            book(n + i, c_t * dri);
            book(n + j, c_j * drj);
            if (has_dk) u_terms(book, c_t * vt + c_j * vj);
          };
          auto vol_at = [&](int row, double c_t, double c_j) {
            vol([&](int col, double v) { at(n + row, col) += v; }, c_t, c_j);
          };
          auto vol_t = [&](int row, double coef) { vol_at(row, coef, 0.0); };
          if (outcome == 0) {
            mass(j, -m[j]);
            mass(i, p.loss_i);
            if (p.k != i) mass(p.k, p.gain_lo);
            mass(p.k + 1, p.gain_hi);
            if (porous) {
              // the product's voids R v(u_i, u_j, d): through R, the bins' u and d(u_i,
              // u_j)
              const double d = has_d ? c.ln_u_ratio[ij] : 0.0;
              const double v = product_voids(m[i], m[j], u_[i].u, u_[j].u, d);
              const double grow = (m[i] + m[j]) * u_[i].u * std::exp(d);
              const double gv_i =
                  (m[i] + m[j]) * u_[i].u * std::expm1(d) + m[j] * u_[i].u + grow * gd_i;
              const double gv_j = -m[j] * u_[j].u + grow * gd_j;
              auto voids_at = [&](int row, double coef) {
                const double cr = coef * rate;
                at(n + row, i) += coef * v * dri + cr * gv_i * u_[i].dlnu_dsigma;
                at(n + row, j) += coef * v * drj + cr * gv_j * u_[j].dlnu_dsigma;
                at(n + row, n + i) += cr * gv_i * u_[i].dlnu_dpsi;
                at(n + row, n + j) += cr * gv_j * u_[j].dlnu_dpsi;
                if (has_dk) kernel_terms(n + row, cr * v);
              };
              const VolumeSplit g = volume_split(p, d);
              vol_at(j, 0.0, -m[j]);
              if (p.k == i) {
                vol_at(i, -g.lo_left * m[i], g.lo * m[j]);
              } else {
                vol_t(i, -m[i]);
                vol_at(p.k, g.lo * m[i], g.lo * m[j]);
              }
              voids_at(p.k, g.lo);
              vol_at(p.k + 1, g.hi * m[i], g.hi * m[j]);
              voids_at(p.k + 1, g.hi);
              // the split itself moves with d(u_i, u_j): the product's volume rate P
              // times dg/dd d d/d ln u into each of its bins
              if (g.dlo_dd != 0.0 || g.dhi_dd != 0.0) {
                const double pv = m[i] * vt + m[j] * vj + rate * v;
                for (const auto& [row, dg] :
                     {std::pair{p.k, g.dlo_dd}, std::pair{p.k + 1, g.dhi_dd}}) {
                  const double a_i = pv * dg * gd_i, a_j = pv * dg * gd_j;
                  at(n + row, i) += a_i * u_[i].dlnu_dsigma;
                  at(n + row, n + i) += a_i * u_[i].dlnu_dpsi;
                  at(n + row, j) += a_j * u_[j].dlnu_dsigma;
                  at(n + row, n + j) += a_j * u_[j].dlnu_dpsi;
                }
              }
            }
            continue;
          }
          // the target's share: cratered (it keeps target_net, the remnant split over
          // rem_bin and rem_bin + 1) or shattered (it loses m_i); booked into the mass
          // rows and, porous, with the same coefficients into the volume rows
          auto target_outcome = [&](auto&& book) {
            if (p.crater) {
              book(i, p.target_net);
              book(p.rem_bin, p.rem_lo);
              if (!p.rem_same) book(p.rem_bin + 1, p.rem_hi);
            } else {
              book(i, -m[i]);
            }
          };
          mass(j, -m[j]);
          target_outcome(mass);
          const std::size_t q = p.frag_bin;
          auto gm = [&](int col) -> double& {
            return g_mass_[static_cast<std::size_t>(col) * n + q];
          };
          gm(i) += p.frag_mass * dri;
          gm(j) += p.frag_mass * drj;
          if (capped) frag_mass_[q] += p.frag_mass * rate;
          if (has_dk)
            u_terms([&](int col, double v) { gm(col) += v; }, p.frag_mass * rate);
          if (porous) {
            vol_at(j, 0.0, -m[j]);
            // fragments' volume: m_j V_j + (crater ? x : m_i) V_t
            const double ct = p.crater ? p.excavated : m[i];
            target_outcome(vol_t);
            auto g = [&](int col) -> double& {
              return g_psi_[static_cast<std::size_t>(col) * n + q];
            };
            vol([&](int col, double v) { g(col) += v; }, ct, m[j]);
            if (capped) frag_psi_[q] += ct * vt + m[j] * vj;
          }
        }
      }
    }
    if (frag) {
      if (capped) fragment_volume_slopes(c.fragment_u_cap);
      for (int col = 0; col < nv; ++col) {
        spread_column(&g_mass_[static_cast<std::size_t>(col) * n], 0, col, jac, nv);
        if (capped)
          spread_capped_column(col, jac, nv);
        else if (porous)
          spread_column(&g_psi_[static_cast<std::size_t>(col) * n], n, col, jac, nv);
      }
    }
    if (porous && !c.ln_phi_floor.empty()) floor_jacobian(c, sigma, psi, jac);
  }

 private:
  struct Pair;

  //! The volume a sticking product leaves in its bins k and k + 1 per unit of its own
  //! volume m_p u_p: g_lo, g_hi, 1 - g_lo (without cancelling terms, for k = i) and
  //! their derivatives by d.
  struct VolumeSplit {
    double lo = 0.0, hi = 0.0, lo_left = 0.0, dlo_dd = 0.0, dhi_dd = 0.0;
  };

  //! The volume split of the product of pair p at d = ln(u_p / u_i) (header): the part
  //! of mass fraction f of the product that goes to bin b carries the specific volume of
  //! the product's own growth step extended to m_b, g = f (m_b / m_p)^s, with the step's
  //! slope s = d / ln(m_p / m_i) bounded to |s| <= kMaxSplitSlope.
  static VolumeSplit volume_split(const Pair& p, double d);

  struct Pair {
    int k = -1;           //!< lower bin of the sticking product; -1: beyond the grid
    double loss_i = 0.0;  //!< mass change of bin i per sticking collision [g]
    double gain_lo = 0.0, gain_hi = 0.0;  //!< mass into bins k, k+1 [g]
    double frac_lo = 0.0, frac_hi = 0.0;  //!< their fractions of m_i + m_j [-]
    double ln_step = 0.0;  //!< ln(m_p / m_i) = ln(1 + m_j / m_i) of the product [-]
    double ln_lo = 0.0, ln_hi = 0.0;  //!< ln(m_k / m_p) <= 0, ln(m_{k+1} / m_p) >= 0 [-]
    bool crater = false;
    int frag_bin = 0;                   //!< bin of the largest fragment
    double frag_mass = 0.0;             //!< mass of the fragments [g]
    double excavated = 0.0;             //!< target mass excavated in cratering [g]
    int rem_bin = 0;                    //!< lower bin of the cratering remnant
    bool rem_same = false;              //!< remnant between bins i-1 and i
    double target_net = 0.0;            //!< mass change of bin i per cratering [g]
    double rem_lo = 0.0, rem_hi = 0.0;  //!< remnant mass into rem_bin, rem_bin+1 [g]
  };

  //! The floors' rows of the Jacobian: T_k = -psi_k softplus(z_k) r_k, z_k = ln floor_k
  //! + ln u_k (spec §4.4), through psi_k, u_k (z_k and, by St_k, floor_k) and r_k =
  //! r(growth_k), growth_k = sum_{j <= k} K_kj (1 - p_kj) sigma_j / m_k over sigma_j > 0
  //! (cell_coefficients), which moves with every such sigma_j and, through K_kj and
  //! p_kj, every such u_j. Uses u_ of jacobian().
  void floor_jacobian(const CellCoefficients& c, std::span<const double> sigma,
                      std::span<const double> psi, std::span<double> jac) const {
    const int n = n_, nv = 2 * n;
    const auto& m = grid_.m;
    const bool d_floor = !c.dlnfloor_dlnu.empty();
    const bool d_rate = !c.drelax_dgrowth.empty() && !c.dlnk_dlnu.empty();
    // with losses p_kj moves with u_k and u_j too
    const bool d_loss = !c.p_frag.empty() && !c.dp_dlnu.empty();
    auto at = [&](int row, int col) -> double& {
      return jac[static_cast<std::size_t>(row) * nv + col];
    };
    // a derivative x by ln u_j, into the columns of sigma_j and psi_j
    auto by_ln_u = [&](int row, int j, double x) {
      at(row, j) += x * u_[j].dlnu_dsigma;
      at(row, n + j) += x * u_[j].dlnu_dpsi;
    };
    for (int k = 0; k < n; ++k) {
      const double z = c.ln_phi_floor[k] + std::log(u_[k].u);
      const double sp = softplus(z, kFloorSharpness);
      const double lg = logistic_step(z, kFloorSharpness);
      const double r = c.relax_rate[k];
      at(n + k, n + k) -= sp * r;
      by_ln_u(n + k, k, -psi[k] * lg * r * (1.0 + (d_floor ? c.dlnfloor_dlnu[k] : 0.0)));
      if (!d_rate) continue;
      // through r_k: dT/d growth_k, then growth_k by sigma_j and ln u_j
      const double t_g = -psi[k] * sp * c.drelax_dgrowth[k] / m[k];
      if (t_g == 0.0) continue;
      // growth_k counts the sticking collisions, K_kj (1 - p_kj) (sticking_kernel)
      double own = 0.0;  // d growth_k m_k / d ln u_k: every pair (k, j <= k) by u_k
      for (int j = 0; j <= k; ++j) {
        if (!(sigma[j] > 0.0)) continue;
        const std::size_t kj = static_cast<std::size_t>(k) * n + j;
        const std::size_t jk = static_cast<std::size_t>(j) * n + k;
        const double kk = c.kernel[kj];
        const double stick = c.sticking_kernel(kj);
        at(n + k, j) += t_g * stick;
        own += stick * c.dlnk_dlnu[kj] * sigma[j];
        if (d_loss) own -= kk * c.dp_dlnu[kj] * sigma[j];
        if (j == k) continue;
        double by_u_j = t_g * stick * c.dlnk_dlnu[jk] * sigma[j];
        if (d_loss) by_u_j -= t_g * kk * c.dp_dlnu[jk] * sigma[j];
        by_ln_u(n + k, j, by_u_j);
      }
      by_ln_u(n + k, k, t_g * own);
    }
  }

  //! The voids of a sticking product per collision, m_p u_p - m_i u_i - m_j u_j [g], with
  //! u_p = u_i e^d (d_ij of CellCoefficients), written without cancelling terms.
  static double product_voids(double m_i, double m_j, double u_i, double u_j, double d) {
    return (m_i + m_j) * u_i * std::expm1(d) + m_j * (u_i - u_j);
  }

  //! u_k of every bin with its derivatives by sigma_k and psi_k (bin_porosity) into u_
  //! (porous; empty otherwise).
  void porosities(const CellCoefficients& c, std::span<const double> sigma,
                  std::span<const double> psi) const {
    u_.resize(psi.size());
    w_.resize(psi.size());
    for (std::size_t k = 0; k < psi.size(); ++k) {
      u_[k] = bin_porosity(sigma[k], psi[k], c.empty_scale);
      w_[k] = psi[k] / grid_.m[k];
    }
  }

  static std::size_t pair_index(int i, int j) {
    return static_cast<std::size_t>(i) * (i + 1) / 2 + j;
  }

  //! k with m_k <= x < m_{k+1}; -1 below the grid.
  int lower_bin(double x) const {
    const auto& m = grid_.m;
    const auto it = std::upper_bound(m.begin(), m.end(), x);
    return static_cast<int>(it - m.begin()) - 1;
  }

  //! out_k += w_k sum_{q >= k} src_q / Z_q.
  void spread_fragments(const std::vector<double>& src, std::span<double> out) const {
    double suffix = 0.0;
    for (int k = n_ - 1; k >= 0; --k) {
      suffix += src[k] * inv_z_[k];
      out[k] += weight_[k] * suffix;
    }
  }
  //! The volume of the fragments landing in bin k: their parents' volume, W_k = w_k
  //! sum_{q >= k} frag_psi_q / Z_q (the mass's spread), capped at cap_k times their
  //! mass M_k (spec §15.3 as amended in porosity.hpp's fragment_u_ceiling) by the smooth
  //! minimum soft_min(W_k, cap_k M_k); where either is not positive (integration noise
  //! of nearly empty bins), W_k. dpsi_k += that; no cap: W_k.
  void spread_fragment_volume(const std::vector<double>& cap,
                              std::span<double> out) const {
    if (cap.empty()) {
      spread_fragments(frag_psi_, out);
      return;
    }
    for_each_fragment_sum(
        cap, [&](int k, const CappedVolume& v) { out[k] += weight_[k] * v.value; });
  }
  //! f(k, capped_volume(W_k, cap_k M_k)) for each bin k, from the top bin down: the one
  //! walk over the suffix sums W_k / w_k and M_k / w_k of the fragments' volume and mass
  //! that spread_fragment_volume and fragment_volume_slopes share.
  template <class F>
  void for_each_fragment_sum(const std::vector<double>& cap, F&& f) const {
    double s_psi = 0.0, s_mass = 0.0;
    for (int k = n_ - 1; k >= 0; --k) {
      s_psi += frag_psi_[k] * inv_z_[k];
      s_mass += frag_mass_[k] * inv_z_[k];
      f(k, capped_volume(s_psi, cap[k] * s_mass));
    }
  }
  //! soft_min(w, c) for w, c > 0 with its slopes by w and by c; else w (slopes 1, 0).
  struct CappedVolume {
    double value = 0.0, by_volume = 1.0, by_cap = 0.0;
  };
  static CappedVolume capped_volume(double w, double c) {
    if (!(w > 0.0 && c > 0.0)) return {w, 1.0, 0.0};
    const double v = soft_min(w, c);
    // soft_min = (w^-p + c^-p)^(-1/p): d/dw = (v / w)^(p + 1)
    return {v, std::pow(v / w, kSoftMaxPower + 1.0),
            std::pow(v / c, kSoftMaxPower + 1.0)};
  }
  //! Per bin k, d dpsi_k / d(sum of frag_psi) and d dpsi_k / d(sum of frag_mass) of the
  //! capped fragment volume at the sources of the Jacobian's state.
  void fragment_volume_slopes(const std::vector<double>& cap) const {
    slope_psi_.resize(n_);
    slope_mass_.resize(n_);
    for_each_fragment_sum(cap, [&](int k, const CappedVolume& v) {
      slope_psi_[k] = weight_[k] * v.by_volume;
      slope_mass_[k] = weight_[k] * v.by_cap * cap[k];
    });
  }
  //! The capped fragment volume's column `col` into the volume rows: the suffix sums of
  //! the column's fragment mass and volume derivatives times the slopes.
  void spread_capped_column(int col, std::span<double> jac, int nv) const {
    const double* gm = &g_mass_[static_cast<std::size_t>(col) * n_];
    const double* gp = &g_psi_[static_cast<std::size_t>(col) * n_];
    double s_psi = 0.0, s_mass = 0.0;
    for (int k = n_ - 1; k >= 0; --k) {
      s_psi += gp[k] * inv_z_[k];
      s_mass += gm[k] * inv_z_[k];
      jac[static_cast<std::size_t>(n_ + k) * nv + col] +=
          slope_psi_[k] * s_psi + slope_mass_[k] * s_mass;
    }
  }
  void spread_column(const double* src, int row0, int col, std::span<double> jac,
                     int nv) const {
    double suffix = 0.0;
    for (int k = n_ - 1; k >= 0; --k) {
      suffix += src[k] * inv_z_[k];
      jac[static_cast<std::size_t>(row0 + k) * nv + col] += weight_[k] * suffix;
    }
  }

  MassGrid grid_;
  FragmentationModel frag_;
  int n_ = 0;
  int crater_bins_ = 0;
  std::vector<Pair> pairs_;
  std::vector<double> weight_, inv_z_;
  mutable std::vector<double> num_, w_, frag_mass_, frag_psi_, g_mass_, g_psi_;
  mutable std::vector<double> slope_psi_, slope_mass_;
  mutable std::vector<BinPorosity> u_;
};

inline Smoluchowski::VolumeSplit Smoluchowski::volume_split(const Pair& p, double d) {
  if (p.frac_hi == 0.0) return {p.frac_lo, p.frac_hi, p.frac_hi, 0.0, 0.0};
  const double slope = d / p.ln_step;
  const bool bounded = std::abs(slope) > kMaxSplitSlope;
  const double s = bounded ? std::copysign(kMaxSplitSlope, slope) : slope;
  VolumeSplit g;
  g.lo = p.frac_lo * std::exp(s * p.ln_lo);
  g.hi = p.frac_hi * std::exp(s * p.ln_hi);
  // 1 - f_lo e^(s ln_lo) with f_lo = 1 - f_hi, written without cancelling terms
  g.lo_left = p.frac_hi - p.frac_lo * std::expm1(s * p.ln_lo);
  if (!bounded) {
    g.dlo_dd = g.lo * p.ln_lo / p.ln_step;
    g.dhi_dd = g.hi * p.ln_hi / p.ln_step;
  }
  return g;
}

}  // namespace panoptic::physics::coagulation
