#pragma once
//! The mass grid of the size-distribution mode (spec §15.1): log-spaced bin centres m_k,
//! k = 0 ... N - 1, from the monomer mass m0 up to m_max, a fixed number of bins per
//! decade (DustPy's default 7; Stammler & Birnstiel 2022). The two-bin split of a
//! sticking product (physics/coagulation/smoluchowski.hpp) needs a regular log grid and a
//! bin ratio below 2 (so that m_k + m_k lies above m_k's upper neighbour).
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace panoptic::physics::coagulation {

//! DustPy's default resolution (spec §15.1) [bins per decade].
inline constexpr double kDefaultBinsPerDecade = 7.0;

//! Log-spaced bin centres [g]: m_k = m0 10^(k / bins_per_decade), the last one the first
//! at or above m_max (to one part in 1e9).
struct MassGrid {
  std::vector<double> m;         //!< bin centres [g]
  double bins_per_decade = 0.0;  //!< [-]
  double ratio = 0.0;            //!< m_{k+1} / m_k [-]
  double dlnm = 0.0;             //!< ln ratio: the width of a bin in ln m [-]

  MassGrid() = default;
  MassGrid(double m0, double m_max, double bpd = kDefaultBinsPerDecade)
      : bins_per_decade(bpd) {
    // ratio < 2: 2 m_k must lie above m_{k+1} (two-bin split of a pair of equal bins)
    if (!(m0 > 0.0) || !(m_max > m0) || !(bpd > 1.0 / std::log10(2.0)))
      throw std::invalid_argument("MassGrid: need 0 < m0 < m_max and bins_per_decade > " +
                                  std::to_string(1.0 / std::log10(2.0)));
    dlnm = std::log(10.0) / bpd;
    ratio = std::exp(dlnm);
    const int n = static_cast<int>(std::ceil(std::log10(m_max / m0) * bpd - 1e-9)) + 1;
    m.resize(n);
    // each centre from m0 directly (no accumulated product): the ratio of neighbours is
    // the same to round-off everywhere
    for (int k = 0; k < n; ++k) m[k] = m0 * std::exp(k * dlnm);
  }

  int size() const { return static_cast<int>(m.size()); }

  //! k with m_k <= x < m_{k+1}; -1 below the grid, size() - 1 at or above the last bin.
  int lower_bin(double x) const {
    const auto it = std::upper_bound(m.begin(), m.end(), x);
    return static_cast<int>(it - m.begin()) - 1;
  }

  //! Where particles of mass x go on the grid: the two-bin split of Kovetz & Olund (1969)
  //! (Brauer, Dullemond & Henning 2008, appendix A.1), eps particles of m_lo and 1 - eps
  //! of m_{lo+1}, eps = (m_{lo+1} - x)/(m_{lo+1} - m_lo), which conserves number and
  //! mass, given as the fractions of their mass that go to bins lo and lo + 1 (to_hi = 1
  //! - to_lo: the mass conserved to round-off). Below the first bin all of it goes into
  //! bin 0, at or above the last into the last (mass conserved, number not).
  struct MassSplit {
    int lo = 0;
    double to_lo = 1.0, to_hi = 0.0;  //!< [-]
  };
  MassSplit split_mass(double x) const {
    const int k = lower_bin(x);
    if (k < 0) return {0, 1.0, 0.0};
    if (k + 1 >= size()) return {size() - 1, 1.0, 0.0};
    const double eps = (m[k + 1] - x) / (m[k + 1] - m[k]);
    const double to_lo = eps * m[k] / x;
    return {k, to_lo, 1.0 - to_lo};
  }
};

}  // namespace panoptic::physics::coagulation
