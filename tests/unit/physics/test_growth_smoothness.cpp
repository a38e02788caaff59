//! Tests that the growth rates suit an implicit integrator (spec §6.4): no jump where a
//! smoothed switch turns (in mass, across phi_bounce, where growth turns to loss), and
//! AutoDiff derivatives equal to central finite differences. Set-up and reference
//! numbers: growth_fixture.hpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <string>
#include <vector>

#include "tests/unit/physics/growth_fixture.hpp"

using namespace growth_fixture;

// ------------------------------------------------------- continuity of smoothed switches

namespace {

//! Largest normalised jump |f(i+1) - f(i)| / (M_i dx) of a sampled f, where M_i is the
//! largest |f| within +-`window` samples of i or i+1 (the local scale of f; the global
//! max over 34 decades in m would hide a jump of a small rate).
struct Jumps {
  std::vector<double> j;  //!< per interval
  std::vector<double> scale;
  double max = 0.0;
  int at = 0;
};
Jumps normalised_jumps(const std::vector<double>& f, double dx, int window) {
  const int n = static_cast<int>(f.size());
  std::vector<double> local(n);
  std::deque<int> q;  // sliding-window maximum of |f|
  for (int k = 0; k < n + window; ++k) {
    if (k < n) {
      while (!q.empty() && std::abs(f[q.back()]) <= std::abs(f[k])) q.pop_back();
      q.push_back(k);
    }
    const int i = k - window;  // centre
    if (i < 0) continue;
    while (q.front() < i - window) q.pop_front();
    local[i] = std::abs(f[q.front()]);
  }
  Jumps r;
  r.j.assign(n - 1, 0.0);
  r.scale.assign(n - 1, 0.0);
  for (int i = 0; i + 1 < n; ++i) {
    const double s = std::max(local[i], local[i + 1]);
    r.scale[i] = s;
    r.j[i] = s > 0.0 ? std::abs(f[i + 1] - f[i]) / (s * dx) : 0.0;
    if (r.j[i] > r.max) {
      r.max = r.j[i];
      r.at = i;
    }
  }
  return r;
}

}  // namespace

