#include "src/run/variant.hpp"

#include <cstdint>
#include <cstdio>

#include "src/core/digest.hpp"
#include "src/scene/config.hpp"

namespace panoptic {
namespace {

bool safe(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
         c == '.' || c == '_' || c == '-' || c == ',' || c == '=';
}

// "key=value" of a --set item as the label writes it; "" when it cannot be written so.
std::string label_item(const std::string& item) {
  const std::size_t eq = item.find('=');
  if (eq == std::string::npos) return "";
  const std::string key = trim_blanks(item.substr(0, eq));
  std::string value = trim_blanks(item.substr(eq + 1));
  if (value.size() >= 2 && value.front() == '"' && value.back() == '"')
    value = value.substr(1, value.size() - 2);  // --set m=lbp reads as --set m="lbp"
  const std::string out = key + "=" + value;
  for (const char c : out)
    if (!safe(c)) return "";
  return key.empty() || value.empty() ? "" : out;
}

}  // namespace

std::string variant_label(const std::string& scene_stem, const std::string& preset,
                          std::span<const std::string> sets) {
  std::string label = scene_stem;
  if (!preset.empty()) label += "+" + preset;
  if (sets.empty()) return label;
  std::string items;
  bool readable = true;
  for (const std::string& s : sets) {
    const std::string item = label_item(s);
    readable = readable && !item.empty();
    items += "+" + item;
  }
  if (readable && label.size() + items.size() <= kMaxLabelChars) return label + items;
  std::string joined;
  for (const std::string& s : sets) joined += s + '\n';
  const std::uint64_t h = fnv1a64(std::as_bytes(std::span(joined.data(), joined.size())));
  char hex[9];
  std::snprintf(hex, sizeof hex, "%08x", static_cast<unsigned>(h >> 32));
  return label + "+set-" + hex;
}

std::vector<OutputAttribute> variant_attributes(const Variant& variant) {
  return {{"", "label", "",
           "the scene's name with the overrides of the run (src/run/README.md, Variants)",
           variant.label},
          {"", "overrides", "",
           "the overrides applied on top of the scene file, in order (a preset's items, "
           "then --set items), as a JSON list of \"table.key=value\" strings",
           overrides_json(variant.overrides)}};
}

std::string overrides_json(std::span<const std::string> items) {
  std::string out = "[";
  for (std::size_t k = 0; k < items.size(); ++k) {
    out += k ? ", \"" : "\"";
    for (const char ch : items[k]) {
      const auto c = static_cast<unsigned char>(ch);
      if (ch == '"' || ch == '\\') {
        out += '\\';
        out += ch;
      } else if (c < 0x20 || c == 0x7F) {
        char esc[8];
        std::snprintf(esc, sizeof esc, "\\u%04x", c);
        out += esc;
      } else {
        out += ch;  // UTF-8 as it is: the loader has checked it
      }
    }
    out += '"';
  }
  return out + "]";
}

}  // namespace panoptic
