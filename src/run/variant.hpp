#pragma once
//! A variant of a scene: the overrides a run applies on top of its scene file (an
//! accuracy preset, then --set items), as a label (the default output name, the header,
//! the `label` root attribute that plot titles show) and as the `overrides` root
//! attribute. The rule of the label: src/run/README.md, Variants.
#include <span>
#include <string>
#include <vector>

#include "src/io/output_entry.hpp"

namespace panoptic {

//! `scene_stem`, then "+<preset>" and "+<key>=<value>" for each --set item (blanks
//! around key and value dropped, and the quotes of a plain string value), e.g.
//! "fiducial+disk.sigma_1au=5100". When an item holds a character other than letters,
//! digits and . _ - , = (a list, a path, a string with blanks), or the label would pass
//! kMaxLabelChars, the items are replaced by "+set-" and 8 hex digits of their FNV-1a
//! digest ("fiducial+set-1b2c3d4e"): a file name on every file system, and one per set.
std::string variant_label(const std::string& scene_stem, const std::string& preset,
                          std::span<const std::string> sets);

//! The longest label written out in full.
inline constexpr std::size_t kMaxLabelChars = 100;

//! What a new output records of its variant.
struct Variant {
  std::string label;                   //!< variant_label(): the `label` root attribute
  std::vector<std::string> overrides;  //!< preset then --set items: `overrides`
};

//! The root attributes `label` and `overrides` of a new output (RunOutput::
//! write_attribute; listed by `panoptic reference --outputs`).
std::vector<OutputAttribute> variant_attributes(const Variant& variant);

//! `items` as a JSON array of strings ("[]" when none): the `overrides` root attribute.
std::string overrides_json(std::span<const std::string> items);

}  // namespace panoptic
