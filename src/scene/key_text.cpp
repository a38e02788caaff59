#include "src/scene/key_text.hpp"

#include <cmath>

#include "src/scene/schema_lookup.hpp"
#include "src/scene/toml_literal.hpp"

namespace panoptic::scene_detail {
namespace {

std::string bound_text(const KeySpec& spec, double x) {
  if (spec.type == KeyType::kInt && std::abs(x) < 1e18) {
    return std::to_string(static_cast<long long>(x));
  }
  return shortest(x);
}

// "a real number > 0 (unit: au)", "one of: powerlaw, lbp".
std::string wanted_text(const KeySpec& spec) {
  if (!spec.choices.empty()) return "one of: " + join(spec.choices, ", ");
  std::string out = type_text(spec.type);
  const std::string range = range_text(spec);
  if (!range.empty()) out += (spec.type == KeyType::kRealList ? ", each " : " ") + range;
  if (!spec.unit.empty()) out += " (unit: " + spec.unit + ")";
  return out;
}

std::string example_value(const KeySpec& spec) {
  if (spec.type == KeyType::kRealList && spec.default_toml == "[]")
    return spec.unit == "au" ? "[3.0, 30.0]" : "[1e3, 1e4]";
  return spec.default_toml;
}

}  // namespace

std::string range_text(const KeySpec& spec) {
  std::string out;
  if (spec.min) out += (spec.min_exclusive ? "> " : ">= ") + bound_text(spec, *spec.min);
  if (spec.max) {
    if (!out.empty()) out += " and ";
    out += (spec.max_exclusive ? "< " : "<= ") + bound_text(spec, *spec.max);
  }
  return out;
}

std::string unit_suffix(const KeySpec& spec) {
  return spec.unit.empty() ? "" : " [" + spec.unit + "]";
}

std::string type_text(KeyType type) {
  switch (type) {
    case KeyType::kReal:
      return "a real number";
    case KeyType::kInt:
      return "an integer";
    case KeyType::kBool:
      return "true or false";
    case KeyType::kString:
      return "a string";
    case KeyType::kRealList:
      return "a list of real numbers";
  }
  return "a value";
}

std::string fix_text(const KeySpec& spec) {
  return "set " + spec.key + " to " + wanted_text(spec) + ", e.g. " + spec.key + " = " +
         example_value(spec);
}

std::string condition_text(const UsedWhen& c) {
  std::string out = c.key + " = ";
  for (size_t i = 0; i < c.values.size(); ++i) out += (i ? " or " : "") + c.values[i];
  if (c.or_else.empty()) return out;
  // in parentheses: the texts are joined with " and " (a warning's fix, the reference)
  for (const UsedWhen& alternative : c.or_else)
    out += " or " + condition_text(alternative);
  return "(" + out + ")";
}

}  // namespace panoptic::scene_detail
