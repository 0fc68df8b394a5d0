#include "outputs/body_message_stage.hpp"

#include <cstddef>
#include <iterator>

#include "outputs/message_time.hpp"

namespace syncap::outputs {

body_frame_t body_message(const pipeline::FrameWork& work, int32_t host_us) {
  const pipeline::BodyFitSummary& b = *work.body;
  body_frame_t m{};
  stamp_frame(m, work, host_us);
  m.fit_us = clamped_int32(b.fit_us);
  m.flags = static_cast<int8_t>(b.flags);
  m.rms_mm = static_cast<float>(b.rms_mm);
  m.points = b.points;
  m.points_kept = b.points_kept;
  for (std::size_t i = 0; i < b.parameters.size() && i < std::size(m.parameters); ++i)
    m.parameters[i] = static_cast<float>(b.parameters[i]);
  for (std::size_t j = 0; j < b.joints_mm.size() && j < std::size(m.joint_mm); ++j)
    for (int k = 0; k < 3; ++k) m.joint_mm[j][k] = static_cast<float>(b.joints_mm[j][k]);
  m.sigma0 = static_cast<float>(b.sigma0);
  for (std::size_t i = 0; i < b.parameter_sigmas.size() && i < std::size(m.parameter_sigmas); ++i)
    m.parameter_sigmas[i] = static_cast<float>(b.parameter_sigmas[i]);
  for (std::size_t j = 0; j < b.joint_sigmas_mm.size() && j < std::size(m.joint_sigma_mm); ++j)
    m.joint_sigma_mm[j] = static_cast<float>(b.joint_sigmas_mm[j]);
  return m;
}

void BodyMessageStage::process(pipeline::FrameWork& work) {
  if (!work.body) return;
  publish_(body_message(work, host_us_so_far(work)));
}

}  // namespace syncap::outputs