TEST(GrowthContinuity, RatesHaveNoJumpInMass) {
  // Sweep m over 1e-14 .. 1e20 g (20000 points, log-uniform: dx = d ln m = 3.9e-3) at
  // phi = 1e-3 and phi = 1, 5 AU, St from the drag law, with compaction floors on and
  // each optional process on in turn. Crossed on the way: Epstein/Stokes/Newton drag,
  // the OC07 blends, E_imp = 3 b E_roll, St = 1, the floor softplus, the St cap, and per
  // run the erosion switch (v_eros = 40 m/s), the fragmentation zero (v_frag = 10 m/s,
  // crossed twice; the 60 m/s default is never reached at 5 AU) or bouncing (constant
  // in m: see the phi sweep below).
  //
  // Normalised jump J = |f(i+1) - f(i)| / (M dx), M = max |f| within +-1 dex of m (the
  // local scale: the global max over 34 decades would hide a jump of a small rate).
  // Bound: the steepest switch is E1's S(x) with w = 0.01: |dS/dx| <= 1/(2w) = 50, and
  // d ln x/d ln m = (d ln dv_ls/d ln St)(d ln St/d ln m) <= 1 * 1 (dv_ls grows at most
  // like St, St at most like m^(2/3) at fixed phi). The logistic switches (k = 12.8 per
  // ln St or ln E_imp) and the softplus (k = 100 in z, dz/d ln m < 1/2) are gentler, and
  // the smooth power laws add |d ln f/d ln m| of a few. Hence C = 60: a jump of relative
  // size delta gives J = delta/dx = 256 delta, so a jump > 25% fails on the grid; every
  // interval with J > C/6 is re-sampled 100x finer, where a jump shows a 100x larger
  // quotient (a jump > 2.5% there fails). The largest J inside each switch's band is
  // printed ("[ jumps ]" lines).
  const LocalGas gas = mmsn_gas(5.0);
  const Species sp = ice_species();
  const int n = 20000;
  const double x0 = std::log(1e-14), x1 = std::log(1e20);
  const double dx = (x1 - x0) / (n - 1);
  const int window = static_cast<int>(std::log(10.0) / dx);  // +-1 dex
  constexpr double kC = 60.0;
  constexpr double kVFrag = 1e3;
  struct Config {
    const char* name;
    GrowthOptions o;
  };
  std::vector<Config> configs(5, {"", plain_options(true)});
  configs[0].name = "no optional process";
  configs[1].name = "erosion halt (E1)";
  configs[1].o.erosion = ErosionModel::kHalt;
  configs[2].name = "erosion balance (E2)";
  configs[2].o.erosion = ErosionModel::kBalance;
  configs[3].name = "fragmentation";
  configs[3].o.fragmentation = true;
  configs[4].name = "bouncing";
  configs[4].o.bouncing = true;
  Species sp_frag = sp;
  sp_frag.v_frag = kVFrag;
  // compaction floor written out from spec §4.3 (for locating its switch only)
  const double st_eta = 1.0 / std::sqrt(gas.reynolds());
  auto floor_of = [&](double m, double st) {
    const double dv_pg = gas.eta * gas.v_k * st * std::sqrt(4 + st * st) / (1 + st * st);
    const double gas_floor =
        std::pow(1e-5 * kM0 * dv_pg * kOmega / (units::kPi * kERoll * st), 3.0 / 7.0) *
        std::pow(m / kM0, 1.0 / 7.0);
    const double grav_floor =
        std::pow(units::kG * kM0 * kM0 / (units::kPi * 1e-5 * kERoll), 0.6) *
        std::pow(m / kM0, 0.4);
    return std::min(std::max(gas_floor, grav_floor), 0.5);  // phi_max
  };
  for (const Config& cfg : configs) {
    const Species& s = cfg.o.fragmentation ? sp_frag : sp;
    for (double phi : {1e-3, 1.0}) {
      auto eval = [&](double x) {
        return rates_at(kSigmaD, std::exp(x), phi, gas, s, cfg.o);
      };
      std::vector<ParticleRates<double>> rs(n);
      std::vector<double> fm(n), fp(n);
      for (int i = 0; i < n; ++i) {
        rs[i] = eval(x0 + i * dx);
        fm[i] = rs[i].dlnm_dt;
        fp[i] = rs[i].dlnphi_dt;
      }
      // the band of each switch: where its argument is within +-0.3 dex of the switch
      // point (E1/E2: |x - 1| < 10 w; floor: |z| < 0.1 = 10/k)
      struct Band {
        const char* name;
        std::vector<double> arg;  // ln(argument / switch point)
        double half_width;
      };
      std::vector<Band> bands = {{"drag x=1", {}, 0.7}, {"OC07 St_eta", {}, 0.7},
                                 {"St=1", {}, 0.7},     {"E_imp=3bE_roll", {}, 0.7},
                                 {"floor", {}, 0.1},    {"St cap", {}, 0.7}};
      if (cfg.o.erosion != ErosionModel::kNone) bands.push_back({"erosion", {}, 0.1});
      if (cfg.o.fragmentation) bands.push_back({"dv=v_frag", {}, 0.7});
      for (int i = 0; i < n; ++i) {
        const auto& r = rs[i];
        const double m = std::exp(x0 + i * dx);
        const double lnx[] = {std::log(4 * r.a / (9 * gas.mfp)),
                              std::log(r.St / st_eta),
                              std::log(r.St),
                              std::log(0.25 * m * r.dv * r.dv / kThreshold),
                              std::log(floor_of(m, r.St) / phi),
                              std::log(r.St / 1e4),
                              r.dv_ls / 4e3 - 1.0,
                              std::log(r.dv / kVFrag)};
        for (std::size_t b = 0; b < bands.size(); ++b)
          bands[b].arg.push_back(b < 6 ? lnx[b] : cfg.o.fragmentation ? lnx[7] : lnx[6]);
      }
      for (int which = 0; which < 2; ++which) {
        const char* fname = which == 0 ? "dlnm_dt" : "dlnphi_dt";
        const Jumps jumps = normalised_jumps(which == 0 ? fm : fp, dx, window);
        // refine every steep interval 100x
        double fine_max = 0.0;
        int refined = 0;
        for (int i = 0; i + 1 < n; ++i) {
          if (jumps.j[i] <= kC / 6.0) continue;
          ++refined;
          const double h = dx / 100.0;
          double prev = which == 0 ? fm[i] : fp[i];
          for (int k = 1; k <= 100; ++k) {
            const auto r = eval(x0 + i * dx + k * h);
            const double cur = which == 0 ? r.dlnm_dt : r.dlnphi_dt;
            fine_max = std::max(fine_max, std::abs(cur - prev) / (jumps.scale[i] * h));
            prev = cur;
          }
        }
        std::string per_band;
        for (const Band& b : bands) {
          double jb = -1.0;
          for (int i = 0; i + 1 < n; ++i)
            if (std::abs(b.arg[i]) < b.half_width ||
                std::abs(b.arg[i + 1]) < b.half_width)
              jb = std::max(jb, jumps.j[i]);
          if (jb < 0.0) continue;  // not crossed
          char buf[64];
          std::snprintf(buf, sizeof buf, "%s%s %.2g", per_band.empty() ? "" : ", ",
                        b.name, jb);
          per_band += buf;
        }
        std::printf(
            "[ jumps    ] %s, phi = %g, %s: max J = %.3g at m = %.3g g (%d steep "
            "intervals refined 100x: %.3g); per switch: %s\n",
            cfg.name, phi, fname, jumps.max, std::exp(x0 + jumps.at * dx), refined,
            fine_max, per_band.c_str());
        EXPECT_LE(jumps.max, kC) << cfg.name << ", phi = " << phi << ", " << fname
                                 << " at m = " << std::exp(x0 + jumps.at * dx);
        EXPECT_LE(fine_max, kC) << cfg.name << ", phi = " << phi << ", " << fname;
      }
    }
  }
}

