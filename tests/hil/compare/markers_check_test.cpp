// The host's 3D markers scored against the simulator's true targets: found, ghosts, RMS, id
// switches (per phase), and markers measured in a calibration's frame moved into the truth's.
#include "markers_check.hpp"

#include <gtest/gtest.h>

namespace syncap::compare {
namespace {

// Two cameras seeing targets 0 and 1 in frames 0..3 (phase 0) and 4..5 (phase 1); target 2 is
// seen by one camera only (not a visible target).
Truth two_camera_truth() {
  Truth truth;
  truth.images = {{0, {640, 480}}, {1, {640, 480}}};
  for (long f = 0; f < 6; ++f) {
    truth.frames[f] = TruthFrame{f, f / 30.0, f < 4 ? 0 : 1, f < 4 ? "wand" : "person"};
    for (int camera = 0; camera < 2; ++camera) {
      auto& list = truth.projections[{f, camera}];
      for (int target = 0; target < 3; ++target) {
        list.push_back({f, camera, target, 100.0 + target, 100, 2, target < 2 || camera == 0});
      }
    }
  }
  return truth;
}

TruePositions positions() {
  TruePositions p;
  for (long f = 0; f < 6; ++f) {
    p[f][0] = {0, 0, 1000};
    p[f][1] = {100, 0, 1000};
    p[f][2] = {0, 100, 1000};
  }
  return p;
}

Group group(long frame, std::vector<Marker> markers) {
  Group g;
  g.frame = frame;
  g.markers = std::move(markers);
  return g;
}

TEST(MarkersCheck, CountsFoundGhostsAndTheErrorOfTheFound) {
  const std::vector<Group> groups = {
      group(0, {{0.3, 0, 1000, 2, 1}, {100, 0.4, 1000, 3, 2}}),
      group(1, {{0, 0, 1000, 2, 1}, {500, 500, 500, 2, 7}}),  // target 1 missed, one ghost
  };
  const MarkersCheck c = check_markers(two_camera_truth(), positions(), groups, 5);
  EXPECT_EQ(c.frames, 2);
  EXPECT_EQ(c.visible_targets, 4);
  EXPECT_EQ(c.found, 3);
  EXPECT_EQ(c.markers, 4);
  EXPECT_EQ(c.ghosts, 1);
  EXPECT_EQ(c.two_camera_markers, 3);
  EXPECT_NEAR(c.rms_mm(), std::sqrt((0.09 + 0.16 + 0) / 3), 1e-12);
}

TEST(MarkersCheck, AnIdSwitchIsATargetFoundUnderAnotherTargetsIdWithinAPhase) {
  const std::vector<Group> groups = {
      group(0, {{0, 0, 1000, 2, 1}, {100, 0, 1000, 2, 2}}),
      group(1, {{0, 0, 1000, 2, 1}, {100, 0, 1000, 2, 2}}),
      group(2, {{0, 0, 1000, 2, 2}, {100, 0, 1000, 2, 1}}),  // swapped: two switches
      group(3, {{0, 0, 1000, 2, 7}}),                        // a new id: a break; 1 hidden
      // Phase 1 numbers its own targets: new ids are neither.
      group(4, {{0, 0, 1000, 2, 10}, {100, 0, 1000, 2, 11}}),
      group(5, {{0, 0, 1000, 2, 10}, {100, 0, 1000, 2, 11}}),
  };
  const MarkersCheck c = check_markers(two_camera_truth(), positions(), groups, 5);
  EXPECT_EQ(c.id_switches, 2);
  EXPECT_EQ(c.track_breaks, 1);
  EXPECT_EQ(c.found, 11);
  EXPECT_NEAR(c.id_switches_per_1000(), 2000.0 / 11, 1e-9);
  EXPECT_NE(format_markers_check(c).find(
                "2 id switches (181.82 per 1000 found), 1 track breaks (90.91 per 1000 found)"),
            std::string::npos)
      << format_markers_check(c);
}

TEST(MarkersCheck, MarkersOfACalibrationsFrameAreMovedIntoTheTruths) {
  Similarity motion;
  motion.rotation = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).matrix();
  motion.translation = {10, 20, 30};
  // Measured in the calibration's frame: the inverse motion of the true points.
  const auto measured = [&](double x, double y, double z) {
    const Eigen::Vector3d p =
        motion.rotation.transpose() * (Eigen::Vector3d(x, y, z) - motion.translation);
    return Marker{p.x(), p.y(), p.z(), 2, 1};
  };
  std::vector<Group> groups = {group(0, {measured(0, 0, 1000), measured(100, 0, 1000)})};
  EXPECT_EQ(check_markers(two_camera_truth(), positions(), groups, 5).found, 0);
  move_markers(groups, motion);
  const MarkersCheck c = check_markers(two_camera_truth(), positions(), groups, 5);
  EXPECT_EQ(c.found, 2);
  EXPECT_LT(c.rms_mm(), 1e-9);
}

}  // namespace
}  // namespace syncap::compare
