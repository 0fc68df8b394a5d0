// Keeps every fitted frame's pose and the trigger's rate, for the motion exports after a run
// (syncap fit: BVH, C3D, TRC).
#pragma once

#include <cstdint>
#include <map>
#include <optional>

#include "fitting/surface_fit.hpp"
#include "pipeline/frame_work.hpp"

namespace syncap::outputs {

// The poses of a run, by frame number: nullopt for a frame the stage saw with no fitted pose
// (a lost track's frame keeps its restart's pose).
struct PoseRecord {
  double rate_hz = 0;  // the trigger's, the latest known; 0: none seen
  std::map<int64_t, std::optional<fitting::PoseVector>> poses;
};

// The stage after the body fit: fills a PoseRecord the caller owns.
class PoseRecordStage : public pipeline::Stage {
 public:
  explicit PoseRecordStage(PoseRecord& record) : record_(record) {}
  const char* name() const override { return "pose record"; }
  void process(pipeline::FrameWork& work) override;

 private:
  PoseRecord& record_;
};

}  // namespace syncap::outputs
