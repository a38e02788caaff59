#pragma once
//! The text of a TOML node as the user wrote it, for messages. Internal to the scene
//! layer.
#include <toml++/toml.h>

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace panoptic::scene_detail {

//! The text of a node as the user wrote it, sliced from the input by its source region
//! (columns count code points, like toml++), whitespace runs collapsed, long text cut.
class SourceText {
 public:
  explicit SourceText(std::string_view text);

  //! The text of `region`, tidied; "" when the region is not in the text.
  std::string slice(const toml::source_region& region) const;
  //! The text from `p` to the end of its line ("" when `p` is not in the text).
  std::string_view rest_of_line(const toml::source_position& p) const;
  //! `s` with whitespace runs collapsed to one space and cut after 60 code points.
  static std::string tidy(std::string_view s);

 private:
  std::optional<size_t> offset(const toml::source_position& p) const;

  std::string_view text_;
  std::vector<size_t> line_starts_;
};

}  // namespace panoptic::scene_detail
