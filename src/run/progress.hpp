#pragma once
//! The status line of a run on a terminal.
#include "src/core/wall_clock.hpp"

namespace panoptic {

//! One status line on a terminal, overwritten in place; nothing when stdout is a file.
class Progress {
 public:
  explicit Progress(double t_end);
  //! At a CVODE step: time t [s] and steps nst; redrawn at most every 0.2 s.
  void update(double t, long nst);
  //! Ends the line (before the next message).
  void done();

 private:
  double t_end_;
  bool tty_;
  WallClock::time_point start_;
  double last_ = 0.0;
};

}  // namespace panoptic
