// Tracked 3D marker trajectories, the input of the exports (docs/design/reconstruction.md). The
// tracking stage fills them; write_c3d and write_trc turn them into files for Vicon/Qualisys tools
// and OpenSim.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace syncap::io {

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

// Longest label the exports accept: keeps each C3D label parameter (255 labels) under the signed
// 16-bit offset that C3D readers follow to the next parameter.
inline constexpr std::size_t kMaxLabelLength = 127;

// Throws ExportError naming `path` when the trajectories cannot be exported as they are: no frame
// or no marker, rate not positive, a row not one sample per label, a present sample with a
// non-finite coordinate or a residual that is negative or not finite, a label that is empty,
// repeated, longer than kMaxLabelLength, or holds a character other than printable ASCII, or
// starts or ends with a space (C3D drops trailing spaces).
void check_exportable(const MarkerTrajectories& trajectories, const std::string& path);

}  // namespace syncap::io
