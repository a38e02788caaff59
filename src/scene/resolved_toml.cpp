// Config::resolved_toml: the scene a run used, every key with its value, stored in every
// output (the config_toml attribute) and in every checkpoint.
#include <vector>

#include "src/scene/config.hpp"
#include "src/scene/key_use.hpp"
#include "src/scene/schema_lookup.hpp"
#include "src/scene/toml_literal.hpp"
#include "src/scene/toml_tables.hpp"

namespace panoptic {
using namespace scene_detail;
namespace {

// The first line of a resolved scene, around the scene file's name.
constexpr std::string_view kHead = "# The resolved scene ";
constexpr std::string_view kTail = ": every key, defaults included.\n";

}  // namespace

std::string resolved_scene_file(std::string_view resolved) {
  if (!resolved.starts_with(kHead)) return "";
  const std::size_t end = resolved.find(kTail);
  const std::size_t line_end = resolved.find('\n');
  if (end == std::string_view::npos || end + kTail.size() != line_end + 1)  // line 1
    return "";
  return std::string(resolved.substr(kHead.size(), end - kHead.size()));
}

std::string Config::resolved_toml() const {
  std::vector<KeyLine> lines;
  for (const KeySpec& spec : scene_keys()) {
    const auto it = values_.find(spec.key);
    if (it == values_.end()) continue;
    std::string comment;
    if (!spec.unit.empty()) comment += " [" + spec.unit + "]";
    const auto origin = origins_.find(spec.key);
    if (!user_set(spec.key)) {
      comment += " (default)";
    } else if (origin != origins_.end() && origin->second.file.empty()) {
      comment += " (--set)";
    } else if (origin != origins_.end() && origin->second.file != file_.string()) {
      comment += " (from " + comment_safe(origin->second.file) + ")";
    }
    if (const auto unmet = unmet_conditions(*this, spec); !unmet.empty()) {
      std::vector<std::string> now;
      for (const UnmetCondition& c : unmet) now.push_back(c.now);
      comment += ' ';
      comment += kNotReadMark;
      comment += comment_safe(join(now, ", "));
      comment += ')';
    }
    lines.push_back(
        KeyLine{spec.key, std::string(leaf_of(spec.key)) + " = " + toml_value(it->second),
                comment});
  }
  constexpr size_t kMaxAlign = 40;  // long values do not push every comment right
  return std::string(kHead) + comment_safe(file_.string()) + std::string(kTail) +
         "# \"(default)\" marks a key the scene did not set, \"(from FILE)\" one a base "
         "scene set,\n"
         "# \"(--set)\" an override, \"(not read: ...)\" one this run does not read "
         "(no warning).\n" +
         tables_text(lines, kMaxAlign, "  #");
}

}  // namespace panoptic
