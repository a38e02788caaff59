#include "src/model/output_table.hpp"

#include <sstream>

namespace panoptic {
namespace {

// A '|' inside a cell would end it: Markdown escapes it as "\|".
std::string escaped(const std::string& text) {
  std::string out;
  for (const char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

}  // namespace

Config every_process_scene() {
  const std::vector<std::string> on{
      "grid.n_cells=16",       "gas.evolve=true",       "growth.enabled=true",
      "porosity.enabled=true", "erosion.model=balance", "planetesimals.coagulation=true",
      "planetesimals.si=d16"};
  return load_scene_text("", "every process", on);
}

std::vector<OutputEntry> output_entries(const std::string& group,
                                        std::span<const OutputField> fields) {
  std::vector<OutputEntry> rows;
  for (const OutputField& f : fields)
    rows.push_back({group + "/" + f.name, f.units, f.description});
  return rows;
}

std::vector<OutputEntry> output_entries(std::span<const StaticField> fields) {
  std::vector<OutputEntry> rows;
  for (const StaticField& f : fields)
    rows.push_back({f.group + "/" + f.name, f.units, f.description});
  return rows;
}

std::vector<OutputEntry> output_entries(std::span<const OutputAttribute> attributes) {
  std::vector<OutputEntry> rows;
  for (const OutputAttribute& a : attributes)
    rows.push_back({a.group + "@" + a.name, a.units, a.description});
  return rows;
}

std::string output_table_markdown(std::span<const OutputEntry> entries) {
  std::ostringstream s;
  s << "| group/field | units | description |\n";
  s << "|---|---|---|\n";
  for (const OutputEntry& e : entries)
    s << "| " << e.path << " | " << (e.units.empty() ? "-" : e.units) << " | "
      << escaped(e.description) << " |\n";
  return s.str();
}

}  // namespace panoptic
