// Trajectories whose every value follows from (frame, marker), so that a reader of the exported
// file (the tests here, tests/host/io/check_exports.py) knows what to expect without the writer's
// data. The formulas are repeated in check_exports.py: change both together.
#pragma once

#include <cstdio>
#include <string>

#include "tracking/marker_trajectories.hpp"

namespace syncap::io::testing {

// Multiples of 1/8 mm: exact in a float, so the C3D values compare exactly.
inline Eigen::Vector3d synthetic_position(long f, long m) {
  return {100.0 * m + 0.5 * f, -50.0 * m + 0.25 * f, 1000.0 + m - 0.125 * f};
}
inline bool synthetic_seen(long f, long m) { return (f * 7 + m * 3) % 11 != 0; }
inline double synthetic_residual(long f, long m) { return 0.1 + 0.01 * ((f + m) % 50); }
inline uint32_t synthetic_cameras(long f, long m) { return static_cast<uint32_t>((f + m) % 512); }

inline std::string numbered_label(long m) {
  char label[24];
  std::snprintf(label, sizeof label, "M%03ld", m + 1);
  return label;
}

// `frames` x `markers`, labels M001, M002, ... unless given.
inline tracking::MarkerTrajectories synthetic_trajectories(long frames, long markers,
                                                           double rate_hz, int64_t first_frame) {
  tracking::MarkerTrajectories t;
  t.rate_hz = rate_hz;
  t.first_frame = first_frame;
  for (long m = 0; m < markers; ++m) t.labels.push_back(numbered_label(m));
  t.samples.resize(static_cast<std::size_t>(frames));
  for (long f = 0; f < frames; ++f) {
    auto& row = t.samples[static_cast<std::size_t>(f)];
    row.resize(static_cast<std::size_t>(markers));
    for (long m = 0; m < markers; ++m) {
      if (!synthetic_seen(f, m)) continue;
      row[static_cast<std::size_t>(m)] = tracking::MarkerSample{
          synthetic_position(f, m), synthetic_residual(f, m), synthetic_cameras(f, m)};
    }
  }
  return t;
}

}  // namespace syncap::io::testing
