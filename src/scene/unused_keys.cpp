// Warnings about the keys a scene sets: none at all (an empty file), or some that a run
// of this scene does not read (KeySpec::used_when).
#include "src/scene/config.hpp"
#include "src/scene/key_defaults.hpp"
#include "src/scene/key_use.hpp"
#include "src/scene/schema_lookup.hpp"
#include "src/scene/toml_literal.hpp"

namespace panoptic {
using namespace scene_detail;
namespace {

// A key that other keys' use depends on (disk.model, growth.enabled, ...).
bool is_switch(std::string_view key) {
  for (const KeySpec& spec : scene_keys()) {
    for (const UsedWhen& c : spec.used_when) {
      if (c.key == key) return true;
      for (const UsedWhen& alternative : c.or_else)
        if (alternative.key == key) return true;
    }
  }
  return false;
}

}  // namespace

std::string empty_scene_warning(const Config& config) {
  // a scene file that sets no key (empty, only comments, or the wrong file): the run
  // would be every default, 1 Myr on 250 cells, without a word
  for (const KeySpec& spec : scene_keys())
    if (config.user_set(spec.key) && config.where(spec.key) != "--set") return "";
  return "panoptic: warning: " + config.file().string() +
         " sets no key: every key not given with --set takes its default "
         "(params/reference.toml); check the file";
}

std::vector<std::string> unused_key_warnings(const Config& config) {
  std::vector<std::string> out;
  for (const KeySpec& spec : scene_keys()) {
    if (spec.used_when.empty() || !config.user_set(spec.key)) continue;
    const auto it = config.values_.find(spec.key);
    if (it == config.values_.end()) continue;
    // a resolved scene's line that says so itself (kNotReadMark)
    if (const auto o = config.origins_.find(spec.key);
        o != config.origins_.end() && o->second.marked_not_read)
      continue;
    const std::string value = toml_value(it->second);
    std::vector<std::string> now, wanted;  // the conditions that fail
    for (const UnmetCondition& c : unmet_conditions(config, spec)) {
      now.push_back(c.now);
      wanted.push_back(c.wanted);
    }
    if (now.empty()) continue;
    // fragmentation.enabled = false with growth off: an explicit "off" turns nothing on
    if (is_switch(spec.key) && value == toml_value(default_values().at(spec.key)))
      continue;
    out.push_back("panoptic: warning: " + spec.key + " = " + value + " (" +
                  config.where(spec.key) + ") is not used: " + join(now, ", ") +
                  "; set " + join(wanted, " and ") + " to use it, or remove the key");
  }
  return out;
}

}  // namespace panoptic
