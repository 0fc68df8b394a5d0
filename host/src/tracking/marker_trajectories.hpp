// Tracked 3D marker trajectories (docs/design/reconstruction.md): what the tracking stage's history
// makes of its tracks, and what the exports (io/c3d_writer.hpp, io/trc_writer.hpp) write for
// Vicon/Qualisys tools and OpenSim.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace syncap::tracking {

// One marker in one frame.
struct MarkerSample {
  // In the calibration's object frame.
  Eigen::Vector3d position_mm;
  // RMS distance of its rays to the point (C3D's residual); 0: not measured (interpolated).
  double residual_mm = 0;
  // Bit i set: camera i saw it (C3D's camera mask; cameras 0..6 fit C3D's 7 bits).
  uint32_t cameras = 0;
};

struct MarkerTrajectories {
  // One per marker (persistent id), e.g. "M001", or a rigid set's name.
  std::vector<std::string> labels;
  double rate_hz = 0;       // frame rate
  int64_t first_frame = 0;  // frame number of samples[0]
  // samples[f][m]: marker m in frame first_frame + f; nullopt when not seen (gap).
  std::vector<std::vector<std::optional<MarkerSample>>> samples;
};

}  // namespace syncap::tracking
