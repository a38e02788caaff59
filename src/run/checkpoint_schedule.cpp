#include "src/run/checkpoint_schedule.hpp"

namespace panoptic {

bool CheckpointSchedule::due(long snapshot_index, double wall_now) const {
  if (every_snapshots_ > 0 && snapshot_index > 0 &&
      snapshot_index % every_snapshots_ == 0)
    return true;
  return every_wall_s_ > 0.0 && wall_now - last_wall_ >= every_wall_s_;
}

}  // namespace panoptic
