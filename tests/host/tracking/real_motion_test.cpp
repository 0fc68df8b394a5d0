// The tracker on marker trajectories real people made (../shared/data/motion/real-markers: a
// Qualisys walk of 55 markers at 200 Hz, an OpenSim running trial of 41 markers at 60 Hz), read
// with the C3D and TRC importers, observed with 0.3 px-like noise (0.3 mm), 10 % of each marker's
// frames hidden in runs of 1-5 frames, and a spurious point a frame. Issue 38 wants at most 1
// exchange and 5 breaks per 1000 marker-frames with the defaults; not reached yet. Measured
// (exchanges / breaks per 1000): running, the quiet model alone (the default) 20.3 / 100.3, with
// the manoeuvring model of 150 m/s^2 7.3 / 9.1 (on exact data with nothing hidden 16.0 / 79.9
// against 0.0 / 0.1); walking at 200 Hz 3.6 / 51.7 against 2.9 / 34.5, most of the breaks from
// the recording's own single-frame jumps of 2-13 mm. Asserted: those gains, with margin. Label
// data: skips without SYNCAP_DATA.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>

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

Score score_on(const std::string& file, const TrackerOptions& options, const char* name) {
  const MarkerTrajectories t = io::read_marker_trajectories((real_markers() / file).string());
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

TrackerOptions manoeuvring() {
  TrackerOptions o;
  o.motion.manoeuvre_acceleration_mm_s2 = 150000;
  return o;
}

void record(const Score& quiet, const Score& mixed) {
  ::testing::Test::RecordProperty("quiet_exchanges_per_1000",
                                  std::to_string(quiet.exchanges_per_1000()));
  ::testing::Test::RecordProperty("quiet_breaks_per_1000", std::to_string(quiet.breaks_per_1000()));
  ::testing::Test::RecordProperty("imm_exchanges_per_1000",
                                  std::to_string(mixed.exchanges_per_1000()));
  ::testing::Test::RecordProperty("imm_breaks_per_1000", std::to_string(mixed.breaks_per_1000()));
}

TEST(RealMotionTracking, RunningAt60HzNeedsTheManoeuvringModel) {
  SKIP_WITHOUT("subject02_running.trc");
  const Score quiet = score_on("subject02_running.trc", {}, "running, 60 Hz, quiet model");
  const Score mixed = score_on("subject02_running.trc", manoeuvring(), "running, 60 Hz, IMM");
  EXPECT_LT(mixed.breaks_per_1000(), 0.2 * quiet.breaks_per_1000());
  EXPECT_LT(mixed.exchanges_per_1000(), 0.5 * quiet.exchanges_per_1000());
  EXPECT_LT(mixed.breaks_per_1000(), 15.0);
  EXPECT_LT(mixed.exchanges_per_1000(), 10.0);
  record(quiet, mixed);
}

TEST(RealMotionTracking, WalkingAt200HzBreaksLessWithTheManoeuvringModel) {
  SKIP_WITHOUT("Qualisys.c3d");
  const Score quiet = score_on("Qualisys.c3d", {}, "walking, 200 Hz, quiet model");
  const Score mixed = score_on("Qualisys.c3d", manoeuvring(), "walking, 200 Hz, IMM");
  EXPECT_LT(mixed.breaks_per_1000(), 0.8 * quiet.breaks_per_1000());
  EXPECT_LT(mixed.exchanges_per_1000(), 5.0);
  record(quiet, mixed);
}

}  // namespace
}  // namespace syncap::tracking
