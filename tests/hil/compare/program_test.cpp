// syncap-hil-compare end to end on hand-written truth and frame groups.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "help_check.hpp"
#include "program_run.hpp"
#include "ring_scene.hpp"
#include "scratch_files.hpp"
#include "sensor/camera_file.hpp"
#include "util/printf_string.hpp"

namespace syncap::compare {
namespace {

using testing::ScratchDir;

using syncap::test::ProgramRun;

ProgramRun run_compare(const std::string& arguments) {
  return syncap::test::run_program(std::string(SYNCAP_COMPARE_PATH) + " " + arguments);
}

std::string last_line(const std::string& text) {
  const std::size_t end = text.find_last_not_of('\n');
  const std::size_t start = text.rfind('\n', end);
  return text.substr(start == std::string::npos ? 0 : start + 1, end - start);
}

// Two cameras 640x480, three wand frames with two targets each, one LED-off frame without
// targets. Target 1 of camera 1 lies at the image edge in every frame: it must not count.
void write_truth(const ScratchDir& dir) {
  dir.write("cameras.json", testing::cameras_json(2));
  dir.write("truth/frames.csv",
            "frame,time_s,phase,phase_type,led_on,gain\n"
            "0,0,0,wand,0,1\n1,0.0333333,0,wand,0,1\n2,0.0666667,0,wand,0,1\n"
            "3,0.1,1,led,0,1\n");
  std::string rows = "frame,camera,target,x_px,y_px,radius_px,visible\n";
  for (int k = 0; k < 3; ++k) {
    const std::string f = std::to_string(k);
    rows += f + ",0,0,100,100,4,1\n" + f + ",0,1,300,200,4,1\n";
    rows += f + ",1,0,120,110,4,1\n" + f + ",1,1,637,240,4,1\n";
  }
  dir.write("truth/targets.csv", "frame,target,X_mm,Y_mm,Z_mm,radius_mm\n");
  dir.write("truth/projections.csv", rows);
}

// The host's lines; camera 1 finds its targets `offset_px` right of the truth.
void write_groups(const ScratchDir& dir, double offset_px) {
  std::string lines;
  for (int k = 0; k < 4; ++k) {
    nlohmann::json g{
        {"frame", k}, {"complete", true}, {"missing_cameras", nlohmann::json::array()}};
    nlohmann::json blobs0 = nlohmann::json::array(), blobs1 = nlohmann::json::array();
    if (k < 3) {
      blobs0 = {{{"x", 100.02}, {"y", 99.97}, {"area", 50}},
                {{"x", 300}, {"y", 200.03}, {"area", 50}}};
      blobs1 = {{{"x", 120 + offset_px}, {"y", 110}, {"area", 50}},
                {{"x", 637.9}, {"y", 240}, {"area", 20}}};  // cut by the border
    }
    g["cameras"] = {{"0", {{"processing_us", 150}, {"blobs", blobs0}}},
                    {"1", {{"processing_us", 170}, {"blobs", blobs1}}}};
    lines += g.dump() + "\n";
  }
  dir.write("groups.jsonl", lines);
}

std::string arguments(const ScratchDir& dir) {
  return "--truth " + dir.path().string() + " --groups " + (dir.path() / "groups.jsonl").string();
}

TEST(Program, PassesOnGoodData) {
  ScratchDir dir;
  write_truth(dir);
  write_groups(dir, 0.05);
  const ProgramRun run =
      run_compare(arguments(dir) + " --json " + (dir.path() / "r.json").string());
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_EQ(last_line(run.output), "PASS") << run.output;
  EXPECT_NE(run.output.find("frames: 4/4 truth frames at the host, 4 complete"), std::string::npos)
      << run.output;
  const auto report = nlohmann::json::parse(std::ifstream(dir.path() / "r.json"));
  EXPECT_TRUE(report["pass"].get<bool>());
  EXPECT_EQ(report["cameras"][1]["counted"]["targets"], 3);
  EXPECT_EQ(report["cameras"][1]["border"]["matched"], 3);
  EXPECT_NEAR(report["cameras"][1]["counted"]["bias_x_px"].get<double>(), 0.05, 1e-9);
  EXPECT_EQ(report["phases"][1]["type"], "led");
}

TEST(Program, FailsNamingTheReason) {
  ScratchDir dir;
  write_truth(dir);
  write_groups(dir, 0.2);
  const ProgramRun run = run_compare(arguments(dir));
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_EQ(last_line(run.output), "FAIL: camera 1: RMS 0.2000 px > 0.1000 px") << run.output;
  // A looser limit passes the same data.
  EXPECT_EQ(run_compare(arguments(dir) + " --max-rms-px 0.25").exit_code, 0);
}

TEST(Program, RejectsUnusableInputNamingFileAndLine) {
  ScratchDir dir;
  write_truth(dir);
  dir.write("groups.jsonl", "{\"frame\":0,\"complete\":true,\"cameras\":{}}\n{oops\n");
  const ProgramRun run = run_compare(arguments(dir));
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.output.find("groups.jsonl:2: not JSON"), std::string::npos) << run.output;
  dir.write("truth/projections.csv", "frame,camera,target,x_px,y_px,radius_px,visible\n0,0,0,1\n");
  const ProgramRun bad_truth = run_compare(arguments(dir));
  EXPECT_EQ(bad_truth.exit_code, 2);
  EXPECT_NE(bad_truth.output.find("projections.csv:2: expected 7 fields, got 4"), std::string::npos)
      << bad_truth.output;
}

TEST(Program, RejectsBadOptions) {
  EXPECT_EQ(run_compare("--truth x").exit_code, 2);
  // Each bad value is named with its option.
  const std::vector<std::pair<std::string, std::string>> bad = {{"--max-rms-px", "fast"},
                                                                {"--min-detection", "98"},
                                                                {"--min-iou", "nan"},
                                                                {"--max-ghosts", "-1"},
                                                                {"--max-reprojection-px", "inf"}};
  for (const auto& [option, value] : bad) {
    const ProgramRun run = run_compare("--truth x --groups y " + option + " " + value);
    EXPECT_EQ(run.exit_code, 2) << option << ' ' << value;
    EXPECT_NE(run.output.find(option + ": '" + value + "'"), std::string::npos) << run.output;
  }
}

// The ring scene's truth and the host's lines written as files: every blob's rays meet at its
// target moved by `shift`, every marker lies `marker_offset` from its target.
void write_ring(const ScratchDir& dir, const Eigen::Vector3d& shift,
                const Eigen::Vector3d& marker_offset) {
  testing::RingScene scene;
  std::vector<sensor::CameraModel> cameras;
  for (const auto& [id, camera] : scene.truth.cameras) cameras.push_back(camera);
  sensor::write_cameras(dir.path() / "cameras.json", cameras);
  std::string frames = "frame,time_s,phase,phase_type,led_on,gain\n";
  std::string targets = "frame,target,X_mm,Y_mm,Z_mm,radius_mm\n";
  std::string rows = "frame,camera,target,x_px,y_px,radius_px,visible\n";
  for (const auto& [f, frame] : scene.truth.frames) {
    frames += std::to_string(f) + "," + std::to_string(frame.time_s) + ",0,wand,0,1\n";
    for (const auto& [t, p] : scene.positions.at(f)) {
      targets += util::printf_string("%ld,%d,%.9f,%.9f,%.9f,%g\n", f, t, p[0], p[1], p[2],
                                     testing::RingScene::kRadiusMm);
    }
    for (const auto& [id, camera] : scene.truth.cameras) {
      for (const Projection& p : scene.truth.projections.at({f, id})) {
        rows += util::printf_string("%ld,%d,%d,%.9f,%.9f,%.9f,1\n", f, id, p.target, p.x_px, p.y_px,
                                    p.radius_px);
      }
    }
  }
  dir.write("truth/frames.csv", frames);
  dir.write("truth/targets.csv", targets);
  dir.write("truth/projections.csv", rows);
  std::string lines;
  for (const Group& g : scene.groups(shift, marker_offset)) {
    nlohmann::json j{
        {"frame", g.frame}, {"complete", true}, {"missing_cameras", nlohmann::json::array()}};
    for (const auto& [id, camera] : g.cameras) {
      nlohmann::json blobs = nlohmann::json::array();
      for (const Blob& b : camera.blobs)
        blobs.push_back({{"x", b.x}, {"y", b.y}, {"area", b.area}});
      j["cameras"][std::to_string(id)] = {{"processing_us", 100}, {"blobs", blobs}};
    }
    j["markers"] = nlohmann::json::array();
    for (const Marker& m : *g.markers) {
      j["markers"].push_back(
          {{"cameras", {0, 1, 2, 3}}, {"id", m.id}, {"x", m.x}, {"y", m.y}, {"z", m.z}});
    }
    lines += j.dump() + "\n";
  }
  dir.write("groups.jsonl", lines);
}

// The markers' reference end to end: printed, in --json, and the optional limit on the ratio.
TEST(Program, PrintsTheMarkersReferenceAndJudgesTheRatioWhenAsked) {
  ScratchDir dir;
  const Eigen::Vector3d shift(0.2, -0.1, 0.15);
  write_ring(dir, shift, {0, 0.5, 0});
  const std::string args = arguments(dir) + " --max-rms-px 1 --max-marker-rms-mm 1";
  const ProgramRun run = run_compare(args + " --json " + (dir.path() / "r.json").string());
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("3D RMS 0.500 mm, best estimator on the same whole views 0.269 mm "
                            "(the host 0.500 mm on those 8 targets, ratio 1.86; 0 with fewer "
                            "than 2 whole views; their 28 blobs' 2D RMS"),
            std::string::npos)
      << run.output;
  const auto report = nlohmann::json::parse(std::ifstream(dir.path() / "r.json"));
  const auto& markers = report["markers"];
  EXPECT_NEAR(markers["reference_rms_mm"].get<double>(), shift.norm(), 1e-5);
  EXPECT_NEAR(markers["rms_over_reference"].get<double>(), 0.5 / shift.norm(), 1e-4);
  EXPECT_EQ(markers["reference_targets"], 8);
  EXPECT_EQ(markers["targets_without_reference"], 0);
  EXPECT_TRUE(markers["pass"].get<bool>());
  EXPECT_TRUE(markers["limits"]["max_rms_over_reference"].is_null());
  const ProgramRun strict = run_compare(args + " --max-rms-over-reference 1.5");
  EXPECT_EQ(strict.exit_code, 1) << strict.output;
  EXPECT_NE(strict.output.find("FAIL: markers (found >= 0.995, ghosts <= 0.005, 3D RMS <= 1 mm, "
                               "3D RMS / best estimator's on the same whole views <= 1.5)"),
            std::string::npos)
      << strict.output;
  EXPECT_EQ(run_compare(args + " --max-rms-over-reference 2").exit_code, 0);
}

