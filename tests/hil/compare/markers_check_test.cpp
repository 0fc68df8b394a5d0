// The host's 3D markers scored against the simulator's true targets: found, ghosts, RMS, id
// switches (per phase), and markers measured in a calibration's frame moved into the truth's.
#include "markers_check.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "ring_scene.hpp"
#include "util/printf_string.hpp"

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

// --- The reference: the best estimator on the same whole views ---

using testing::RingScene;

TEST(MarkersReference, ExactBlobsGiveAReferenceOfZero) {
  RingScene scene;
  const auto groups = scene.groups(Eigen::Vector3d::Zero(), {0.3, 0, 0});
  const MarkersCheck c = check_markers(scene.truth, scene.positions, groups, 5, 3);
  EXPECT_EQ(c.found, 8);
  const WholeViewReference& r = c.reference;
  EXPECT_EQ(r.targets, 8);
  EXPECT_EQ(r.without, 0);
  EXPECT_EQ(r.views, 2 * (16 - 2));  // the merged pair in camera 0 left out
  ASSERT_TRUE(r.rms_mm());
  EXPECT_LT(*r.rms_mm(), 1e-6);
  EXPECT_LT(*r.view_rms_px(), 1e-9);
  EXPECT_NEAR(*r.host_rms_mm(), 0.3, 1e-9);
}

