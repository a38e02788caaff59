#pragma once
//! The scene schema: every key a scene may hold (its type, default, unit, meaning,
//! bounds, choices and the switches that make a run read it). The tables are in
//! keys_*.cpp, listed by scene_keys() in scene_keys.cpp.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace panoptic {

enum class KeyType { kReal, kInt, kBool, kString, kRealList };

//! A condition under which a run reads a key: the switch `key` holds one of `values`, or
//! one of the alternatives `or_else` holds.
struct UsedWhen {
  std::string key;  //!< the switch, "disk.model"
  //! its values that use the key, as canonical TOML literals: "\"lbp\"", "true", "[]"
  std::vector<std::string> values;
  //! other switches that meet the condition instead (empty: none): erosion.eps_eros is
  //! read in the distribution mode with any erosion model, in the single-size model
  //! with erosion.model = "balance" only
  std::vector<UsedWhen> or_else;
};

//! One documented scene key. The schema is the single source of truth for what a scene
//! may contain, for the defaults, for `panoptic check` and for params/reference.toml.
struct KeySpec {
  std::string key;  //!< dotted name, "grid.r_in_au"
  KeyType type = KeyType::kReal;
  std::string default_toml;  //!< the default as a TOML literal: "1.0", "\"mmsn\"", "[]"
  std::string unit;  //!< unit of the value as the user writes it ("au", "" = none)
  std::string doc;   //!< one line: what the key means
  std::optional<double> min;   //!< numbers (and every element of a list) must be >= min
  std::optional<double> max;   //!< ... and <= max
  bool min_exclusive = false;  //!< make min a strict bound (> min)
  bool max_exclusive = false;  //!< make max a strict bound (< max)
  std::vector<std::string> choices;  //!< allowed values of a string key (empty = any)
  //! `panoptic run` reads the key only when every condition holds (empty: always); a key
  //! the user set that is not read gets a warning (unused_key_warnings)
  std::vector<UsedWhen> used_when;
};

//! Every key a scene may hold, grouped by table, in the order they are documented.
const std::vector<KeySpec>& scene_keys();

//! The schema default of a real-valued key (`KeySpec::default_toml` as parsed for the
//! scene; throws for a key that is not in the schema or not real).
double default_real(std::string_view key);

}  // namespace panoptic
