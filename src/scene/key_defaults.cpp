#include "src/scene/key_defaults.hpp"

#include <optional>

#include "src/core/error.hpp"
#include "src/scene/scene_keys.hpp"
#include "src/scene/value_conversion.hpp"

namespace panoptic {
namespace scene_detail {

const std::map<std::string, ConfigValue, std::less<>>& default_values() {
  static const auto values = [] {
    std::map<std::string, ConfigValue, std::less<>> out;
    for (const KeySpec& spec : scene_keys()) {
      std::string problem;
      std::optional<ConfigValue> value;
      try {
        // Trusted text from the source code: parsed in-process, without the guard.
        const toml::table doc =
            toml::parse("v = " + spec.default_toml, std::string_view("schema"));
        if (const toml::node* node = doc.get("v")) value = convert(spec, *node, problem);
      } catch (const toml::parse_error& e) {
        problem = std::string(e.description());
      }
      if (!value) {
        throw Error("internal error in src/scene/scene_keys.cpp: the default of " +
                    spec.key + " (" + spec.default_toml + ") is invalid: " + problem);
      }
      out.emplace(spec.key, std::move(*value));
    }
    return out;
  }();
  return values;
}

}  // namespace scene_detail

double default_real(std::string_view key) {
  const auto it = scene_detail::default_values().find(key);
  if (it == scene_detail::default_values().end() ||
      !std::holds_alternative<double>(it->second))
    throw Error("internal error: " + std::string(key) +
                " is not a real key of the schema");
  return std::get<double>(it->second);
}

}  // namespace panoptic
