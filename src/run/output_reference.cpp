#include "src/run/output_reference.hpp"

#include <vector>

#include "src/io/run_output.hpp"
#include "src/model/output_table.hpp"
#include "src/model/simulation.hpp"
#include "src/run/diagnostics.hpp"
#include "src/run/variant.hpp"
#include "src/solver/solver_stats.hpp"

namespace panoptic {

namespace {

//! The rows a model declares, in the order of the file: static datasets and attributes,
//! snapshots, time series, summary.
std::vector<OutputEntry> model_entries(const Simulation& sim) {
  std::vector<OutputEntry> rows;
  auto add = [&rows](std::vector<OutputEntry> more) {
    rows.insert(rows.end(), more.begin(), more.end());
  };
  add(output_entries(sim.static_fields()));
  add(output_entries(sim.output_attributes()));
  rows.push_back(RunOutput::snapshot_time());
  add(output_entries("snapshots", sim.output_fields()));
  add(output_entries("snapshots", RunDiagnostics::output_fields(sim)));
  add(output_entries("timeseries", RunDiagnostics::timeseries_fields(sim)));
  add(output_entries(RunDiagnostics::timeseries_attributes(sim)));
  add(output_entries("summary", RunDiagnostics::summary_fields(sim)));
  return rows;
}

}  // namespace

std::string output_reference_markdown() {
  // the single-size model with every process on, then what the size distribution adds
  std::vector<OutputEntry> rows = output_entries(RunOutput::root_attributes({}, ""));
  for (const OutputEntry& e : output_entries(variant_attributes({}))) rows.push_back(e);
  std::vector<OutputEntry> model = model_entries(Simulation(every_process_scene()));
  merge_entries(model, model_entries(Simulation(distribution_scene())),
                "model.kind = \"distribution\"");
  rows.insert(rows.end(), model.begin(), model.end());
  for (const OutputEntry& e :
       output_entries(RunOutput::solver_attributes(SolverStats{}, 0.0, "")))
    rows.push_back(e);
  return output_table_markdown(rows);
}

}  // namespace panoptic