TEST(GrowthContinuity, RatesHaveNoJumpAcrossPhiBounce) {
  // Bouncing switches in phi, which the mass sweep holds fixed: sweep phi over 1e-3 .. 1
  // (20000 points, d ln phi = 3.5e-4) at m = 1e6 g with bouncing on. The step has k =
  // ln 19/(0.05 ln 10) = 25.6 per ln phi: |d(1 - step)/d ln phi| <= k/4 = 6.4, plus the
  // power-law dependence of the rates on phi (|d ln f/d ln phi| of order 1) and of the
  // Epstein/Stokes and E_imp switches: C = 10.
  const LocalGas gas = mmsn_gas(5.0);
  const Species sp = ice_species();
  GrowthOptions o = plain_options(true);
  o.bouncing = true;
  const int n = 20000;
  const double x0 = std::log(1e-3), x1 = 0.0, dx = (x1 - x0) / (n - 1);
  std::vector<double> fm(n), fp(n);
  for (int i = 0; i < n; ++i) {
    const auto r = rates_at(kSigmaD, 1e6, std::exp(x0 + i * dx), gas, sp, o);
    fm[i] = r.dlnm_dt;
    fp[i] = r.dlnphi_dt;
  }
  const int window = static_cast<int>(std::log(10.0) / 10.0 / dx);  // +-0.1 dex
  const Jumps jm = normalised_jumps(fm, dx, window);
  const Jumps jp = normalised_jumps(fp, dx, window);
  std::printf(
      "[ jumps    ] bouncing, phi sweep      dlnm_dt max %.3g at phi=%.3g, "
      "dlnphi_dt max %.3g at phi=%.3g\n",
      jm.max, std::exp(x0 + jm.at * dx), jp.max, std::exp(x0 + jp.at * dx));
  EXPECT_LE(jm.max, 10.0);
  EXPECT_LE(jp.max, 10.0);
}

