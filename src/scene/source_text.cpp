#include "src/scene/source_text.hpp"

namespace panoptic::scene_detail {

SourceText::SourceText(std::string_view text) : text_(text) {
  line_starts_.push_back(0);
  for (size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '\n') line_starts_.push_back(i + 1);
  }
}

std::string SourceText::slice(const toml::source_region& region) const {
  const auto begin = offset(region.begin);
  const auto end = offset(region.end);
  if (!begin || !end || *end <= *begin) return "";
  return tidy(text_.substr(*begin, *end - *begin));
}

std::string_view SourceText::rest_of_line(const toml::source_position& p) const {
  const auto begin = offset(p);
  if (!begin || *begin > text_.size()) return {};
  const size_t end = text_.find('\n', *begin);
  return text_.substr(*begin, end == std::string_view::npos ? end : end - *begin);
}

std::string SourceText::tidy(std::string_view s) {
  constexpr size_t kMaxCodePoints = 60;
  std::string out;
  size_t code_points = 0;
  bool space = false;
  for (size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    if (c == ' ' || c == '\t' || c == '\n' || c == '\r') {
      space = !out.empty();
      continue;
    }
    if ((static_cast<unsigned char>(c) & 0xC0) != 0x80) {
      if (code_points + (space ? 1 : 0) >= kMaxCodePoints) return out + " ...";
      ++code_points;
    }
    if (space) out += ' ', ++code_points;
    space = false;
    out += c;
  }
  return out;
}

std::optional<size_t> SourceText::offset(const toml::source_position& p) const {
  if (p.line < 1 || p.line > line_starts_.size() || p.column < 1) return std::nullopt;
  size_t i = line_starts_[p.line - 1];
  for (size_t col = 1; col < p.column; ++col) {
    if (i >= text_.size()) return std::nullopt;
    ++i;
    while (i < text_.size() && (static_cast<unsigned char>(text_[i]) & 0xC0) == 0x80) ++i;
  }
  return i;
}

}  // namespace panoptic::scene_detail
