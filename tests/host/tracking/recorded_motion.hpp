// A test::Motion (synthetic_motion.hpp) from marker trajectories real people made (a C3D or TRC
// file, io/c3d_reader.hpp, io/trc_reader.hpp): the recorded positions as the truth, observed with
// noise, hidden in runs as the synthetic motion hides them (besides the recording's own gaps), and
// spurious points in the recording's volume. Markers never present are left out.
#pragma once

#include <random>

#include "synthetic_motion.hpp"
#include "tracking/marker_trajectories.hpp"

namespace syncap::test {

// `o`'s frames, markers and rate come from the file; its noise, hiding and spurious points apply.
inline Motion recorded_motion(const tracking::MarkerTrajectories& t, MotionOptions o) {
  std::vector<int> present;
  for (std::size_t m = 0; m < t.labels.size(); ++m) {
    for (const auto& row : t.samples) {
      if (m < row.size() && row[m]) {
        present.push_back(static_cast<int>(m));
        break;
      }
    }
  }
  o.frames = static_cast<int>(t.samples.size());
  o.markers = static_cast<int>(present.size());
  o.rate_hz = t.rate_hz;
  std::mt19937 rng(o.seed);
  Motion motion;
  const auto hidden = hidden_runs(o, rng, motion.occlusions);
  Eigen::Vector3d low = Eigen::Vector3d::Constant(1e300), high = -low;
  for (const auto& row : t.samples) {
    for (int m : present) {
      if (!row[m]) continue;
      low = low.cwiseMin(row[m]->position_mm);
      high = high.cwiseMax(row[m]->position_mm);
    }
  }
  std::normal_distribution<double> noise(0, o.noise_mm);
  std::poisson_distribution<int> spurious(o.spurious_per_frame);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int f = 0; f < o.frames; ++f) {
    MotionFrame frame{f, f / o.rate_hz, {}, {}};
    std::vector<Eigen::Vector3d> truth;
    for (int i = 0; i < o.markers; ++i) {
      const auto& sample = t.samples[f][present[i]];
      truth.push_back(sample ? sample->position_mm : Eigen::Vector3d::Zero());
      if (!sample || hidden[f][i]) continue;
      frame.points.push_back(
          observed(truth.back() + Eigen::Vector3d(noise(rng), noise(rng), noise(rng)), o.noise_mm));
      frame.marker_of_point.push_back(i);
    }
    for (int s = spurious(rng); s > 0; --s) {
      const Eigen::Vector3d p(low.x() + unit(rng) * (high.x() - low.x()),
                              low.y() + unit(rng) * (high.y() - low.y()),
                              low.z() + unit(rng) * (high.z() - low.z()));
      frame.points.push_back(observed(p, o.noise_mm));
      frame.marker_of_point.push_back(-1);
    }
    motion.frames.push_back(std::move(frame));
    motion.truth.push_back(std::move(truth));
  }
  return motion;
}

}  // namespace syncap::test
