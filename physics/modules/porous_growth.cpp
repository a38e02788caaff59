#include "physics/modules/porous_growth.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <type_traits>

#include "physics/modules/evolving_gas_ad.hpp"
#include "src/core/units.hpp"

namespace panoptic {

using physics::LocalGas;

namespace {
// Sharpness of the soft clamps of ln m and ln(1/phi): at the bound the value is shifted
// by ln 2/k = 0.007 (phi = 0.993 for a monomer), invisible beyond 0.05 from it.
constexpr double kClampSharpness = 100.0;

//! The state a cell's particle laws depend on, the key of the per-cell caches of St and
//! of the rates: Sigma_d, Q_m, Q_phi (0 without porosity), Sigma_g (0 if the gas is
//! static).
template <class T>
std::array<double, 4> cell_key(const ParticleCodec& codec, int gas_slot, const T* yc) {
  return {value_of(yc[codec.sigma_slot]), value_of(yc[codec.qm_slot]),
          codec.qphi_slot >= 0 ? value_of(yc[codec.qphi_slot]) : 0.0,
          gas_slot >= 0 ? value_of(yc[gas_slot]) : 0.0};
}

//! The state components the particle laws are differentiated by: Sigma_d, Q_m, (with
//! porosity) Q_phi and (with evolving gas) Sigma_g, as the derivative directions 0..n-1
//! of a per-cell evaluation whose gradient ad_chain carries onto each caller's seeds.
struct Seeds {
  int slots[4];
  int key_index[4];  // entry of cell_key for each direction
  int n = 0;
  Seeds(const ParticleCodec& codec, int gas_slot) {
    add(codec.sigma_slot, 0);
    add(codec.qm_slot, 1);
    if (codec.qphi_slot >= 0) add(codec.qphi_slot, 2);
    if (gas_slot >= 0) add(gas_slot, 3);
  }
  void add(int slot, int key) {
    slots[n] = slot;
    key_index[n++] = key;
  }
  //! The cell's state at `key` with the seeds as the AD directions (A: AD where the
  //! gas evolves, whose laws are written for it; ADCell otherwise).
  template <class A>
  void seed(const std::array<double, 4>& key, A* local) const {
    for (int i = 0; i < kMaxLocalDerivs; ++i) local[i] = A(0.0);
    for (int i = 0; i < n; ++i) local[slots[i]] = ad_seed<A>(key[key_index[i]], i);
  }
  //! The first n derivatives of `x` (the gradient by the seeds), zero-padded to 4.
  template <class A>
  std::array<double, 4> gradient(const A& x) const {
    std::array<double, 4> g{};
    for (int i = 0; i < n; ++i) g[i] = x.derivatives()[i];
    return g;
  }
};
}  // namespace

template <class T>
T ParticleCodec::ln_mass_ratio(int cell, const T* yc) const {
  const T& sigma = yc[sigma_slot];
  const T x = yc[qm_slot] * sigma / (sigma * sigma + eps_sigma * eps_sigma);
  // soft clamp to [x_lo, x_max]: exact inside, smooth at the edges
  const T above = x_lo[cell] + physics::softplus<T>(x - x_lo[cell], kClampSharpness);
  return above - physics::softplus<T>(above - x_max, kClampSharpness);
}

template <class T>
T ParticleCodec::mass(int cell, const T* yc) const {
  using std::exp;
  return m_ref * exp(ln_mass_ratio(cell, yc));
}

template <class T>
T ParticleCodec::phi(const T* yc) const {
  using std::exp;
  if (qphi_slot < 0) return T(1.0);
  const T& sigma = yc[sigma_slot];
  const T y = yc[qphi_slot] * sigma / (sigma * sigma + eps_sigma * eps_sigma);
  // 1e-10 <= phi <= 1: soft clamps of y = ln(1/phi) to [0, y_max]
  const T y_pos = physics::softplus<T>(y, kClampSharpness);
  return exp(-(y_pos - physics::softplus<T>(y_pos - y_max, kClampSharpness)));
}

// Used by the engine for output (double) and by the Jacobians (AD).
template double ParticleCodec::ln_mass_ratio<double>(int, const double*) const;
template double ParticleCodec::mass<double>(int, const double*) const;
template double ParticleCodec::phi<double>(const double*) const;
template AD ParticleCodec::mass<AD>(int, const AD*) const;
template AD ParticleCodec::phi<AD>(const AD*) const;

physics::LocalGasT<AD> CellGas::at_ad(int cell, const AD* yc) const {
  // as at(), with the ratio carrying the derivatives of Sigma_g
  return physics::with_density_ratio(reference_[cell],
                                     AD(yc[gas_.slot] / reference_[cell].sigma_g));
}

const GrowthStokes::Particle& GrowthStokes::particle(int cell, const double* yc) const {
  if (cache_.empty()) {
    cache_.assign(species_.size(), Particle{});
    cache_key_.assign(species_.size(), {-1.0, -1.0, -1.0, -1.0});
  }
  const auto key = cell_key(codec_, gas_.evolves_slot(), yc);
  Particle& p = cache_[cell];
  if (key == cache_key_[cell]) return p;
  p.m = codec_.mass(cell, yc);
  p.phi = codec_.phi(yc);
  p.a = physics::radius(p.m, p.phi, species_[cell].rho0);
  p.st = physics::stokes_number_of_radius(p.a, p.phi, species_[cell].rho0,
                                          gas_.at(cell, yc), law_);
  cache_key_[cell] = key;
  return p;
}

double GrowthStokes::St(int cell, const double* yc) const {
  return particle(cell, yc).st;
}

template <class A>
A GrowthStokes::st_chained(int cell, const A* yc) const {
  if (ad_cache_.empty()) ad_cache_.resize(species_.size());
  const auto key = cell_key(codec_, gas_.evolves_slot(), yc);
  const Seeds seeds(codec_, gas_.evolves_slot());
  AdEntry& e = ad_cache_[cell];
  if (e.key != key) {
    // St depends on the state through m and phi (Sigma_d, Q_m, Q_phi) and the gas
    // density (Sigma_g): evaluate once, by the cell's own directions.
    const double rho0 = species_[cell].rho0;
    if (gas_.evolves_slot() >= 0) {
      AD local[kMaxLocalDerivs];
      seeds.seed(key, local);
      const AD m = codec_.mass(cell, local), phi = codec_.phi(local);
      const AD st =
          physics::stokes_number_ad_gas(m, phi, rho0, gas_.at_ad(cell, local), law_);
      e.st = st.value();
      e.grad = seeds.gradient(st);
    } else {
      ADCell local[kMaxLocalDerivs];
      seeds.seed(key, local);
      const ADCell m = codec_.mass(cell, local), phi = codec_.phi(local);
      const ADCell st = physics::stokes_number(m, phi, rho0, gas_.at(cell, local), law_);
      e.st = st.value();
      e.grad = seeds.gradient(st);
    }
    e.key = key;
  }
  return ad_chain(e.st, e.grad.data(), seeds.slots, seeds.n, yc);
}

AD GrowthStokes::St(int cell, const AD* yc) const { return st_chained(cell, yc); }
ADCell GrowthStokes::St(int cell, const ADCell* yc) const { return st_chained(cell, yc); }

PorousGrowth::PorousGrowth(StateLayout& layout, ParticleCodec& codec, const CellGas& gas,
                           const GrowthStokes& stokes,
                           const std::vector<physics::Species>& species,
                           physics::GrowthOptions options, double sigma_scale)
    : CellRangeForm(layout),
      codec_(codec),
      gas_(gas),
      stokes_(stokes),
      species_(species),
      opt_(options) {
  codec.qm_slot =
      layout.add_cell_var({"q_m", "g cm^-2",
                           "log-moment Sigma_d ln(m/m_ref) of the particle mass "
                           "(spec §6.2)",
                           sigma_scale, false});
  if (opt_.porosity)
    codec.qphi_slot = layout.add_cell_var(
        {"q_phi", "g cm^-2",
         "log-moment Sigma_d ln(1/phi) of the filling factor (spec §6.2)", sigma_scale,
         false});
}

template <class T>
physics::ParticleRates<T> PorousGrowth::compute_rates(int cell, const T* yc) const {
  if constexpr (std::is_same_v<T, double>) {  // m, phi, a, St computed once per state
    const GrowthStokes::Particle& p = stokes_.particle(cell, yc);
    return physics::particle_rates(yc[codec_.sigma_slot], p.m, p.phi, p.st,
                                   gas_.at(cell, yc), species_[cell], opt_, &p.a);
  } else {
    const T m = codec_.mass(cell, yc), phi = codec_.phi(yc), st = stokes_.St(cell, yc);
    if constexpr (std::is_same_v<T, AD>) {  // evolving gas (rates_ad)
      return physics::particle_rates_ad_gas(yc[codec_.sigma_slot], m, phi, st,
                                            gas_.at_ad(cell, yc), species_[cell], opt_);
    } else {  // ADCell: static gas
      return physics::particle_rates(yc[codec_.sigma_slot], m, phi, st, gas_.at(cell, yc),
                                     species_[cell], opt_);
    }
  }
}

const physics::ParticleRates<double>& PorousGrowth::cell_rates(int cell,
                                                               const double* yc) const {
  if (memo_.empty()) {
    memo_.resize(species_.size());
    memo_key_.assign(species_.size(), {-1.0, -1.0, -1.0, -1.0});
  }
  const auto key = cell_key(codec_, gas_.evolves_slot(), yc);
  if (key != memo_key_[cell]) {
    memo_[cell] = compute_rates(cell, yc);
    memo_key_[cell] = key;
  }
  return memo_[cell];
}

void PorousGrowth::rates_ad(int cell, const AD* yc, AD& dlnm_dt, AD& dlnphi_dt) const {
  if (ad_memo_.empty()) ad_memo_.resize(species_.size());
  const auto key = cell_key(codec_, gas_.evolves_slot(), yc);
  const Seeds seeds(codec_, gas_.evolves_slot());
  const int n = seeds.n;
  AdRates& e = ad_memo_[cell];
  if (e.key != key) {
    // The rates depend on the state through Sigma_d, m, phi and the gas density: evaluate
    // once, by the cell's own directions.
    const auto store = [&](const auto& r) {
      e.dlnm = r.dlnm_dt.value();
      e.dlnphi = r.dlnphi_dt.value();
      e.grad_m = seeds.gradient(r.dlnm_dt);
      e.grad_phi = seeds.gradient(r.dlnphi_dt);
    };
    if (gas_.evolves_slot() >= 0) {
      AD local[kMaxLocalDerivs];
      seeds.seed(key, local);
      store(compute_rates(cell, local));
    } else {
      ADCell local[kMaxLocalDerivs];
      seeds.seed(key, local);
      store(compute_rates(cell, local));
    }
    e.key = key;
  }
  dlnm_dt = ad_chain(e.dlnm, e.grad_m.data(), seeds.slots, n, yc);
  dlnphi_dt = ad_chain(e.dlnphi, e.grad_phi.data(), seeds.slots, n, yc);
}

template <class T>
void PorousGrowth::cell_sources(int cell, const T* yc, T& dqm, T& dqphi) const {
  const T& sigma = yc[codec_.sigma_slot];
  if constexpr (std::is_same_v<T, double>) {
    const auto& r = cell_rates(cell, yc);
    dqm = sigma * r.dlnm_dt;       // spec §6.2
    dqphi = -sigma * r.dlnphi_dt;  // spec §6.2
  } else {
    AD dlnm_dt, dlnphi_dt;
    rates_ad(cell, yc, dlnm_dt, dlnphi_dt);
    dqm = sigma * dlnm_dt;       // spec §6.2
    dqphi = -sigma * dlnphi_dt;  // spec §6.2
  }
}

void PorousGrowth::declare_pattern(PatternBuilder& p) const {
  const int nv = layout_.n_cell_vars();
  for (int i = 0; i < layout_.n_cells(); ++i)
    for (int row : {codec_.qm_slot, codec_.qphi_slot}) {
      if (row < 0) continue;
      for (int j = 0; j < nv; ++j) p.add(layout_.index(i, row), layout_.index(i, j));
    }
}

void PorousGrowth::add_rhs_cells(double, std::span<const double> y,
                                 std::span<double> ydot, int lo, int hi) const {
  for (int i = lo; i < hi; ++i) {
    double dqm = 0.0, dqphi = 0.0;
    cell_sources(i, &y[layout_.index(i, 0)], dqm, dqphi);
    ydot[layout_.index(i, codec_.qm_slot)] += dqm;
    if (codec_.qphi_slot >= 0) ydot[layout_.index(i, codec_.qphi_slot)] += dqphi;
  }
}

void PorousGrowth::add_jacobian_cells(double, std::span<const double> y,
                                      JacobianValues& jac, int lo, int hi) const {
  const int nv = layout_.n_cell_vars();
  AD yc[kMaxLocalDerivs];
  for (int i = lo; i < hi; ++i) {
    for (int j = 0; j < nv; ++j) yc[j] = ad_seed(y[layout_.index(i, j)], j);
    AD dqm, dqphi;
    cell_sources(i, yc, dqm, dqphi);
    for (const auto& [slot, val] :
         {std::pair{codec_.qm_slot, &dqm}, {codec_.qphi_slot, &dqphi}}) {
      if (slot < 0) continue;
      for (int j = 0; j < nv; ++j)
        jac.add(layout_.index(i, slot), layout_.index(i, j), val->derivatives()[j]);
    }
  }
}

physics::ParticleRates<double> PorousGrowth::rates(int cell,
                                                   std::span<const double> y) const {
  return compute_rates(cell, &y[layout_.index(cell, 0)]);
}

std::vector<OutputField> PorousGrowth::output_fields() const {
  const int n = layout_.n_cells();
  const std::size_t cells = static_cast<std::size_t>(n);
  // a value of every cell from its state yc and its rates r
  const auto per_cell = [this, n](auto value) {
    return [this, n, value](std::span<const double> y) {
      std::vector<double> out(n);
      for (int i = 0; i < n; ++i) out[i] = value(i, &y[layout_.index(i, 0)], y);
      return out;
    };
  };
  std::vector<OutputField> fields{
      {"m", cells, "g", "mass of the mass-dominating particle",
       per_cell([this](int i, const double* yc, auto) { return codec_.mass(i, yc); })},
      {"phi", cells, "", "filling factor of the mass-dominating particle",
       per_cell([this](int, const double* yc, auto) { return codec_.phi(yc); })},
      {"a", cells, "cm", "radius of the mass-dominating particle",
       per_cell([this](int i, const double*, auto y) { return rates(i, y).a; })},
      {"rho_int", cells, "g cm^-3", "internal density phi rho0",
       per_cell([this](int i, const double* yc, auto) {
         return codec_.phi(yc) * species_[i].rho0;
       })},
      {"dv", cells, "cm s^-1", "collision speed used for growth (spec §3)",
       per_cell([this](int i, const double*, auto y) { return rates(i, y).dv; })},
      {"t_grow", cells, "yr", "growth time m/|dm/dt| (inf: growth halted)",
       per_cell([this](int i, const double* yc, auto y) {
         // +inf where growth has halted exactly (a saturated erosion switch gives
         // dm/dt = 0)
         const double dm_dt = rates(i, y).dm_dt;
         return dm_dt != 0.0 ? codec_.mass(i, yc) / std::abs(dm_dt) / units::kYr
                             : std::numeric_limits<double>::infinity();
       })}};
  if (opt_.eroding())
    fields.push_back(
        {"dv_ls", cells, "cm s^-1",
         "collision speed against the small projectiles, which erosion compares with "
         "v_eros (spec §3, §5.1-§5.2)",
         per_cell([this](int i, const double*, auto y) { return rates(i, y).dv_ls; })});
  return fields;
}

}  // namespace panoptic
