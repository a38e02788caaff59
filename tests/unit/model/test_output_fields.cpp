// The snapshot fields as the modules and the model declare them (OutputField): the table
// of `panoptic reference --outputs` lists every field a fiducial output holds, with the
// units attribute the file carries; the registry builds the fiducial scene's modules in
// the order that sets its state layout.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "src/io/h5.hpp"
#include "src/io/run_output.hpp"
#include "src/model/module_registry.hpp"
#include "src/model/output_table.hpp"
#include "src/model/simulation.hpp"
#include "src/run/diagnostics.hpp"
#include "src/run/output_reference.hpp"
#include "src/scene/config.hpp"

namespace fs = std::filesystem;
using namespace panoptic;

namespace {

std::string fiducial_scene() {
  return std::string(PANOPTIC_SOURCE_DIR) + "/params/fiducial.toml";
}

std::string units_of(hid_t g, const std::string& name) {
  h5::Handle ds(H5Dopen2(g, name.c_str(), H5P_DEFAULT), H5Dclose);
  return h5::get_attr_string(ds.get(), "units");
}

// Every dataset a scene's output is set up with (prepare_output and the diagnostics'
// declarations) is a row of the table, with the units attribute the file carries.
void expect_every_dataset_listed(const std::string& scene, const std::string& tag) {
  const Simulation sim(load_scene(scene, {}));
  const fs::path dir = fs::temp_directory_path() / "panoptic_output_fields";
  fs::create_directories(dir);
  const fs::path path = dir / (tag + ".h5");
  fs::remove(path);
  {
    RunOutput out(path, false, {tag, "", "", ""});
    sim.prepare_output(out);
    RunDiagnostics diag(sim, out, 0.0);
    out.start_appending();  // the file set up aside moves into place
  }
  const std::string table = output_reference_markdown();

  h5::quiet_errors();
  h5::Handle file = h5::open_file(path.string(), false);
  for (const char* group : {"grid", "disk", "pebbles", "snapshots"}) {
    h5::Handle g = h5::open_group(file.get(), group);
    const auto names = h5::dataset_names(g.get());
    ASSERT_FALSE(names.empty()) << tag << " " << group;
    for (const std::string& name : names) {
      if (name == "time") continue;  // the stacks' own time axis (RunOutput), not a field
      const std::string units = units_of(g.get(), name);
      const std::string row = "| " + std::string(group) + "/" + name + " | " +
                              (units.empty() ? "-" : units) + " | ";
      EXPECT_NE(table.find(row), std::string::npos) << tag << ": " << row << "\n"
                                                    << table;
    }
  }
}

}  // namespace

TEST(OutputTable, ListsEveryFieldOfAFiducialOutput) {
  expect_every_dataset_listed(fiducial_scene(), "fiducial");
}

TEST(OutputTable, ListsEveryFieldOfADistributionOutput) {
  // the size distribution's own datasets (/snapshots/sigma, /grid/m_bins, a_bins) too
  expect_every_dataset_listed(
      std::string(PANOPTIC_SOURCE_DIR) + "/params/tests/distribution_small.toml",
      "distribution_small");
  const std::string table = output_reference_markdown();
  for (const char* row : {"| snapshots/sigma | g cm^-2 | ", "| grid/m_bins | g | ",
                          "| grid/a_bins | cm | "})
    EXPECT_NE(table.find(row), std::string::npos) << row;
}

TEST(OutputTable, EveryProcessSceneDeclaresTheFieldsOfEveryModule) {
  const Simulation every(every_process_scene());
  std::vector<std::string> names;
  for (const OutputField& f : every.output_fields()) names.push_back(f.name);
  for (const char* want : {"sigma_d", "sigma_g", "St", "v_r", "mdot_d", "m_out_gas", "m",
                           "phi", "a", "rho_int", "dv", "t_grow", "dv_ls", "sigma_pl",
                           "sigma_pl_coag", "sigma_pl_si", "m_through", "pebble_flux"})
    EXPECT_NE(std::find(names.begin(), names.end(), want), names.end()) << want;
  // the size distribution (model.kind = "distribution") replaces the single-size
  // modules (size_distribution, and bin_planetesimals for the planetesimal channels),
  // so it has a scene of its own
  const std::vector<std::string> channels{"planetesimals.coagulation=true",
                                          "planetesimals.si=\"d16\""};
  const Simulation dist(load_scene(
      std::string(PANOPTIC_SOURCE_DIR) + "/params/tests/distribution_small.toml",
      channels));
  names.clear();
  for (const OutputField& f : dist.output_fields()) names.push_back(f.name);
  for (const char* want :
       {"sigma", "sigma_d", "sigma_g", "St", "mdot_d", "m", "a", "m_out_inner",
        "m_through", "pebble_flux", "sigma_pl", "sigma_pl_coag", "sigma_pl_si"})
    EXPECT_NE(std::find(names.begin(), names.end(), want), names.end()) << want;
  EXPECT_EQ(every.model().modules().size() + 2, module_registry().size());
  EXPECT_EQ(dist.model().modules().back()->name(), "size_distribution");
}

TEST(ModuleRegistry, FiducialLayoutInBuildOrder) {
  // the build order sets the state layout: Sigma_d (transport), then Q_m and Q_phi
  // (growth), then the planetesimal channels; the monitors and the snow line's booked
  // mass after every module's own global variables
  const Simulation fiducial(load_scene(fiducial_scene(), {}));
  const StateLayout& L = fiducial.model().layout();
  std::string cells, globals;
  for (int k = 0; k < L.n_cell_vars(); ++k) cells += L.cell_var(k).name + " ";
  for (int k = 0; k < L.n_global_vars(); ++k) globals += L.global_var(k).name + " ";
  EXPECT_EQ(cells, "sigma_d q_m q_phi sigma_pl_coag sigma_pl_si ");
  EXPECT_EQ(globals,
            "m_out_dust m_through_146 m_through_157 m_through_254 m_through_304 "
            "m_sublimated ");
  // the right-hand sides are summed with the transport last
  std::string order;
  for (const auto& m : fiducial.model().modules()) order += std::string(m->name()) + " ";
  EXPECT_EQ(order, "porous_growth planetesimals dust_transport ");
}
