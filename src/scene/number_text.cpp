#include "src/scene/number_text.hpp"

#include <cerrno>
#include <cstdlib>

namespace panoptic {

NumberText read_number_text(const std::string& text) {
  NumberText out;
  if (text.empty()) return out;
  const char* const end_of_text = text.c_str() + text.size();
  char* end = nullptr;
  errno = 0;
  (void)std::strtod(text.c_str(), &end);
  out.real = end == end_of_text;
  out.beyond_double = out.real && errno == ERANGE;
  errno = 0;
  (void)std::strtoll(text.c_str(), &end, 10);
  out.integer = end == end_of_text;
  out.beyond_int64 = out.integer && errno == ERANGE;
  return out;
}

}  // namespace panoptic
