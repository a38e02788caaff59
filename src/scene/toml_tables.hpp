#pragma once
//! A scene written as TOML tables, one line a key with an aligned comment: the layout
//! of the resolved scene and of params/reference.toml. Internal to the scene layer.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace panoptic::scene_detail {

//! One key's line.
struct KeyLine {
  std::string key;      //!< "grid.r_in_au": its table is the header it goes under
  std::string text;     //!< "r_in_au = 1.0"
  std::string comment;  //!< written after `mark` ("" = no comment)
};

//! `lines` (in schema order) under "\n[table]\n" headers. The comments of a table start
//! in one column, `mark` ("  #") past the longest text of at most `max_align`
//! characters, so that a long value does not push every comment right.
std::string tables_text(const std::vector<KeyLine>& lines, std::size_t max_align,
                        std::string_view mark);

}  // namespace panoptic::scene_detail
