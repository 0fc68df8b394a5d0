// The tracker on marker trajectories real people made (../shared/data/motion/real-markers: a
// Qualisys walk of 55 markers at 200 Hz, an OpenSim running trial of 41 markers at 60 Hz), read
// with the C3D and TRC importers, observed with 0.3 px-like noise (0.3 mm), 10 % of each marker's
// frames hidden in runs of 1-5 frames, and a spurious point a frame; the walk also at 100 and 50
// Hz (every 2nd, 4th frame). Issue 38 wants at most 1 exchange and 5 breaks per 1000
// marker-frames with the defaults. Measured with the defaults (exchanges / breaks per 1000;
// docs/results/markers.md): running 60 Hz 2.13 / 8.59 (the quiet model alone, the tracker's
// former default: 20.3 / 100.3); walk 200 Hz 0.00 / 0.66 (3.6 / 51.7), 100 Hz 0.12 / 0.59,
// 50 Hz 1.91 / 6.45. Asserted: those, with margin, and the gain over the quiet model. Label
// data: skips without SYNCAP_DATA.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

#include "io/c3d_reader.hpp"
#include "io/trc_reader.hpp"
#include "recorded_motion.hpp"
#include "tracking_score.hpp"

namespace syncap::tracking {
namespace {

std::filesystem::path real_markers() {
  const char* data = std::getenv("SYNCAP_DATA");
  return data ? std::filesystem::path(data) / "motion" / "real-markers" : std::filesystem::path();
}

#define SKIP_WITHOUT(file)                                                                  \
  if (real_markers().empty() || !std::filesystem::exists(real_markers() / (file)))          \
  GTEST_SKIP() << "needs SYNCAP_DATA with motion/real-markers/" << (file) << " (set it to " \
               << "../shared/data)"

MarkerTrajectories every_nth(MarkerTrajectories t, int n) {
  std::vector<std::vector<std::optional<MarkerSample>>> kept;
  for (std::size_t f = 0; f < t.samples.size(); f += n) kept.push_back(t.samples[f]);
  t.samples = std::move(kept);
  t.rate_hz /= n;
  return t;
}

Score score_on(const MarkerTrajectories& t, const TrackerOptions& options, const char* name) {
  test::MotionOptions o;
  o.noise_mm = 0.3;
  const test::Motion motion = test::recorded_motion(t, o);
  TrackerCounters c;
  const Score s = track_and_score(motion, options, &c);
  std::printf(
      "%s: %ld marker-frames, %.2f exchanges and %.2f breaks per 1000, %ld/%ld occlusions "
      "bridged, %ld unlabelled; tracks started %ld\n",
      name, s.marker_frames, s.exchanges_per_1000(), s.breaks_per_1000(), s.bridged, s.occlusions,
      s.unlabelled, c.tracks_started);
  return s;
}

MarkerTrajectories read(const char* file) {
  return io::read_marker_trajectories((real_markers() / file).string());
}

// The tracker's former default: one constant-velocity model of 10 m/s^2, no wide gate.
TrackerOptions quiet_only() {
  TrackerOptions o;
  o.motion.manoeuvre_acceleration_mm_s2 = 0;
  o.wide_gate_acceleration_mm_s2 = 0;
  return o;
}

void record(const char* what, const Score& s) {
  ::testing::Test::RecordProperty(std::string(what) + "_exchanges_per_1000",
                                  std::to_string(s.exchanges_per_1000()));
  ::testing::Test::RecordProperty(std::string(what) + "_breaks_per_1000",
                                  std::to_string(s.breaks_per_1000()));
}

TEST(RealMotionTracking, RunningAt60Hz) {
  SKIP_WITHOUT("subject02_running.trc");
  const MarkerTrajectories t = read("subject02_running.trc");
  const Score quiet = score_on(t, quiet_only(), "running, 60 Hz, the quiet model alone");
  const Score s = score_on(t, {}, "running, 60 Hz, defaults");
  EXPECT_LT(s.breaks_per_1000(), 0.2 * quiet.breaks_per_1000());
  EXPECT_LT(s.exchanges_per_1000(), 0.25 * quiet.exchanges_per_1000());
  EXPECT_LT(s.breaks_per_1000(), 12.0);
  EXPECT_LT(s.exchanges_per_1000(), 3.5);
  record("defaults", s);
  record("quiet", quiet);
}

TEST(RealMotionTracking, WalkingAt200And100And50Hz) {
  SKIP_WITHOUT("Qualisys.c3d");
  const MarkerTrajectories t = read("Qualisys.c3d");
  const Score quiet = score_on(t, quiet_only(), "walking, 200 Hz, the quiet model alone");
  const Score s200 = score_on(t, {}, "walking, 200 Hz, defaults");
  const Score s100 = score_on(every_nth(t, 2), {}, "walking, 100 Hz, defaults");
  const Score s50 = score_on(every_nth(t, 4), {}, "walking, 50 Hz, defaults");
  EXPECT_LT(s200.breaks_per_1000(), 0.1 * quiet.breaks_per_1000());
  EXPECT_LT(s200.exchanges_per_1000(), 0.5);
  EXPECT_LT(s200.breaks_per_1000(), 2.0);
  EXPECT_LT(s100.exchanges_per_1000(), 0.5);
  EXPECT_LT(s100.breaks_per_1000(), 2.0);
  EXPECT_LT(s50.exchanges_per_1000(), 3.0);
  EXPECT_LT(s50.breaks_per_1000(), 9.0);
  record("walk200", s200);
  record("walk50", s50);
}

}  // namespace
}  // namespace syncap::tracking
