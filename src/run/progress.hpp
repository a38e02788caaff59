#pragma once
//! The progress of a run: a status line on a terminal, and with an interval (--progress,
//! PANOPTIC_PROGRESS) one line per interval in a log.
#include "src/core/wall_clock.hpp"

namespace panoptic {

//! On a terminal one status line, overwritten in place; when stdout is a file or a pipe
//! (a batch job's log), one line every `interval_s` of wall time (nothing when 0):
//! "progress: t = 2.5e+04 yr (61.2 %), 3120 steps, wall 12.3 s, ETA 7.8 s".
class Progress {
 public:
  //! A run from t_start to t_end [s] (a restart starts at its checkpoint's time).
  Progress(double t_start, double t_end, double interval_s);
  //! At a CVODE step: time t [s] and steps nst; redrawn at most every 0.2 s on a
  //! terminal, a line every interval_s in a log.
  void update(double t, long nst);
  //! Ends the line (before the next message).
  void done();

 private:
  //! The share of the run done at t: in log time, over which the snapshots and the work
  //! are spread roughly evenly.
  double fraction(double t) const;

  double t_start_;
  double t_end_;
  double interval_s_;
  bool tty_;
  WallClock::time_point start_;
  double last_ = 0.0;
};

}  // namespace panoptic
