#include <cmath>
#include <string>

#include "disk/gas_disk.hpp"
#include "physics/modules/size_distribution.hpp"
#include "physics/stokes_model.hpp"
#include "src/core/units.hpp"
#include "src/io/run_output.hpp"
#include "src/model/simulation.hpp"

namespace panoptic {

using units::kAu;

std::vector<OutputField> Simulation::make_output_fields() const {
  const int n = grid_.n_cells();
  const std::size_t cells = static_cast<std::size_t>(n), n_mon = monitors_.size();
  std::vector<OutputField> fields;
  // the modules' own, in the order they were built (module_registry.cpp)
  for (const PhysicsModule* m : modules_in_build_order_)
    for (OutputField& f : m->output_fields()) fields.push_back(std::move(f));
  // A field wider than one value per face holds several values per cell (sigma(r, m) of
  // the distribution, 10^4 values a row): deflated. The single-size model's fields are
  // at most one value per face and stay as they were.
  for (OutputField& f : fields) f.compressed = f.width > cells + 1;
  // then the model's: the gas column, the Stokes model, the budget and the monitors
  fields.push_back({"sigma_g", cells, "g cm^-2", "gas surface density",
                    [this, n](std::span<const double> y) {
                      std::vector<double> sg(n);
                      for (int i = 0; i < n; ++i)
                        sg[i] = gas_.sigma(i, &y[layout_->index(i, 0)]);
                      return sg;
                    }});
  if (distribution_)
    fields.push_back(
        {"St", cells, "", "Stokes number of the mass-dominating bin",
         [this](std::span<const double> y) { return distribution_->dominant_st(y); }});
  else
    fields.push_back({"St", cells, "", "Stokes number of the dust",
                      [this, n](std::span<const double> y) {
                        std::vector<double> st(n);
                        for (int i = 0; i < n; ++i)
                          st[i] = stokes_->St(i, &y[layout_->index(i, 0)]);
                        return st;
                      }});
  for (const BudgetTerm& term : budget_terms_)
    if (term.in_snapshots)
      fields.push_back({term.name, 0, "g", term.description,
                        [mass = term.mass](std::span<const double> y) {
                          return std::vector<double>{mass(y)};
                        }});
  fields.push_back({"m_through", n_mon, "g",
                    "cumulative dust mass that crossed each /pebbles/r_au inward",
                    [this](std::span<const double> y) { return pebble_mass(y); }});
  fields.push_back({"pebble_flux", n_mon, "g s^-1",
                    "inward dust mass flow through each /pebbles/r_au",
                    [this](std::span<const double> y) { return pebble_flux(y); }});
  return fields;
}

std::vector<StaticField> Simulation::static_fields() const {
  const int n = grid_.n_cells();
  std::vector<double> r_c(n), r_f(n + 1), T(n), cs(n), om(n), hg(n), alpha(n);
  for (int i = 0; i <= n; ++i) r_f[i] = grid_.r_f(i) / kAu;
  for (int i = 0; i < n; ++i) {
    const double r = grid_.r_c(i);
    r_c[i] = r / kAu;
    T[i] = disk_->temperature(r);
    cs[i] = disk_->c_s(r);
    om[i] = disk_->omega_k(r);
    hg[i] = disk_->h_g(r);
    alpha[i] = disk_->alpha(r);
  }
  std::vector<double> r_mon;
  for (const auto& mon : monitors_) r_mon.push_back(mon.r_au);
  std::vector<StaticField> fields{
      {"grid", "r_c", r_c, "au", "cell centres (geometric mean of the faces)"},
      {"grid", "r_f", r_f, "au", "cell faces (log-spaced, or stretched by grid.stretch)"},
      {"grid", "area", grid_.areas(), "cm^2", "annulus area of each cell"},
      {"disk", "T", T, "K", "midplane temperature"},
      {"disk", "c_s", cs, "cm s^-1", "isothermal sound speed"},
      {"disk", "omega_k", om, "s^-1", "Keplerian angular frequency"},
      {"disk", "h_g", hg, "cm", "gas pressure scale height"},
      {"disk", "alpha", alpha, "", "turbulence parameter"},
      {"disk", "eta", eta_centres(*disk_, grid_, gas_.static_sigma), "",
       "pressure-gradient parameter of the initial gas (spec §1.4)"},
      {"pebbles", "r_au", r_mon, "au",
       "radii (faces) where the pebble flux is recorded; attribute names"}};
  if (distribution_) {  // the mass grid of /snapshots/sigma (spec §15.1)
    fields.push_back({"grid", "m_bins", distribution_->mass_grid().m, "g",
                      "mass of every bin of the size distribution"});
    fields.push_back({"grid", "a_bins", distribution_->bin_radii(), "cm",
                      "radius of every bin (compact, the monomer density of the "
                      "innermost cell's species)"});
  }
  return fields;
}

std::vector<OutputAttribute> Simulation::output_attributes() const {
  std::string monitors;
  for (const auto& mon : monitors_) monitors += (monitors.empty() ? "" : ";") + mon.name;
  std::string terms;
  for (const auto& term : budget_terms_)
    if (term.in_snapshots) terms += (terms.empty() ? "" : ";") + term.name;
  return {{"disk", "r_snow_au", "au",
           "snow line, where T = T_sub (written also when the run has no snow line)",
           disk_->r_snow() / kAu},
          {"pebbles", "names", "", "names of the radii /pebbles/r_au (;-separated)",
           monitors},
          {"snapshots", "budget_terms", "",
           "the datasets of the mass budget terms (;-separated): their sum is the "
           "initial dust mass",
           terms}};
}

void Simulation::prepare_output(RunOutput& out) const {
  for (const StaticField& f : static_fields())
    out.write_static(f.group, f.name, f.values, f.units, f.description);
  for (const OutputField& f : output_fields_)
    out.add_field(f.name, f.width, f.units, f.description, f.compressed);
  for (const OutputAttribute& a : output_attributes()) out.write_attribute(a);
}

std::map<std::string, std::vector<double>> Simulation::snapshot_fields(
    std::span<const double> y) const {
  std::map<std::string, std::vector<double>> values;
  for (const OutputField& f : output_fields_) values[f.name] = f.fill(y);
  return values;
}

}  // namespace panoptic