TEST(MarkersReference, AMergedPairIsLeftOutForBothTargets) {
  RingScene scene;
  const auto& camera0 = scene.truth.projections.at({0, 0});
  const auto& camera1 = scene.truth.projections.at({0, 1});
  EXPECT_FALSE(whole_view(camera0, 0, {1000, 1000}));
  EXPECT_FALSE(whole_view(camera0, 3, {1000, 1000}));
  EXPECT_TRUE(whole_view(camera0, 1, {1000, 1000}));
  EXPECT_TRUE(whole_view(camera1, 0, {1000, 1000}));
  EXPECT_TRUE(whole_view(camera1, 3, {1000, 1000}));
  // Two discs 1 px farther apart than their radii are no longer merged.
  std::vector<Projection> apart = {{0, 0, 0, 100, 100, 2, true}, {0, 0, 1, 105.01, 100, 2, true}};
  EXPECT_TRUE(whole_view(apart, 0, {1000, 1000}));
  apart[1].x_px = 104.99;
  EXPECT_FALSE(whole_view(apart, 0, {1000, 1000}));
  // The merged spot's centroid lies between the two: the reference does not see it.
  auto groups = scene.groups(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  for (Group& g : groups) {
    g.cameras.at(0).blobs[0].x += 1.5;
    g.cameras.at(0).blobs[3].x += 1.5;
  }
  const MarkersCheck c = check_markers(scene.truth, scene.positions, groups, 5, 3);
  EXPECT_EQ(c.reference.targets, 8);
  EXPECT_EQ(c.reference.views, 2 * 14);
  EXPECT_LT(*c.reference.rms_mm(), 1e-6);
}

TEST(MarkersReference, HiddenViewsAreLeftOutAndOneWholeViewGivesNoReference) {
  RingScene scene;
  for (long f = 0; f < RingScene::kFrames; ++f) {
    scene.truth.projections.at({f, 2})[1].visible = false;  // target 1 hidden in camera 2
    // Target 2: hidden in cameras 2 and 3, its blob in camera 1 lost: one whole view.
    scene.truth.projections.at({f, 2})[2].visible = false;
    scene.truth.projections.at({f, 3})[2].visible = false;
  }
  auto groups = scene.groups(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  for (Group& g : groups) {
    // The hidden discs' spots, cut by the person: off by 1.5 px.
    g.cameras.at(2).blobs[1].y += 1.5;
    g.cameras.at(2).blobs[2].y += 1.5;
    g.cameras.at(3).blobs[2].y += 1.5;
    auto& blobs1 = g.cameras.at(1).blobs;
    blobs1.erase(blobs1.begin() + 2);
  }
  const MarkersCheck c = check_markers(scene.truth, scene.positions, groups, 5, 3);
  EXPECT_EQ(c.found, 8);
  EXPECT_EQ(c.reference.targets, 6);
  EXPECT_EQ(c.reference.without, 2);
  EXPECT_EQ(c.reference.views, 2 * (3 + 3 + 3));  // targets 0, 3: the merge; 1: hidden
  EXPECT_LT(*c.reference.rms_mm(), 1e-6);
  EXPECT_NE(format_markers_check(c).find("2 with fewer than 2 whole views"), std::string::npos)
      << format_markers_check(c);
}

TEST(MarkersReference, TheRatioIsTheHostsRmsOverTheReferencesOnTheSameTargets) {
  RingScene scene;
  const Eigen::Vector3d shift(0.2, -0.1, 0.15);    // every whole view's blob points here
  auto groups = scene.groups(shift, {0, 0.5, 0});  // every marker 0.5 mm off
  // Target 2 has one whole view (hidden in cameras 2 and 3, its blob in camera 1 lost): no
  // reference, and its marker, 2 mm farther off, does not enter the ratio.
  for (long f = 0; f < RingScene::kFrames; ++f) {
    for (int camera : {2, 3}) scene.truth.projections.at({f, camera})[2].visible = false;
  }
  for (Group& g : groups) {
    (*g.markers)[2].x += 2;
    auto& blobs1 = g.cameras.at(1).blobs;
    blobs1.erase(blobs1.begin() + 2);
  }
  const MarkersCheck c = check_markers(scene.truth, scene.positions, groups, 5, 3);
  EXPECT_EQ(c.found, 8);
  const WholeViewReference& r = c.reference;
  EXPECT_EQ(r.targets, 6);
  EXPECT_EQ(r.without, 2);
  EXPECT_EQ(r.views, 2 * (3 + 4 + 3));
  EXPECT_NEAR(*r.rms_mm(), shift.norm(), 1e-6);
  EXPECT_NEAR(*r.host_rms_mm(), 0.5, 1e-9);
  EXPECT_NEAR(*r.ratio(), 0.5 / shift.norm(), 1e-5);
  EXPECT_NEAR(c.rms_mm(), std::sqrt((6 * 0.25 + 2 * (0.25 + 4)) / 8), 1e-9);
  // The whole views' 2D errors, from the truth's own pixels.
  double sum = 0;
  long n = 0;
  for (const auto& [id, camera] : scene.truth.cameras) {
    for (int t : {0, 1, 3}) {
      if (id == 0 && t != 1) continue;  // the merged pair
      sum += (scene.pixel(id, scene.targets[t] + shift) - scene.pixel(id, scene.targets[t]))
                 .squaredNorm();
      ++n;
    }
  }
  EXPECT_EQ(2 * n, r.views);
  EXPECT_NEAR(*r.view_rms_px(), std::sqrt(sum / n), 1e-9);
  const std::string line = format_markers_check(c);
  const std::string expected = util::printf_string(
      "best estimator on the same whole views %.3f mm (the host 0.500 mm on those 6 targets, "
      "ratio %.2f; 2 with fewer than 2 whole views; their 20 blobs' 2D RMS %.3f px)",
      shift.norm(), 0.5 / shift.norm(), std::sqrt(sum / n));
  EXPECT_NE(line.find(expected), std::string::npos) << line << "\n" << expected;
  const auto json = markers_json(c);
  EXPECT_NEAR(json["reference_rms_mm"].get<double>(), shift.norm(), 1e-6);
  EXPECT_NEAR(json["rms_over_reference"].get<double>(), 0.5 / shift.norm(), 1e-5);
  EXPECT_EQ(json["reference_targets"], 6);
  EXPECT_EQ(json["targets_without_reference"], 2);
  EXPECT_EQ(json["reference_views"], 20);
}

// Groups without true cameras (a truth made by hand): every found target is without a reference.
TEST(MarkersReference, WithoutTrueCamerasThereIsNone) {
  const std::vector<Group> groups = {group(0, {{0, 0, 1000, 2, 1}})};
  const MarkersCheck c = check_markers(two_camera_truth(), positions(), groups, 5);
  EXPECT_EQ(c.reference.targets, 0);
  EXPECT_EQ(c.reference.without, 1);
  EXPECT_FALSE(c.reference.rms_mm());
  EXPECT_FALSE(c.reference.ratio());
  EXPECT_TRUE(markers_json(c)["reference_rms_mm"].is_null());
}

}  // namespace
}  // namespace syncap::compare
