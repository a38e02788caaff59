#include "src/run/progress.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>

#include "src/core/units.hpp"

namespace panoptic {

Progress::Progress(double t_end)
    : t_end_(t_end), tty_(isatty(STDOUT_FILENO)), start_(WallClock::now()) {}

void Progress::update(double t, long nst) {
  if (!tty_) return;
  const double wall = seconds_since(start_);
  if (wall - last_ < 0.2) return;
  last_ = wall;
  // progress in log time: snapshots and the work are spread roughly evenly in log t
  const double t_ref = 1e2 * units::kYr;
  const double frac = std::log1p(t / t_ref) / std::log1p(t_end_ / t_ref);
  const double eta = frac > 1e-3 ? wall * (1.0 - frac) / frac : NAN;
  std::printf("\r  t = %.3e yr  (%5.1f%%)  steps %ld  wall %.1f s  ETA %.0f s   ",
              t / units::kYr, 100.0 * frac, nst, wall, eta);
  std::fflush(stdout);
}

void Progress::done() {
  if (tty_ && last_ > 0.0) std::printf("\n");
}

}  // namespace panoptic