// --help: both forms and every option with its meaning and default.
TEST(Program, HelpIsComplete) {
  const ProgramRun run = run_compare("--help");
  EXPECT_EQ(run.exit_code, 0);
  syncap::test::expect_help_mentions(run.output, {"syncap-hil-compare --truth DIR --groups FILE",
                                                  "syncap-hil-compare --truth DIR --calibration",
                                                  "--truth DIR",
                                                  "--groups FILE",
                                                  "--json FILE",
                                                  "--max-rms-px PX",
                                                  "(0.1)",
                                                  "--min-detection SHARE",
                                                  "(0.98)",
                                                  "--match-radius-px PX",
                                                  "(3)",
                                                  "--min-frames SHARE",
                                                  "(0.99)",
                                                  "--min-iou SHARE",
                                                  "(0.95)",
                                                  "--require-silhouettes",
                                                  "--marker-radius-mm MM",
                                                  "(5)",
                                                  "--min-markers-found SHARE",
                                                  "(0.995)",
                                                  "--max-ghosts SHARE",
                                                  "(0.005)",
                                                  "--max-marker-rms-mm MM",
                                                  "(0.5)",
                                                  "--max-rms-over-reference R",
                                                  "(0: not checked)",
                                                  "--calibration FILE",
                                                  "--max-reprojection-px PX",
                                                  "Both --groups and --calibration",
                                                  "exit 0 PASS, 1 FAIL, 2 unusable inputs"});
}

// Issue 15: an unknown last option said "needs a value".
TEST(Program, UnknownOptionIsNamedAsUnknownWherever) {
  for (const char* arguments : {"--truth x --groups y --x", "--x 1 --truth x --groups y"}) {
    const ProgramRun run = run_compare(arguments);
    EXPECT_EQ(run.exit_code, 2) << arguments;
    EXPECT_EQ(run.output.rfind("syncap-hil-compare: unknown option '--x'\n", 0), 0u)
        << arguments << "\n"
        << run.output;
  }
}

}  // namespace
}  // namespace syncap::compare
