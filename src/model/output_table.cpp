#include "src/model/output_table.hpp"

#include <algorithm>
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

Config distribution_scene() {
  const std::vector<std::string> on{"model.kind=distribution",
                                    "grid.n_cells=16",
                                    "gas.evolve=true",
                                    "growth.enabled=true",
                                    "porosity.enabled=false",
                                    "snowline.enabled=false",
                                    "planetesimals.coagulation=true",
                                    "planetesimals.si=d16"};
  return load_scene_text("", "size distribution", on);
}

void merge_entries(std::vector<OutputEntry>& rows, std::span<const OutputEntry> more,
                   const std::string& model) {
  auto group_of = [](const std::string& path) {
    return path.substr(0, path.find_first_of("/@"));
  };
  for (const OutputEntry& e : more) {
    const auto same = std::find_if(
        rows.begin(), rows.end(), [&](const OutputEntry& r) { return r.path == e.path; });
    if (same != rows.end()) {
      if (same->description != e.description)
        same->description += "; " + model + ": " + e.description;
      continue;
    }
    // after the last row of its group, so that a group's rows stay together
    const auto last = std::find_if(rows.rbegin(), rows.rend(), [&](const OutputEntry& r) {
      return group_of(r.path) == group_of(e.path);
    });
    rows.insert(last.base(), {e.path, e.units, "(" + model + ") " + e.description});
  }
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
