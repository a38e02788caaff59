#include "src/scene/toml_tables.hpp"

#include <algorithm>

#include "src/scene/schema_lookup.hpp"

namespace panoptic::scene_detail {

std::string tables_text(const std::vector<KeyLine>& lines, std::size_t max_align,
                        std::string_view mark) {
  std::string out;
  for (std::size_t begin = 0, end = 0; begin < lines.size(); begin = end) {
    const std::string_view table = table_of(lines[begin].key);
    std::size_t width = 0;
    for (end = begin; end < lines.size() && table_of(lines[end].key) == table; ++end) {
      const std::size_t n = lines[end].text.size();
      if (n <= max_align) width = std::max(width, n);
    }
    out += "\n[" + std::string(table) + "]\n";
    for (std::size_t i = begin; i < end; ++i) {
      const KeyLine& line = lines[i];
      out += line.text;
      if (!line.comment.empty()) {
        const std::size_t n = line.text.size();
        out += std::string(n < width ? width - n : 0, ' ') + std::string(mark) +
               line.comment;
      }
      out += "\n";
    }
  }
  return out;
}

}  // namespace panoptic::scene_detail
