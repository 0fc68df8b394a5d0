#include "scenario.hpp"

#include <gtest/gtest.h>

#include <filesystem>

namespace syncap::sim {
namespace {

const char* kMinimal = R"(
name: tiny
cameras:
  count: 2
phases:
  - type: wand
    frames: 10
)";

std::string error_of(const std::string& text) {
  try {
    parse_scenario(text, "broken.yaml");
  } catch (const ScenarioError& e) {
    return e.what();
  }
  return "no error";
}

TEST(Scenario, MinimalFileGetsDocumentedDefaults) {
  const Scenario s = parse_scenario(kMinimal, "tiny.yaml");
  EXPECT_EQ(s.name, "tiny");
  EXPECT_EQ(s.cameras.count, 2);
  EXPECT_EQ(s.cameras.layout, "ring");
  ASSERT_EQ(s.phases.size(), 1u);
  EXPECT_EQ(s.phases[0].background, "dark");
  EXPECT_EQ(s.phases[0].wand.target_offsets_mm.size(), 2u);
  EXPECT_EQ(s.total_frames(), 10);
}

TEST(Scenario, ShippedScenariosLoad) {
  const std::filesystem::path dir = std::filesystem::path(SYNCAP_SOURCE_DIR) / "hil" / "scenarios";
  for (const char* name :
       {"wand-3cam-basler", "ring-6cam-person", "led-6cam-webcam", "markers-8cam-qualisys",
        "markers-8cam-qualisys-dense", "markers-8cam-running"}) {
    const Scenario s = load_scenario(dir / (std::string(name) + ".yaml"));
    EXPECT_EQ(s.name, name);
    EXPECT_GT(s.total_frames(), 0);
  }
  const Scenario basler = load_scenario(dir / "wand-3cam-basler.yaml");
  EXPECT_EQ(basler.cameras.width_px, 1280);
  EXPECT_DOUBLE_EQ(basler.cameras.pixel_size_mm, 0.0067);
  EXPECT_EQ(basler.phases[0].wand.target_offsets_mm.size(), 3u);
}

TEST(Scenario, ErrorsNameFileLineAndProblem) {
  EXPECT_EQ(error_of("cameras:\n  count: 2\nphases:\n  - type: wand\n    frames: -3\n"),
            "broken.yaml:5: phases[0].frames = -3 is outside 1..10000000");
  EXPECT_EQ(error_of("cameras:\n  count: 2\n  lens: 4\nphases:\n  - {type: wand, frames: 1}\n"),
            "broken.yaml:3: unknown key 'lens' in cameras");
  EXPECT_EQ(error_of("cameras:\n  count: 2\nphases:\n  - type: dance\n    frames: 1\n"),
            "broken.yaml:4: phases[0].type 'dance' is not one of: led, mocap, person, room, wand");
  EXPECT_EQ(error_of("phases:\n  - {type: room, frames: 1}\n"),
            "broken.yaml:1: scenario needs 'cameras'");
  EXPECT_EQ(
      error_of(
          "cameras: {count: 2}\nphases:\n  - {type: wand, frames: 1, target_offsets_mm: [0]}\n"),
      "broken.yaml:3: a wand has 2 or 3 targets (target_offsets_mm)");
  EXPECT_EQ(error_of("cameras: {count: 2}\nvolume_min_mm: [0, 0]\nphases: []\n"),
            "broken.yaml:2: scenario.volume_min_mm must be a list of three numbers [x, y, z]");
}

// Found by the fuzzer (issue 15): yaml-cpp's own exceptions escaped the reader for a list with
// a word in it and for a key that is not text.
TEST(Scenario, MistypedListsAndKeysAreScenarioErrors) {
  EXPECT_EQ(error_of("cameras: {count: 2}\nvolume_max_mm: [800, i800, 1900]\nphases: []\n"),
            "broken.yaml:2: scenario.volume_max_mm must be a list of three numbers [x, y, z]");
  EXPECT_EQ(error_of("cameras: {count: 2}\nphases:\n  - {type: wand, frames: 1, "
                     "target_offsets_mm: [0, x]}\n"),
            "broken.yaml:3: phases[0].target_offsets_mm must be a list of numbers");
  EXPECT_EQ(error_of("cameras: {count: 2, [1, 2]: 3}\nphases:\n  - {type: wand, frames: 1}\n"),
            "broken.yaml:1: a key in cameras is not text");
}

TEST(Scenario, YamlSyntaxErrorsNameTheLine) {
  const std::string e = error_of("cameras:\n  count: 2\nphases: [\n  - type: wand\n");
  EXPECT_EQ(e.rfind("broken.yaml:", 0), 0u) << e;
  EXPECT_NE(e.find(":4:"), std::string::npos) << e;
}

TEST(Scenario, ExplicitLayoutNeedsMatchingPoses) {
  const Scenario s = parse_scenario(R"(
cameras:
  layout: explicit
  poses:
    - {position_mm: [0, -3000, 1500], omega: 1.5}
    - {position_mm: [3000, 0, 1500], omega: 1.5, kappa: 1.57}
phases: [{type: room, frames: 2}]
)",
                                    "explicit.yaml");
  ASSERT_EQ(s.cameras.poses.size(), 2u);
  EXPECT_EQ(s.cameras.count, 2);
  EXPECT_DOUBLE_EQ(s.cameras.poses[1].kappa, 1.57);
  EXPECT_EQ(error_of("cameras:\n  layout: explicit\n  poses:\n    - {omega: 1}\nphases: []\n"),
            "broken.yaml:4: cameras.poses[0] needs 'position_mm'");
}