TEST(GrowthContinuity, PhiRateIsSmoothWhereGrowthTurnsToLoss) {
  // d ln phi/dt = s (d ln m/dt)_+ must stay smooth where dm/dt changes sign (at
  // dv = v_frag with fragmentation, where E2 turns into net erosion):
  // fragmentation-limited particles settle exactly there, and spec §6.4 wants every
  // switch smooth. The positive part is therefore taken of dm/dm_coag with a relative
  // band. (Found as a bug: an absolute band of 1e-30 s^-1 acted as a hard max at real
  // rates.)
  //
  // Check: compact 1e4 g body (python: a = 11.9 cm, x = 0.044, St = 0.1728, Epstein
  // compression, s = -1/8), v_frag set to its dv. Across the zero of dm/dt (St +- 1e-7
  // relative) d(d ln phi/dt)/d ln St should change by O(1e-4) at most (the hard max
  // dropped it from s (dm_coag/m) d(factor)/d ln St = s (dm_coag/m)(-1)(d ln dv/d ln St =
  // 0.624) to 0; d factor/d ln dv = -4 u/(1 + u)^2 = -1 at u = dv^2/v_frag^2 = 1).
  const LocalGas gas = mmsn_gas(5.0);
  Species sp = ice_species();
  GrowthOptions o = plain_options();
  o.fragmentation = true;
  const double m = 1e4, phi = 1.0, st = 0.17278861207467963;
  sp.v_frag = dv_pair(st, m, gas);     // dm/dt = 0 at (m, St)
  auto slope_at = [&](double ln_st) {  // d(d ln phi/dt)/d ln St at fixed m
    AD x(ln_st);
    x.derivatives()[0] = 1.0;
    const AD st_ad = exp(x);
    const auto r = particle_rates(AD(kSigmaD), AD(m), AD(phi), st_ad, gas, sp, o);
    return r.dlnphi_dt.derivatives()[0];
  };
  const double below = slope_at(std::log(st) - 1e-7);  // dm/dt > 0 (dv < v_frag)
  const double above = slope_at(std::log(st) + 1e-7);  // dm/dt < 0
  const double coag =
      particle_rates(kSigmaD, m, phi, st, gas, sp, plain_options()).dlnm_dt;
  const double kink = -0.125 * coag * (-1.0) * 0.6236652407842769;  // python slope
  EXPECT_NEAR(below, above, 1e-3 * std::abs(kink))
      << "below " << below << ", above " << above << ", expected kink " << kink;
}

// --------------------------------------------------------------------------- AutoDiff

