#include "src/scene/value_conversion.hpp"

#include <algorithm>
#include <cmath>

#include "src/scene/key_suggestions.hpp"
#include "src/scene/key_text.hpp"
#include "src/scene/number_text.hpp"
#include "src/scene/schema_lookup.hpp"
#include "src/scene/toml_literal.hpp"

namespace panoptic::scene_detail {
namespace {

std::string node_type_text(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::table:
      return "a table";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a real number";
    case toml::node_type::boolean:
      return "a boolean";
    case toml::node_type::date:
      return "a date";
    case toml::node_type::time:
      return "a time";
    case toml::node_type::date_time:
      return "a date-time";
    case toml::node_type::none:
      break;
  }
  return "nothing";
}

// The reason `x` violates the bounds of `spec` ("must be > 0 [au]"), or "" when it does
// not.
std::string range_problem(const KeySpec& spec, double x) {
  const bool below =
      spec.min && (spec.min_exclusive ? !(x > *spec.min) : !(x >= *spec.min));
  const bool above =
      spec.max && (spec.max_exclusive ? !(x < *spec.max) : !(x <= *spec.max));
  if (!below && !above) return "";
  return "must be " + range_text(spec) + unit_suffix(spec);
}

}  // namespace

std::optional<ConfigValue> convert(const KeySpec& spec, const toml::node& node,
                                   std::string& problem) {
  const auto type_problem = [&](std::string extra = "") {
    std::string what = node_type_text(node);
    // a --set value that reads as a number only beyond the range of a double or of a
    // 64-bit integer (1e999, 99999999999999999999) arrives as a string
    if (const auto* str = node.as_string()) {
      const std::string& t = str->get();
      const NumberText n = read_number_text(t);
      if (n.beyond_double)
        what = "a number beyond the range of a double";
      else if (n.real && spec.type == KeyType::kInt && n.beyond_int64)
        what = "a number beyond the range of a 64-bit integer";
      else if ((spec.type == KeyType::kInt && n.integer) ||
               (spec.type == KeyType::kReal && n.real))
        what = "a string (\"" + t + "\": write the number without quotes)";
    }
    problem = "must be " + type_text(spec.type) + unit_suffix(spec) + ", not " + what +
              "; " + (extra.empty() ? fix_text(spec) : extra);
    return std::nullopt;
  };
  const auto number = [](const toml::node& n) -> std::optional<double> {
    if (const auto* i = n.as_integer()) return static_cast<double>(i->get());
    if (const auto* f = n.as_floating_point()) return f->get();
    return std::nullopt;
  };
  const auto finite_problem = [&](double x) {
    problem = std::string("must be a finite number, not ") +
              (std::isnan(x) ? "nan"
               : x < 0       ? "-inf"
                             : "inf") +
              "; " + fix_text(spec);
  };

  switch (spec.type) {
    case KeyType::kReal: {
      const auto x = number(node);
      if (!x) return type_problem();
      if (!std::isfinite(*x)) {
        finite_problem(*x);
        return std::nullopt;
      }
      if (std::string p = range_problem(spec, *x); !p.empty()) {
        problem = p + "; " + fix_text(spec);
        return std::nullopt;
      }
      return ConfigValue(*x);
    }
    case KeyType::kInt: {
      const auto* i = node.as_integer();
      if (!i) {
        if (const auto* f = node.as_floating_point(); f && std::isfinite(f->get()) &&
                                                      std::trunc(f->get()) == f->get() &&
                                                      std::abs(f->get()) < 1e18) {
          return type_problem(
              "write it without a decimal point or exponent: " + spec.key + " = " +
              std::to_string(static_cast<long long>(f->get())));
        }
        return type_problem();
      }
      const auto x = static_cast<long>(i->get());
      if (std::string p = range_problem(spec, static_cast<double>(x)); !p.empty()) {
        problem = p + "; " + fix_text(spec);
        return std::nullopt;
      }
      return ConfigValue(x);
    }
    case KeyType::kBool: {
      const auto* b = node.as_boolean();
      if (!b) {
        if (const auto* s = node.as_string();
            s && (s->get() == "true" || s->get() == "false")) {
          return type_problem("write " + s->get() + " without quotes");
        }
        return type_problem();
      }
      return ConfigValue(b->get());
    }
    case KeyType::kString: {
      const auto* s = node.as_string();
      if (!s) return type_problem();
      if (!spec.choices.empty() && std::find(spec.choices.begin(), spec.choices.end(),
                                             s->get()) == spec.choices.end()) {
        problem = "unknown choice; choose one of: " + join(spec.choices, ", ");
        if (auto best = nearest(s->get(), spec.choices))
          problem += " (did you mean " + *best + "?)";
        return std::nullopt;
      }
      return ConfigValue(s->get());
    }
    case KeyType::kRealList: {
      const auto* array = node.as_array();
      if (!array) {
        if (const auto x = number(node)) {
          return type_problem("write a list, even of one value: " + spec.key + " = [" +
                              toml_real(*x) + "]");
        }
        return type_problem();
      }
      std::vector<double> xs;
      for (size_t k = 0; k < array->size(); ++k) {
        const toml::node& element = *array->get(k);
        const auto x = number(element);
        const std::string which = "element " + std::to_string(k + 1);
        if (!x) {
          problem = which + " is " + node_type_text(element) +
                    ": every element must be a number" + unit_suffix(spec) + "; " +
                    fix_text(spec);
          return std::nullopt;
        }
        if (!std::isfinite(*x)) {
          problem = which + " must be a finite number; " + fix_text(spec);
          return std::nullopt;
        }
        if (std::string p = range_problem(spec, *x); !p.empty()) {
          problem = which + " (" + shortest(*x) + ") " + p + "; " + fix_text(spec);
          return std::nullopt;
        }
        xs.push_back(*x);
      }
      return ConfigValue(std::move(xs));
    }
  }
  return type_problem();
}

}  // namespace panoptic::scene_detail
