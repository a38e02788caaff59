#include "src/run/output_reference.hpp"

#include <vector>

#include "src/io/run_output.hpp"
#include "src/model/output_table.hpp"
#include "src/model/simulation.hpp"
#include "src/run/diagnostics.hpp"
#include "src/run/variant.hpp"
#include "src/solver/solver_stats.hpp"

namespace panoptic {

std::string output_reference_markdown() {
  const Simulation every(every_process_scene());  // so every field is declared
  std::vector<OutputEntry> rows;
  auto add = [&rows](std::vector<OutputEntry> more) {
    rows.insert(rows.end(), more.begin(), more.end());
  };
  add(output_entries(RunOutput::root_attributes({}, "")));
  add(output_entries(variant_attributes({})));
  add(output_entries(every.static_fields()));
  add(output_entries(every.output_attributes()));
  rows.push_back(RunOutput::snapshot_time());
  add(output_entries("snapshots", every.output_fields()));
  add(output_entries("snapshots", RunDiagnostics::output_fields(every)));
  add(output_entries("timeseries", RunDiagnostics::timeseries_fields(every)));
  add(output_entries(RunDiagnostics::timeseries_attributes(every)));
  add(output_entries("summary", RunDiagnostics::summary_fields(every)));
  add(output_entries(RunOutput::solver_attributes(SolverStats{}, 0.0, "")));
  return output_table_markdown(rows);
}

}  // namespace panoptic