const char* kMarkers = R"(
cameras:
  count: 2
phases:
  - type: person
    frames: 5
    bvh: motion.bvh
    body_brightness: 0.3
    marker_radius_mm: 10
    markers:
      - {segment: l_thigh, at: [0, 0, 1]}
      - {segment: skull, at: [1, 0, 0]}
)";

TEST(Scenario, PersonMarkersAreReadWithTheirSegments) {
  const Scenario s = parse_scenario(kMarkers, "markers.yaml");
  const PersonSpec& p = s.phases.at(0).person;
  ASSERT_EQ(p.markers.size(), 2u);
  EXPECT_EQ(p.markers[0].segment, "l_thigh");
  EXPECT_EQ(p.markers[0].at, Eigen::Vector3d(0, 0, 1));
  EXPECT_EQ(p.markers[1].segment, "skull");
  EXPECT_DOUBLE_EQ(p.marker_radius_mm, 10);
  EXPECT_DOUBLE_EQ(p.marker_brightness_dn, 250);
  EXPECT_DOUBLE_EQ(p.body_brightness, 0.3);
}

TEST(Scenario, ABrokenMarkerNamesItsLine) {
  std::string text = kMarkers;
  text.replace(text.find("l_thigh"), 7, "l_tail");
  EXPECT_NE(error_of(text).find("broken.yaml:11: person.markers[].segment 'l_tail' is not one of"),
            std::string::npos)
      << error_of(text);
  text = kMarkers;
  text.replace(text.find("[1, 0, 0]"), 9, "[0, 0, 0]");
  EXPECT_EQ(error_of(text), "broken.yaml:12: person.markers[].at must not be [0, 0, 0]");
  text = kMarkers;
  text.replace(text.find("at: [0, 0, 1]"), 13, "on: [0, 0, 1]");
  EXPECT_EQ(error_of(text), "broken.yaml:11: person.markers[] needs 'at'");
}

TEST(Scenario, APersonIsTheEllipsoidsOrANamedSkinnedSubject) {
  const char* person = R"(
name: skinned
cameras: {count: 2}
phases:
  - {type: person, frames: 3, bvh: /dev/null, model: mesh, subject: tall-male}
)";
  const PersonSpec p = parse_scenario(person, "skinned.yaml").phases.at(0).person;
  EXPECT_EQ(p.model, "mesh");
  EXPECT_EQ(p.subject, "tall-male");
  EXPECT_EQ(parse_scenario(kMarkers, "markers.yaml").phases.at(0).person.model, "ellipsoids");
  std::string text = person;
  text.replace(text.find("model: mesh, "), 13, "");
  EXPECT_NE(error_of(text).find("person.subject needs person.model: mesh"), std::string::npos)
      << error_of(text);
  text = person;
  text.replace(text.find("mesh"), 4, "voxels");
  EXPECT_NE(error_of(text).find("broken.yaml:5:"), std::string::npos) << error_of(text);
}

TEST(Scenario, MissingFileIsNamed) {
  try {
    load_scenario("/nonexistent/s.yaml");
    FAIL();
  } catch (const ScenarioError& e) {
    EXPECT_STREQ(e.what(), "/nonexistent/s.yaml: cannot read the scenario file");
  }
}

}  // namespace
}  // namespace syncap::sim
