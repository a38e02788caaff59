#pragma once
//! Wall time of the process, from a monotonic clock (a change of the system time does
//! not move it): for --max-wall, the checkpoint schedule, progress and run records.
#include <chrono>

namespace panoptic {

using WallClock = std::chrono::steady_clock;

//! Seconds elapsed since `t0`.
inline double seconds_since(WallClock::time_point t0) {
  return std::chrono::duration<double>(WallClock::now() - t0).count();
}

}  // namespace panoptic
