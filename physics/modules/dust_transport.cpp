#include "physics/modules/dust_transport.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "disk/gas_disk.hpp"
#include "disk/pressure_gradient.hpp"
#include "disk/viscous_gas.hpp"
#include "src/core/units.hpp"
#include "src/solver/grid.hpp"

namespace panoptic {

DustTransport::DustTransport(StateLayout& layout, const Grid& grid, const GasDisk& disk,
                             const GasColumn& gas, const ViscousStencil* viscous,
                             const StokesModel& stokes, DustTransportOptions options,
                             double sigma_scale, double dust_mass)
    : CellRangeForm(layout),
      grid_(grid),
      gas_(gas),
      stokes_(stokes),
      flux_(grid, disk, gas, viscous, options),
      opt_(options),
      mass_unit_(dust_mass) {
  // No >= 0 constraint on Sigma_d: CVODE lets a constrained component dip below zero by
  // up to about its error weight and a restart (CvodeIntegrator::reinit) must then clip
  // it, creating that much dust, which the dust budget of the LBP test sees
  // (tests/bench/results/performance_log.md). The transport and the sinks are linear in
  // Sigma_d with non-negative exact solutions, so its negative excursions are integration
  // error held to the absolute tolerance by the error test. The decoded m and phi read
  // Sigma_d through the codec's floor (ParticleCodec::eps_sigma), the SI triggers
  // through a smooth positive part (Planetesimals::cell_rates), so a negative Sigma_d
  // (which Newton iterates reach in any case) is safe there.
  slot_ = layout.add_cell_var(
      {"sigma_d", "g cm^-2", "dust surface density", sigma_scale, false});
  const double area_total =
      units::kPi * grid.r_f(grid.n_cells()) * grid.r_f(grid.n_cells());
  // The booked masses (this one, the sublimated ice, the pebble monitors) feed nothing
  // back, like Sigma_pl, but stay in CVODE's error test: their error holds the step where
  // Newton converges at the inner edge; left out, Newton fails to converge there many
  // times more often and the runs take more steps, several times more on a grid reaching
  // in to 0.05 au (tests/bench/results/performance_log.md). They carry no >= 0
  // constraint: clipping would lose mass.
  g_out_ = layout.add_global_var({"m_out_dust", "initial dust mass",
                                  "dust mass that left through r_in, in units of the "
                                  "initial dust mass on the grid",
                                  sigma_scale * area_total / dust_mass, false});
  transported_.push_back(slot_);
}

void DustTransport::set_snowline(StateLayout& layout, int face, double f_ice,
                                 int qm_slot) {
  snow_face_ = face;
  f_ice_ = f_ice;
  snow_qm_slot_ = qm_slot;
  g_sub_ =
      add_booked_mass(layout, "m_sublimated", "ice that sublimated at the snow line");
}

int DustTransport::add_booked_mass(StateLayout& layout, const std::string& name,
                                   const std::string& what) const {
  return layout.add_global_var(booked_mass_info(name, what,
                                                layout.cell_var(slot_).abs_scale,
                                                grid_.r_f(grid_.n_cells()), mass_unit_));
}

int DustTransport::add_monitor(StateLayout& layout, int face) {
  if (monitor_slot_.empty()) monitor_slot_.assign(grid_.n_cells(), -1);
  if (monitor_slot_[face] >= 0) return monitor_slot_[face];
  monitor_slot_[face] =
      add_booked_mass(layout, "m_through_" + std::to_string(face),
                      "dust mass that crossed a face inward (pebble flux, spec §8)");
  return monitor_slot_[face];
}

template <class T>
void DustTransport::received_flows(int f, const T* flows, T* received, T& sublimated,
                                   bool inward) const {
  const int nt = static_cast<int>(transported_.size());
  for (int k = 0; k < nt; ++k) received[k] = flows[k];
  sublimated = T(0.0);
  if (f != snow_face_ || !inward) return;
  // spec §6.3 and §11 #18: the ice sublimates, m -> (1 - f_ice) m, phi kept
  const double keep = 1.0 - f_ice_;
  for (int k = 0; k < nt; ++k) received[k] = keep * flows[k];
  for (int k = 0; k < nt; ++k)
    if (transported_[k] ==
        snow_qm_slot_)  // Q_m = Sigma ln(m/m_ref): ln m drops by ln keep
      received[k] += keep * std::log(keep) * flows[0];
  sublimated = f_ice_ * flows[0];  // < 0: mass leaving the dust
}

template <class T>
T DustTransport::velocity(int f, const T* ya, const T* yb, const T& st) const {
  const int a = f > 0 ? f - 1 : 0;
  return flux_.velocity(f, gas_.sigma(a, ya), gas_.sigma(a + 1, yb), st);
}

template <class T>
int DustTransport::face_flows(int f, const T* ya, const T* yb, std::span<const double> y,
                              T* flows, double* d_far) const {
  const int nt = static_cast<int>(transported_.size());
  // Stokes number on the face (DustFaceFlux::face_stokes): the geometric mean of the
  // neighbours. With `upwind_stokes` each cell's dust leaves at the speed of its own St
  // instead (flux-vector splitting, v_a^+ q_a + v_b^- q_b); on the fiducial scene that
  // needed many more steps and drove stronger travelling waves at the growth front
  // (tests/bench/results/performance_log.md), so it is an option.
  const T st_a = stokes_.St(f > 0 ? f - 1 : 0, ya);
  const T st_b = f > 0 ? T(stokes_.St(f, yb)) : st_a;
  const T sg_a = gas_.sigma(f > 0 ? f - 1 : 0, ya), sg_b = gas_.sigma(f > 0 ? f : 1, yb);
  const auto face =
      flux_.face_terms(f, DustFaceFlux::face_stokes(f, st_a, st_b), sg_a, sg_b);
  if (opt_.upwind_stokes && f > 0) {  // each cell's dust at its own speed
    const auto face_a = flux_.face_terms(f, st_a, sg_a, sg_b);
    const auto face_b = flux_.face_terms(f, st_b, sg_a, sg_b);
    for (int k = 0; k < nt; ++k) {
      const int s = transported_[k];
      flows[k] = flux_.split_flow(f, face_a, face_b, face, sg_a, sg_b, ya[s], yb[s]);
    }
    return -1;
  }
  for (int k = 0; k < nt; ++k) {
    const int s = transported_[k];
    flows[k] = flux_.flow(f, face, sg_a, sg_b, ya[s], yb[s],
                          face.far >= 0 ? y[layout_.index(face.far, s)] : 0.0,
                          d_far ? &d_far[k] : nullptr);
  }
  return face.far;
}

void DustTransport::declare_pattern(PatternBuilder& p) const {
  const int n = grid_.n_cells(), nv = layout_.n_cell_vars();
  for (int f = 0; f < n; ++f) {
    const int a = f > 0 ? f - 1 : 0, b = f > 0 ? f : 1;
    std::vector<long> rows;
    for (int s : transported_) {
      rows.push_back(layout_.index(f, s));
      if (f > 0) rows.push_back(layout_.index(f - 1, s));
    }
    if (f == 0) rows.push_back(layout_.global_index(g_out_));
    if (f == snow_face_) rows.push_back(layout_.global_index(g_sub_));
    if (!monitor_slot_.empty() && monitor_slot_[f] >= 0)
      rows.push_back(layout_.global_index(monitor_slot_[f]));
    for (long row : rows) {
      for (int j = 0; j < nv; ++j) {
        p.add(row, layout_.index(a, j));
        p.add(row, layout_.index(b, j));
      }
      // limited scheme: the far upwind cell on either side (the drift may turn)
      if (opt_.limited && opt_.drift && f > 0)
        for (int far : {f - 2, f + 1})
          if (far >= 0 && far < n)
            for (int s : transported_) p.add(row, layout_.index(far, s));
    }
  }
}

// Cells [lo, hi) are fed by the faces lo..hi (face f: between cells f - 1 and f; face n,
// the outer edge, carries nothing, spec §6.3).
void DustTransport::add_rhs_cells(double, std::span<const double> y,
                                  std::span<double> ydot, int lo, int hi) const {
  const int n = grid_.n_cells(), nt = static_cast<int>(transported_.size());
  std::array<double, kMaxVars> flows{}, received{};
  double sublimated = 0.0;
  for (int f = lo; f <= std::min(hi, n - 1); ++f) {
    const int a = f > 0 ? f - 1 : 0, b = f > 0 ? f : 1;
    face_flows(f, &y[layout_.index(a, 0)], &y[layout_.index(b, 0)], y, flows.data());
    received_flows(f, flows.data(), received.data(), sublimated, flows[0] < 0.0);
    for (int k = 0; k < nt; ++k) {
      const int s = transported_[k];
      ydot[layout_.index(f, s)] += flows[k] / grid_.area(f);
      if (f > 0) ydot[layout_.index(f - 1, s)] -= received[k] / grid_.area(f - 1);
    }
    if (f == 0) ydot[layout_.global_index(g_out_)] -= flows[0] / mass_unit_;
    if (f == snow_face_) ydot[layout_.global_index(g_sub_)] -= sublimated / mass_unit_;
    if (!monitor_slot_.empty() && monitor_slot_[f] >= 0)
      ydot[layout_.global_index(monitor_slot_[f])] -= flows[0] / mass_unit_;
  }
}

void DustTransport::add_jacobian_cells(double, std::span<const double> y,
                                       JacobianValues& jac, int lo, int hi) const {
  const int n = grid_.n_cells(), nv = layout_.n_cell_vars();
  const int nt = static_cast<int>(transported_.size()), nloc = 2 * nv;
  std::array<AD, kMaxVars> ya, yb, flows, received;
  std::array<double, kMaxVars> d_far{}, unit{}, rec_far{};
  AD sublimated;
  for (int f = lo; f <= std::min(hi, n - 1); ++f) {
    const int a = f > 0 ? f - 1 : 0, b = f > 0 ? f : 1;
    for (int j = 0; j < nv; ++j) {
      ya[j] = ad_seed(y[layout_.index(a, j)], j);
      yb[j] = ad_seed(y[layout_.index(b, j)], nv + j);
    }
    const int far = face_flows(f, ya.data(), yb.data(), y, flows.data(), d_far.data());
    const bool inward = flows[0].value() < 0.0;
    received_flows(f, flows.data(), received.data(), sublimated, inward);
    if (far >= 0) {
      // The far upwind cell enters only through the limiter: d flows[k]/d y[far, s_j] =
      // delta_kj d_far[j]; what the rows receive is the same linear map of it.
      for (int j = 0; j < nt; ++j) {
        if (d_far[j] == 0.0) continue;
        const long col = layout_.index(far, transported_[j]);
        unit.fill(0.0);
        unit[j] = d_far[j];
        double sub = 0.0;
        received_flows(f, unit.data(), rec_far.data(), sub, inward);
        jac.add(layout_.index(f, transported_[j]), col, d_far[j] / grid_.area(f));
        for (int k = 0; k < nt; ++k)
          if (rec_far[k] != 0.0)
            jac.add(layout_.index(f - 1, transported_[k]), col,
                    -rec_far[k] / grid_.area(f - 1));
        if (j == 0 && !monitor_slot_.empty() && monitor_slot_[f] >= 0)
          jac.add(layout_.global_index(monitor_slot_[f]), col, -d_far[0] / mass_unit_);
        if (f == snow_face_ && sub != 0.0)
          jac.add(layout_.global_index(g_sub_), col, -sub / mass_unit_);
      }
    }
    auto column = [&](int j) {
      return j < nv ? layout_.index(a, j) : layout_.index(b, j - nv);
    };
    for (int k = 0; k < nt; ++k) {
      const auto& d = flows[k].derivatives();
      const auto& dr = received[k].derivatives();
      const int s = transported_[k];
      for (int j = 0; j < nloc; ++j) {
        if (d[j] != 0.0) jac.add(layout_.index(f, s), column(j), d[j] / grid_.area(f));
        if (f > 0 && dr[j] != 0.0)
          jac.add(layout_.index(f - 1, s), column(j), -dr[j] / grid_.area(f - 1));
        if (f == 0 && k == 0 && d[j] != 0.0)
          jac.add(layout_.global_index(g_out_), column(j), -d[j] / mass_unit_);
      }
    }
    if (!monitor_slot_.empty() && monitor_slot_[f] >= 0)
      for (int j = 0; j < nloc; ++j)
        if (flows[0].derivatives()[j] != 0.0)
          jac.add(layout_.global_index(monitor_slot_[f]), column(j),
                  -flows[0].derivatives()[j] / mass_unit_);
    if (f == snow_face_)
      for (int j = 0; j < nloc; ++j)
        if (sublimated.derivatives()[j] != 0.0)
          jac.add(layout_.global_index(g_sub_), column(j),
                  -sublimated.derivatives()[j] / mass_unit_);
  }
}

std::vector<double> DustTransport::mass_flow(std::span<const double> y) const {
  const int n = grid_.n_cells();
  std::vector<double> out(n + 1, 0.0);
  std::array<double, kMaxVars> flows{};
  for (int f = 0; f < n; ++f) {
    const int a = f > 0 ? f - 1 : 0, b = f > 0 ? f : 1;
    face_flows(f, &y[layout_.index(a, 0)], &y[layout_.index(b, 0)], y, flows.data());
    out[f] = flows[0];
  }
  return out;
}

std::vector<double> DustTransport::face_velocity(std::span<const double> y) const {
  const int n = grid_.n_cells();
  std::vector<double> out(n + 1, 0.0);
  for (int f = 0; f < n; ++f) {
    const int a = f > 0 ? f - 1 : 0, b = f > 0 ? f : 1;
    const double* ya = &y[layout_.index(a, 0)];
    const double* yb = &y[layout_.index(b, 0)];
    if (!opt_.drift) continue;
    const double st_a = stokes_.St(a, ya), st_b = f > 0 ? stokes_.St(b, yb) : st_a;
    if (opt_.upwind_stokes && f > 0)  // the speeds split_flow moves each cell's dust at
      out[f] = std::max(velocity(f, ya, yb, st_a), 0.0) +
               std::min(velocity(f, ya, yb, st_b), 0.0);
    else
      out[f] = velocity(f, ya, yb, DustFaceFlux::face_stokes(f, st_a, st_b));
  }
  return out;
}

std::vector<BudgetTerm> DustTransport::budget_terms() const {
  return outflow_budget_terms(
      [this](std::span<const double> y) { return mass_out(y); },
      [this](std::span<const double> y) { return mass_sublimated(y); });
}

double DustTransport::mass_out(std::span<const double> y) const {
  return y[layout_.global_index(g_out_)] * mass_unit_;
}

double DustTransport::mass_sublimated(std::span<const double> y) const {
  return g_sub_ < 0 ? 0.0 : y[layout_.global_index(g_sub_)] * mass_unit_;
}

std::vector<OutputField> DustTransport::output_fields() const {
  const int n = layout_.n_cells();
  const std::size_t cells = static_cast<std::size_t>(n);
  return {{"sigma_d", cells, "g cm^-2", "dust surface density",
           [this, n](std::span<const double> y) {
             std::vector<double> sigma(n);
             for (int i = 0; i < n; ++i) sigma[i] = y[layout_.index(i, slot_)];
             return sigma;
           }},
          {"v_r", cells + 1, "cm s^-1", "dust radial velocity on the faces",
           [this](std::span<const double> y) { return face_velocity(y); }},
          {"mdot_d", cells + 1, "g s^-1",
           "dust mass flow through the faces, positive outward",
           [this](std::span<const double> y) { return mass_flow(y); }}};
}

}  // namespace panoptic
