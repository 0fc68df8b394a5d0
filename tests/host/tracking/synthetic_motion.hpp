// Synthetic marker motion with exact truth for the tracking tests and benchmark: markers on
// smooth random paths (sums of sinusoids, peak speeds up to a person's 3 m/s) in a person-sized
// box, measured with noise, hidden for runs of 1..5 frames, with spurious points, and each frame's
// points shuffled (the tracker gets no help from their order).
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include "tracking/marker_tracker.hpp"

namespace syncap::test {

struct MotionOptions {
  int markers = 32;
  double rate_hz = 100;
  int frames = 2000;
  double noise_mm = 0.3;
  double missing = 0.10;  // share of marker-frames hidden
  int max_occlusion = 5;  // frames; occlusions are 1..max_occlusion long
  double spurious_per_frame = 1.0;
  double max_speed_mm_s = 3000;
  unsigned seed = 1;
};

struct MotionFrame {
  int64_t frame = 0;
  double time_s = 0;
  std::vector<tracking::PointObservation> points;
  std::vector<int> marker_of_point;  // -1: spurious
};

struct Occlusion {
  int marker = 0;
  int first_hidden = 0;  // frame index
  int length = 0;
};

struct Motion {
  std::vector<MotionFrame> frames;
  std::vector<Occlusion> occlusions;
  std::vector<std::vector<Eigen::Vector3d>> truth;  // [frame][marker]
};

// One marker's path: per axis three sinusoids, scaled so its peak speed is `speed`.
struct Path {
  Eigen::Vector3d centre;
  Eigen::Matrix3d amplitude, frequency, phase;  // [axis][term]
  Eigen::Vector3d at(double t) const {
    Eigen::Vector3d p = centre;
    for (int a = 0; a < 3; ++a)
      for (int k = 0; k < 3; ++k)
        p[a] += amplitude(a, k) * std::sin(2 * M_PI * frequency(a, k) * t + phase(a, k));
    return p;
  }
};

inline Path random_path(std::mt19937& rng, double speed, double duration_s) {
  std::uniform_real_distribution<double> xy(-600, 600), z(300, 1700), f(0.1, 1.0), ph(0, 2 * M_PI),
      amp(50, 300);
  Path path{{xy(rng), xy(rng), z(rng)}, {}, {}, {}};
  for (int a = 0; a < 3; ++a)
    for (int k = 0; k < 3; ++k) {
      path.amplitude(a, k) = amp(rng);
      path.frequency(a, k) = f(rng);
      path.phase(a, k) = ph(rng);
    }
  double peak = 0;
  for (double t = 0; t < duration_s; t += 0.005)
    peak = std::max(peak, (path.at(t + 1e-4) - path.at(t)).norm() / 1e-4);
  path.amplitude *= speed / peak;
  return path;
}

// Per marker and frame: hidden or not, as runs of 1..max_occlusion frames covering `missing`.
inline std::vector<std::vector<char>> hidden_runs(const MotionOptions& o, std::mt19937& rng,
                                                  std::vector<Occlusion>& occlusions) {
  const double mean_length = (1 + o.max_occlusion) / 2.0;
  std::bernoulli_distribution starts(o.missing / ((1 - o.missing) * mean_length));
  std::uniform_int_distribution<int> length(1, o.max_occlusion);
  std::vector<std::vector<char>> hidden(o.frames, std::vector<char>(o.markers, 0));
  for (int m = 0; m < o.markers; ++m) {
    for (int f = 1; f < o.frames; ++f) {
      if (!starts(rng)) continue;
      const int n = std::min(length(rng), o.frames - 1 - f);  // never hidden at the very end
      if (n <= 0) break;
      occlusions.push_back({m, f, n});
      for (int i = 0; i < n; ++i) hidden[f + i][m] = 1;
      f += n;  // visible at least one frame between occlusions
    }
  }
  return hidden;
}

inline tracking::PointObservation observed(const Eigen::Vector3d& p, double sigma) {
  tracking::PointObservation o;
  o.position_mm = p;
  o.covariance_mm2 = Eigen::Matrix3d::Identity() * sigma * sigma;
  o.cameras = 0xff;
  o.rms_px = 0.15;
  return o;
}

inline Motion simulate_motion(const MotionOptions& o) {
  std::mt19937 rng(o.seed);
  std::uniform_real_distribution<double> speed(0.5 * o.max_speed_mm_s, o.max_speed_mm_s);
  std::vector<Path> paths;
  for (int m = 0; m < o.markers; ++m)
    paths.push_back(random_path(rng, speed(rng), o.frames / o.rate_hz));
  Motion motion;
  const auto hidden = hidden_runs(o, rng, motion.occlusions);
  std::normal_distribution<double> noise(0, o.noise_mm);
  std::poisson_distribution<int> spurious(o.spurious_per_frame);
  std::uniform_real_distribution<double> xy(-1000, 1000), z(0, 2000);
  for (int f = 0; f < o.frames; ++f) {
    MotionFrame frame{f, f / o.rate_hz, {}, {}};
    std::vector<Eigen::Vector3d> truth;
    for (int m = 0; m < o.markers; ++m) {
      truth.push_back(paths[m].at(frame.time_s));
      if (hidden[f][m]) continue;
      frame.points.push_back(
          observed(truth.back() + Eigen::Vector3d(noise(rng), noise(rng), noise(rng)), o.noise_mm));
      frame.marker_of_point.push_back(m);
    }
    for (int s = spurious(rng); s > 0; --s) {
      frame.points.push_back(observed({xy(rng), xy(rng), z(rng)}, o.noise_mm));
      frame.marker_of_point.push_back(-1);
    }
    std::vector<int> order(frame.points.size());
    std::iota(order.begin(), order.end(), 0);
    std::shuffle(order.begin(), order.end(), rng);
    MotionFrame shuffled{frame.frame, frame.time_s, {}, {}};
    for (int i : order) {
      shuffled.points.push_back(frame.points[i]);
      shuffled.marker_of_point.push_back(frame.marker_of_point[i]);
    }
    motion.frames.push_back(std::move(shuffled));
    motion.truth.push_back(std::move(truth));
  }
  return motion;
}

}  // namespace syncap::test
