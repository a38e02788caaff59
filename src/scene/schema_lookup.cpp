#include "src/scene/schema_lookup.hpp"

#include <algorithm>

namespace panoptic::scene_detail {

const KeySpec* find_spec(std::string_view key) {
  for (const KeySpec& spec : scene_keys()) {
    if (spec.key == key) return &spec;
  }
  return nullptr;
}

std::string_view table_of(std::string_view key) { return key.substr(0, key.find('.')); }

std::string_view leaf_of(std::string_view key) {
  const size_t dot = key.find('.');
  return dot == std::string_view::npos ? key : key.substr(dot + 1);
}

// The tables, in schema order.
std::vector<std::string> schema_tables() {
  std::vector<std::string> tables;
  for (const KeySpec& spec : scene_keys()) {
    const std::string t(table_of(spec.key));
    if (std::find(tables.begin(), tables.end(), t) == tables.end()) tables.push_back(t);
  }
  return tables;
}

bool is_table(std::string_view name) {
  for (const KeySpec& spec : scene_keys()) {
    if (table_of(spec.key) == name) return true;
  }
  return false;
}

std::string join(const std::vector<std::string>& items, std::string_view sep) {
  std::string out;
  for (size_t i = 0; i < items.size(); ++i) {
    if (i) out += sep;
    out += items[i];
  }
  return out;
}

std::string keys_of_table(std::string_view table) {
  std::vector<std::string> leaves;
  for (const KeySpec& spec : scene_keys()) {
    if (table_of(spec.key) == table) leaves.emplace_back(leaf_of(spec.key));
  }
  return join(leaves, ", ");
}

}  // namespace panoptic::scene_detail
