#pragma once
//! When a run writes its checkpoint (step 4 of run.cpp): the checkpoint.* keys.

namespace panoptic {

//! When to checkpoint: at a snapshot, if checkpoint.every_snapshots divides its index,
//! or if checkpoint.every_wall_s has passed since the last checkpoint (or the start).
class CheckpointSchedule {
 public:
  CheckpointSchedule(double every_wall_s, long every_snapshots, double wall_now)
      : every_wall_s_(every_wall_s),
        every_snapshots_(every_snapshots),
        last_wall_(wall_now) {}
  bool due(long snapshot_index, double wall_now) const;
  void taken(double wall_now) { last_wall_ = wall_now; }

 private:
  double every_wall_s_;
  long every_snapshots_;
  double last_wall_;
};

}  // namespace panoptic
