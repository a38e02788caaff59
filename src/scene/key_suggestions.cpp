#include "src/scene/key_suggestions.hpp"

#include <algorithm>
#include <limits>

#include "src/scene/schema_lookup.hpp"

namespace panoptic::scene_detail {
namespace {

// No scene key is longer than ~40 characters: a name longer than this is no typo of one
// (comparing it with every key costs O(length) each, seconds for a name of megabytes),
// and a message shows only its start.
constexpr std::size_t kLongestPlausibleKey = 200;

}  // namespace

// Levenshtein distance, case-insensitive (disk.t_1au is a typo of disk.T_1au).
size_t edit_distance(std::string_view a, std::string_view b) {
  const auto lower = [](char c) {
    return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c;
  };
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diag = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t up = row[j];
      const size_t cost = lower(a[i - 1]) == lower(b[j - 1]) ? 0 : 1;
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + cost});
      diag = up;
    }
  }
  return row[b.size()];
}

// The candidate nearest to `word`, if it is near enough to be a plausible typo.
std::optional<std::string> nearest(std::string_view word,
                                   const std::vector<std::string>& candidates) {
  std::optional<std::string> best;
  size_t best_d = std::numeric_limits<size_t>::max();
  for (const std::string& c : candidates) {
    const size_t d = edit_distance(word, c);
    if (d < best_d) {
      best_d = d;
      best = c;
    }
  }
  const size_t limit = std::max<size_t>(2, word.size() / 3);
  if (best && best_d <= limit) return best;
  return std::nullopt;
}

// A key as a message shows it: whole up to kLongestPlausibleKey characters, else its
// start and length.
std::string shown_key(const std::string& key) {
  if (key.size() <= kLongestPlausibleKey) return key;
  return key.substr(0, 80) + "... (a name of " + std::to_string(key.size()) +
         " characters)";
}

// The schema key the user probably meant by `key` ("table.key", or a bare key written
// outside any table): the same leaf in another table first, then the nearest spelling.
std::optional<std::string> suggest_key(std::string_view key) {
  if (key.size() > kLongestPlausibleKey) return std::nullopt;
  const std::string_view leaf = leaf_of(key);
  for (const KeySpec& spec : scene_keys()) {
    if (leaf_of(spec.key) == leaf) return spec.key;
  }
  std::vector<std::string> all;
  for (const KeySpec& spec : scene_keys()) all.push_back(spec.key);
  if (auto best = nearest(key, all)) return best;
  // A bare key: compare with the leaves.
  if (key.find('.') == std::string_view::npos) {
    std::optional<std::string> best;
    size_t best_d = std::numeric_limits<size_t>::max();
    for (const KeySpec& spec : scene_keys()) {
      const size_t d = edit_distance(key, leaf_of(spec.key));
      if (d < best_d) {
        best_d = d;
        best = spec.key;
      }
    }
    if (best_d <= std::max<size_t>(2, key.size() / 3)) return best;
  }
  return std::nullopt;
}

std::string unknown_key_fix(const std::string& key) {
  if (auto best = suggest_key(key)) {
    return "did you mean " + *best + "? (params/reference.toml lists every key)";
  }
  const std::string table(table_of(key));
  if (key.find('.') != std::string::npos && is_table(table)) {
    return "the keys of [" + table + "] are: " + keys_of_table(table);
  }
  return "params/reference.toml lists every key; the tables are: " +
         join(schema_tables(), ", ");
}

std::string unknown_table_fix(const std::string& name) {
  const std::vector<std::string> tables = schema_tables();
  std::string fix;
  if (auto best = nearest(name, tables)) {
    fix = "did you mean [" + *best + "]? ";
  } else if (const KeySpec* spec = find_spec(suggest_key(name).value_or(""))) {
    fix = "did you mean " + spec->key + "? ";
  }
  return fix + "the tables are: " + join(tables, ", ");
}

}  // namespace panoptic::scene_detail
