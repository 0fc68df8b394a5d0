#include "comparison.hpp"

#include <gtest/gtest.h>

#include "summary.hpp"

namespace syncap::compare {
namespace {

// Two cameras, four frames (two wand, two room); one target at (100, 100) in every wand frame.
Truth two_camera_truth() {
  Truth t;
  for (long k = 0; k < 4; ++k) t.frames[k] = {k, k / 30.0, k < 2 ? 0 : 1, k < 2 ? "wand" : "room"};
  t.images = {{0, {640, 480}}, {1, {640, 480}}};
  for (long k = 0; k < 2; ++k) {
    for (int c = 0; c < 2; ++c) t.projections[{k, c}] = {{k, c, 0, 100, 100, 4, true}};
  }
  return t;
}

Group group(long frame, std::map<int, std::vector<Blob>> blobs_by_camera) {
  Group g;
  g.frame = frame;
  g.complete = blobs_by_camera.size() == 2;
  for (auto& [id, blobs] : blobs_by_camera) g.cameras[id] = {100, blobs, std::nullopt};
  return g;
}

std::vector<Group> perfect_groups(double error_px = 0.01) {
  const std::vector<Blob> hit{{100 + error_px, 100, 50}};
  return {group(0, {{0, hit}, {1, hit}}), group(1, {{0, hit}, {1, hit}}),
          group(2, {{0, {}}, {1, {}}}), group(3, {{0, {}}, {1, {}}})};
}

TEST(Compare, PassesWhenEverythingArrivedAndMatched) {
  const Report r = compare(two_camera_truth(), perfect_groups(), {});
  EXPECT_TRUE(r.pass()) << verdict_line(r);
  EXPECT_EQ(r.overall.frames.truth, 4);
  EXPECT_EQ(r.overall.frames.complete, 4);
  EXPECT_EQ(r.cameras.at(1).tally.counted.matched, 2);
  EXPECT_EQ(r.phase_types, (std::vector<std::string>{"wand", "room"}));
  EXPECT_EQ(r.phases.at("wand").tally.counted.targets, 4);
  EXPECT_EQ(r.phases.at("room").tally.counted.targets, 0);
  EXPECT_EQ(verdict_line(r), "PASS");
}

TEST(Compare, FailsOnCentroidError) {
  const Report r = compare(two_camera_truth(), perfect_groups(0.25), {});
  EXPECT_EQ(verdict_line(r),
            "FAIL: camera 0: RMS 0.2500 px > 0.1000 px; "
            "camera 1: RMS 0.2500 px > 0.1000 px");
}

TEST(Compare, FailsOnMissedTargetsAndMissingFrames) {
  auto groups = perfect_groups();
  groups[1] = group(1, {{0, {{100, 100, 50}}}, {1, {{150, 100, 50}}}});  // camera 1 misses
  groups.pop_back();                                                     // frame 3 never came
  groups.push_back(group(9, {}));                                        // not in the truth
  const Report r = compare(two_camera_truth(), groups, {});
  EXPECT_EQ(r.overall.frames.at_host, 3);
  EXPECT_EQ(r.groups_outside_truth, 1);
  EXPECT_EQ(r.cameras.at(1).tally.false_blobs, 1);
  EXPECT_EQ(
      verdict_line(r),
      "FAIL: frames: 3/4 complete groups (75.00% < 99.00%); camera 1: detection 50.00% < 98.00%");
}

TEST(Compare, CountsCamerasMissingFromAGroup) {
  auto groups = perfect_groups();
  groups[0] = group(0, {{0, {{100, 100, 50}}}});
  const Report r = compare(two_camera_truth(), groups, {.min_frames = 0.5});
  EXPECT_EQ(r.cameras.at(1).groups_without, 1);
  EXPECT_EQ(r.cameras.at(1).groups_with, 3);
  EXPECT_EQ(r.cameras.at(1).tally.counted.targets, 1);  // only frames the camera reported
  EXPECT_TRUE(r.pass()) << verdict_line(r);
}

TEST(Summary, ShowsTablesAndEndsWithTheVerdict) {
  const std::string text = format_summary(compare(two_camera_truth(), perfect_groups(), {}), "hi");
  EXPECT_EQ(text.rfind("hi\n", 0), 0u);
  EXPECT_NE(text.find("frames: 4/4 truth frames at the host, 4 complete (100.0%)"),
            std::string::npos)
      << text;
  // camera 0: 4 groups, none missing, 100 us, 2 targets matched, no false blobs, 0.01 px error.
  EXPECT_NE(text.find("  0            4       0    100.0       2       2  100.0%       0   0.0100"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("  room         2       2        2       0       0       -       0        -"),
            std::string::npos)
      << text;
  EXPECT_EQ(text.substr(text.size() - 5), "PASS\n");
}

TEST(Summary, JsonHoldsTheFigures) {
  const auto j = report_json(compare(two_camera_truth(), perfect_groups(0.25), {}));
  EXPECT_FALSE(j["pass"].get<bool>());
  EXPECT_EQ(j["failures"].size(), 2u);
  EXPECT_EQ(j["frames"]["complete"], 4);
  EXPECT_NEAR(j["cameras"][0]["counted"]["rms_px"].get<double>(), 0.25, 1e-12);
  EXPECT_TRUE(j["phases"][1]["counted"]["rms_px"].is_null());  // room: no targets
}

}  // namespace
}  // namespace syncap::compare
