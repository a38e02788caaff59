#include "src/run/max_wall.hpp"

#include <charconv>
#include <cmath>
#include <string>

#include "src/core/error.hpp"

namespace panoptic {

double parse_duration(std::string_view text, std::string_view option) {
  const auto bad = [&] {
    return ConfigError(std::string(option) + " " + std::string(text) +
                       ": not a duration; write e.g. 90m, 2h, 3600s or 1h30m (units d, "
                       "h, m, s, each once and from the largest down; a plain number is "
                       "seconds), greater than 0");
  };
  double total = 0.0;
  std::size_t i = 0;
  bool any = false, bare = false;
  double previous_unit = 1e300;  // "90m30m" or "30m1h": a typo, not a sum to guess at
  while (i < text.size()) {
    double x = 0.0;
    const auto r = std::from_chars(text.data() + i, text.data() + text.size(), x);
    if (r.ec != std::errc() || !std::isfinite(x) || x < 0.0) throw bad();
    i = static_cast<std::size_t>(r.ptr - text.data());
    double unit = 1.0;
    if (i == text.size()) {
      if (any) throw bad();  // "1h30": is 30 minutes or seconds? say it
      bare = true;
    } else {
      switch (text[i]) {
        case 'd':
          unit = 86400.0;
          break;
        case 'h':
          unit = 3600.0;
          break;
        case 'm':
          unit = 60.0;
          break;
        case 's':
          unit = 1.0;
          break;
        default:
          throw bad();
      }
      ++i;
      if (!(unit < previous_unit)) throw bad();
      previous_unit = unit;
    }
    total += x * unit;
    any = true;
    if (bare) break;
  }
  if (!any || !(total > 0.0)) throw bad();
  return total;
}

}  // namespace panoptic
