// The 6-DoF pose of each rigid marker set (the calibration wand, a tool, a head band; a file of
// tracking::read_rigid_sets) in every frame, found among the frame's tracked markers by their
// distances (tracking::RigidSetFinder). Runs after the tracking stage: it needs the markers' ids,
// and uses only measured markers (not the tracker's predictions).
#pragma once

#include <string>
#include <vector>

#include "pipeline/frame_work.hpp"
#include "tracking/rigid_set.hpp"

namespace syncap::reconstruction {

struct RigidSetStageStats {
  long frames = 0;
  std::vector<long> found;  // per set: frames it was found in
};

class RigidSetStage : public pipeline::Stage {
 public:
  explicit RigidSetStage(std::vector<tracking::RigidSet> sets);
  const char* name() const override { return "rigid sets"; }
  void process(pipeline::FrameWork& work) override;
  const RigidSetStageStats& stats() const { return stats_; }
  // One line a set: "rigid set wand: found in 290 of 450 frames\n".
  std::string summary() const;
  const std::vector<tracking::RigidSet>& sets() const { return finder_.sets(); }

 private:
  tracking::RigidSetFinder finder_;
  std::vector<tracking::PointObservation> points_;  // reused frame to frame
  std::vector<tracking::TrackId> ids_;
  std::vector<std::size_t> marker_of_point_;  // index into work.markers
  RigidSetStageStats stats_;
};

}  // namespace syncap::reconstruction
