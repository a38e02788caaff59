#include "src/scene/key_use.hpp"

#include <algorithm>
#include <utility>

#include "src/scene/key_text.hpp"
#include "src/scene/schema_lookup.hpp"
#include "src/scene/toml_literal.hpp"

namespace panoptic::scene_detail {

namespace {

// The switch `c.key` as the scene has it, "disk.model = \"powerlaw\"", and whether that
// holds one of c.values.
std::pair<std::string, bool> switch_state(const Config& config, const UsedWhen& c) {
  const auto sw = config.values_.find(c.key);
  const std::string v = sw == config.values_.end() ? "" : toml_value(sw->second);
  return {c.key + " = " + v,
          std::find(c.values.begin(), c.values.end(), v) != c.values.end()};
}

}  // namespace

std::vector<UnmetCondition> unmet_conditions(const Config& config, const KeySpec& spec) {
  std::vector<UnmetCondition> out;
  std::vector<std::string> named;  // the switches an earlier unmet condition named
  for (const UsedWhen& c : spec.used_when) {
    auto [state, met] = switch_state(config, c);
    std::vector<std::string> states{state};
    for (const UsedWhen& alternative : c.or_else) {
      const auto [alt_now, alt_met] = switch_state(config, alternative);
      met = met || alt_met;
      // erosion.model = "none" fails both erosion({"halt", "balance"}) and
      // either(distribution(), {erosion({"balance"})}): said once
      if (std::find(named.begin(), named.end(), alt_now) == named.end())
        states.push_back(alt_now);
    }
    if (met) continue;
    named.insert(named.end(), states.begin(), states.end());
    out.push_back({join(states, ", "), condition_text(c)});
  }
  return out;
}

}  // namespace panoptic::scene_detail