TEST(GrowthAutoDiff, MatchesCentralFiniteDifferences) {
  // d(d ln m/dt) and d(d ln phi/dt) with respect to Sigma_d, m, phi through
  // particle_rates() with St = stokes_number(m, phi) (AD), against central differences
  // with Richardson extrapolation (steps 1e-4 and 5e-5 relative: truncation O(h^4) <
  // 1e-9 even across the w = 0.01 erosion switch, width ~0.02 in ln m; round-off ~1e-12
  // of |f|/x). Tolerance 1e-6 relative, plus 1e-9 |f|/x for derivatives that vanish.
  // One state per regime and per switch, several inside a switch's transition band.
  const LocalGas gas = mmsn_gas(5.0);
  const Species sp = ice_species();
  struct Case {
    const char* what;
    double m, phi;
    GrowthOptions o;
    double v_frag = 6e3;
  };
  std::vector<Case> cases = {
      {"hit-and-stick", 1e-12, 1e-2, plain_options(true)},
      {"E_imp = 3 b E_roll", 2.16266531069291e-07, 1e-2, plain_options(true)},
      {"Epstein compression", 1.0, 1e-3, plain_options(true)},
      {"Epstein/Stokes (x = 1)", 11665.648182477757, 1e-4, plain_options(true)},
      {"Stokes, gas floor push", 1e9, 1e-6, plain_options(true)},
      {"St = 1", 2296877226.4092894, 1e-3, plain_options(true)},
      {"St >> 1", 1e12, 1e-3, plain_options(true)},
      {"St cap (St = 1e4)", 1.2580197071079174e+16, 1e-2, plain_options(true)},
      {"floor softplus bend", 1e4, 1.3367e-4, plain_options(true)},
      {"self-gravity floor", 1e15, 1e-4, plain_options(true)},
      {"E1 at x = 0.98", 1e10, 1e-5, plain_options(true)},
      {"E1 at x = 1", 10708412973.512157, 1e-5, plain_options(true)},
      {"E2 at x = 1", 10708412973.512157, 1e-5, plain_options(true)},
      {"E2 net erosion (St = 1)", 2296877226.4092894, 1e-3, plain_options(true)},
      {"fragmentation, dv = 0.9 v_frag", 1e8, 5e-4, plain_options(true)},
      {"fragmentation, dv = 3 v_frag", 1e8, 5e-4, plain_options(true)},
      {"bouncing at phi_bounce", 1e3, 0.3, plain_options(true)},
      {"compact, porosity off", 1e5, 1.0, plain_options(false)},
  };
  for (Case& c : cases) {
    const std::string w = c.what;
    if (w.rfind("E1", 0) == 0) c.o.erosion = ErosionModel::kHalt;
    if (w.rfind("E2", 0) == 0) c.o.erosion = ErosionModel::kBalance;
    if (w == "E2 net erosion (St = 1)") c.o.f_s = 0.95;
    if (w.rfind("fragmentation", 0) == 0) {
      c.o.fragmentation = true;
      const double dv = dv_pair(stokes_number(c.m, c.phi, kRho0, gas), c.m, gas);
      c.v_frag = dv / (w.find("0.9") != std::string::npos ? 0.9 : 3.0);
    }
    if (w.rfind("bouncing", 0) == 0) c.o.bouncing = true;
    if (w == "compact, porosity off") c.o.porosity = false;
  }
  double worst = 0.0;  // largest relative AD - FD difference (non-vanishing derivatives)
  for (const Case& c : cases) {
    Species s = sp;
    s.v_frag = c.v_frag;
    auto f = [&](double sigma, double m, double phi) {
      const auto r = rates_at(sigma, m, phi, gas, s, c.o);
      return std::pair{r.dlnm_dt, r.dlnphi_dt};
    };
    AD sig_ad(kSigmaD), m_ad(c.m), phi_ad(c.phi);
    sig_ad.derivatives()[0] = 1.0;
    m_ad.derivatives()[1] = 1.0;
    phi_ad.derivatives()[2] = 1.0;
    const AD st_ad = stokes_number(m_ad, phi_ad, kRho0, gas, c.o.drag);
    const ParticleRates<AD> r = particle_rates(sig_ad, m_ad, phi_ad, st_ad, gas, s, c.o);
    const auto f0 = f(kSigmaD, c.m, c.phi);
    EXPECT_EQ(r.dlnm_dt.value(), f0.first) << c.what;
    EXPECT_EQ(r.dlnphi_dt.value(), f0.second) << c.what;
    const double x[3] = {kSigmaD, c.m, c.phi};
    const char* const kInput[3] = {"sigma_d", "m", "phi"};
    // natural scale of both rates: d ln phi/dt is s d ln m/dt plus the push
    const double scale = std::max(std::abs(f0.first), std::abs(f0.second));
    for (int k = 0; k < 3; ++k) {
      auto at = [&](double d) {
        double y[3] = {x[0], x[1], x[2]};
        y[k] += d;
        return f(y[0], y[1], y[2]);
      };
      auto central = [&](double h) {
        const auto p = at(h), q = at(-h);
        return std::pair{(p.first - q.first) / (2 * h), (p.second - q.second) / (2 * h)};
      };
      const double h = 1e-4 * x[k];
      const auto d1 = central(h), d2 = central(0.5 * h);
      const double fd_m = (4.0 * d2.first - d1.first) / 3.0;
      const double fd_p = (4.0 * d2.second - d1.second) / 3.0;
      const double ad_m = r.dlnm_dt.derivatives()[k], ad_p = r.dlnphi_dt.derivatives()[k];
      for (const auto& [ad, fd] : {std::pair{ad_m, fd_m}, std::pair{ad_p, fd_p}})
        if (std::abs(fd) > 1e-6 * scale / x[k])
          worst = std::max(worst, std::abs(ad - fd) / std::abs(fd));
      EXPECT_NEAR(ad_m, fd_m, 1e-6 * std::abs(fd_m) + 1e-9 * scale / x[k])
          << c.what << ": d(dlnm_dt)/d" << kInput[k];
      EXPECT_NEAR(ad_p, fd_p, 1e-6 * std::abs(fd_p) + 1e-9 * scale / x[k])
          << c.what << ": d(dlnphi_dt)/d" << kInput[k];
    }
  }
  std::printf("[ autodiff ] %zu states x 3 inputs x 2 rates: max |AD/FD - 1| = %.2g\n",
              cases.size(), worst);
}
