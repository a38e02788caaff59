#include "src/run/progress.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>

#include "src/core/units.hpp"

namespace panoptic {

Progress::Progress(double t_start, double t_end, double interval_s)
    : t_start_(t_start),
      t_end_(t_end),
      interval_s_(interval_s),
      tty_(isatty(STDOUT_FILENO)),
      start_(WallClock::now()) {}

double Progress::fraction(double t) const {
  const double t_ref = 1e2 * units::kYr;
  const double a = std::log1p(t_start_ / t_ref), b = std::log1p(t_end_ / t_ref);
  return b > a ? (std::log1p(t / t_ref) - a) / (b - a) : 1.0;
}

void Progress::update(double t, long nst) {
  if (!tty_ && !(interval_s_ > 0.0)) return;
  const double wall = seconds_since(start_);
  if (wall - last_ < (tty_ ? 0.2 : interval_s_)) return;
  last_ = wall;
  const double frac = fraction(t);
  const double eta = frac > 1e-3 ? wall * (1.0 - frac) / frac : NAN;
  if (tty_) {
    std::printf("\r  t = %.3e yr  (%5.1f%%)  steps %ld  wall %.1f s  ETA %.0f s   ",
                t / units::kYr, 100.0 * frac, nst, wall, eta);
  } else {
    char eta_text[32] = "unknown";
    if (std::isfinite(eta)) std::snprintf(eta_text, sizeof eta_text, "%.3g s", eta);
    std::printf("progress: t = %.4g yr (%.1f %%), %ld steps, wall %.3g s, ETA %s\n",
                t / units::kYr, 100.0 * frac, nst, wall, eta_text);
  }
  std::fflush(stdout);
}

void Progress::done() {
  if (tty_ && last_ > 0.0) std::printf("\n");
}

}  // namespace panoptic
