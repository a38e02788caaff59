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

std::string output_table_markdown(std::span<const StaticField> static_fields,
                                  std::span<const OutputField> fields) {
  std::ostringstream s;
  s << "| group/field | units | description |\n";
  s << "|---|---|---|\n";
  for (const StaticField& f : static_fields)
    s << "| " << f.group << "/" << f.name << " | " << (f.units.empty() ? "-" : f.units)
      << " | " << escaped(f.description) << " |\n";
  for (const OutputField& f : fields)
    s << "| snapshots/" << f.name << " | " << (f.units.empty() ? "-" : f.units) << " | "
      << escaped(f.description) << " |\n";
  return s.str();
}

}  // namespace panoptic
