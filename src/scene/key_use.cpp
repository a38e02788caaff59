#include "src/scene/key_use.hpp"

#include <algorithm>

#include "src/scene/key_text.hpp"
#include "src/scene/toml_literal.hpp"

namespace panoptic::scene_detail {

std::vector<UnmetCondition> unmet_conditions(const Config& config, const KeySpec& spec) {
  std::vector<UnmetCondition> out;
  for (const UsedWhen& c : spec.used_when) {
    const auto sw = config.values_.find(c.key);
    const std::string v = sw == config.values_.end() ? "" : toml_value(sw->second);
    if (std::find(c.values.begin(), c.values.end(), v) == c.values.end())
      out.push_back({c.key + " = " + v, condition_text(c)});
  }
  return out;
}

}  // namespace panoptic::scene_detail
