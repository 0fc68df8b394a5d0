#include "outputs/pose_record_stage.hpp"

#include <algorithm>

namespace syncap::outputs {

void PoseRecordStage::process(pipeline::FrameWork& work) {
  if (work.group.trigger && work.group.trigger->rate_hz > 0)
    record_.rate_hz = work.group.trigger->rate_hz;
  if (!work.body) return;
  std::optional<fitting::PoseVector>& pose = record_.poses[work.group.frame_number];
  const pipeline::BodyFitSummary& b = *work.body;
  if (b.parameters.size() == fitting::kPoseParameterCount) {
    pose.emplace();
    std::copy(b.parameters.begin(), b.parameters.end(), pose->begin());
  }
}

}  // namespace syncap::outputs
