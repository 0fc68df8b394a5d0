// syncap-sim end to end: what it writes is deterministic, its truth projections are the camera
// model's, and its person silhouettes are exact.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "camera_rig.hpp"
#include "help_check.hpp"
#include "program_run.hpp"
#include "render.hpp"
#include "scenario.hpp"
#include "sensor/camera_file.hpp"

namespace syncap::sim {
namespace {

namespace fs = std::filesystem;

const char* kWandAndRoom = R"(
name: tiny-wand
seed: 5
frame_rate_hz: 25
cameras:
  count: 3
  layout: half_circle
  arc_deg: 120
  radius_mm: 3500
  height_mm: 2000
  width_px: 320
  height_px: 240
  pixel_size_mm: 0.012
  c_mm: 4.0
  k1: 4.0e-3
  p1: 2.0e-5
  sh: 1.0e-4
image: {noise_sigma_dn: 2.0, drift: 0.05, flicker_hz: 100, flicker_amplitude: 0.02}
phases:
  - {type: wand, frames: 12, target_offsets_mm: [0, 300, 800], exposure_ms: 5}
  - {type: led, frames: 6, on_frames: 2, off_frames: 1}
  - {type: room, frames: 3}
)";

class SimOutput : public ::testing::Test {
 protected:
  static fs::path run_sim(const std::string& scenario_text, const std::string& tag) {
    const fs::path dir =
        fs::temp_directory_path() / ("syncap_sim_" + tag + "_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    std::ofstream(dir / "scenario.yaml") << scenario_text;
    const std::string command = std::string(SYNCAP_SIM_EXE) + " --quiet --scenario " +
                                (dir / "scenario.yaml").string() + " --out " +
                                (dir / "out").string();
    EXPECT_EQ(std::system(command.c_str()), 0) << command;
    return dir / "out";
  }
  static std::string read(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
};

TEST_F(SimOutput, TruthProjectionsAreTheCameraModels) {
  const fs::path out = run_sim(kWandAndRoom, "proj");
  const auto cameras = sensor::read_cameras(out / "cameras.json");
  ASSERT_EQ(cameras.size(), 3u);
  // targets.csv: frame,target,X,Y,Z,r ; projections.csv: frame,camera,target,x,y,r,visible
  std::map<std::pair<int, int>, Eigen::Vector3d> targets;
  std::ifstream t(out / "truth" / "targets.csv");
  std::string line;
  std::getline(t, line);
  while (std::getline(t, line)) {
    int frame, target;
    double x, y, z, r;
    char c;
    std::istringstream(line) >> frame >> c >> target >> c >> x >> c >> y >> c >> z >> c >> r;
    targets[{frame, target}] = {x, y, z};
  }
  EXPECT_EQ(targets.size(), 12u * 3 + 4u);  // LED on in 4 of its 6 frames
  std::ifstream p(out / "truth" / "projections.csv");
  std::getline(p, line);
  int checked = 0;
  while (std::getline(p, line)) {
    int frame, camera, target, visible;
    double x, y, r;
    char c;
    std::istringstream(line) >> frame >> c >> camera >> c >> target >> c >> x >> c >> y >> c >> r >>
        c >> visible;
    const auto projected =
        cameras[static_cast<std::size_t>(camera)].project(targets.at({frame, target}));
    ASSERT_TRUE(projected.ok());
    EXPECT_NEAR(projected.pixel.x(), x, 1e-6);
    EXPECT_NEAR(projected.pixel.y(), y, 1e-6);
    ++checked;
  }
  EXPECT_EQ(checked, 3 * (12 * 3 + 4));
}

TEST_F(SimOutput, SameScenarioSameBytes) {
  const fs::path a = run_sim(kWandAndRoom, "a");
  const fs::path b = run_sim(kWandAndRoom, "b");
  for (const char* file : {"camera00/frame_000000.pgm", "camera02/frame_000011.pgm",
                           "camera01/frame_000020.pgm", "truth/projections.csv", "cameras.json"}) {
    EXPECT_EQ(read(a / file), read(b / file)) << file;
  }
  EXPECT_NE(read(a / "camera00/frame_000000.pgm"), read(a / "camera00/frame_000001.pgm"));
}

TEST_F(SimOutput, EveryFrameOfEveryCameraIsWritten) {
  const fs::path out = run_sim(kWandAndRoom, "count");
  for (int c = 0; c < 3; ++c) {
    int images = 0;
    for (const auto& e : fs::directory_iterator(out / ("camera0" + std::to_string(c))))
      images += e.path().extension() == ".pgm";
    EXPECT_EQ(images, 21);
    const cv::Mat first =
        cv::imread((out / ("camera0" + std::to_string(c)) / "frame_000000.pgm").string(),
                   cv::IMREAD_UNCHANGED);
    EXPECT_EQ(first.cols, 320);
    EXPECT_EQ(first.type(), CV_8UC1);
  }
}

TEST_F(SimOutput, BrokenScenarioIsReportedWithFileAndLine) {
  const fs::path dir =
      fs::temp_directory_path() / ("syncap_sim_broken_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "bad.yaml") << "cameras: {count: 2}\nphases:\n  - {type: wand, frames: 0}\n";
  const std::string command = std::string(SYNCAP_SIM_EXE) + " --scenario " +
                              (dir / "bad.yaml").string() + " --out " + (dir / "out").string() +
                              " 2> " + (dir / "err.txt").string();
  EXPECT_NE(std::system(command.c_str()), 0);
  EXPECT_NE(read(dir / "err.txt").find("bad.yaml:3: phases[0].frames = 0 is outside"),
            std::string::npos)
      << read(dir / "err.txt");
}

// Issue 15: the README's `syncap sim --scenario hil/scenarios/ring-6cam-person.yaml` failed
// (exit 1) unless SYNCAP_DATA was set, and the error did not mention it.
TEST_F(SimOutput, MissingMotionNamesSyncapDataAndThePathTriedAndExitsTwo) {
  const fs::path dir =
      fs::temp_directory_path() / ("syncap_sim_nomotion_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "person.yaml")
      << "cameras: {count: 1}\nphases:\n  - {type: person, frames: 1, bvh: motion/none.bvh}\n";
  const std::string command = "SYNCAP_DATA=/nonexistent-data " + std::string(SYNCAP_SIM_EXE) +
                              " --scenario " + (dir / "person.yaml").string() + " --out " +
                              (dir / "out").string() + " 2> " + (dir / "err.txt").string();
  const int status = std::system(command.c_str());
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 2) << status;
  const std::string err = read(dir / "err.txt");
  EXPECT_NE(err.find("$SYNCAP_DATA (/nonexistent-data/motion/none.bvh)"), std::string::npos) << err;
  EXPECT_NE(err.find("set SYNCAP_DATA"), std::string::npos) << err;
  fs::remove_all(dir);
}

// A mocap phase from a TRC file beside the scenario: marker_names.csv names every target, and a
// marker absent in a frame (B's gap in the second sample) has no rows that frame while the
// others keep their numbers.
TEST_F(SimOutput, MocapPhaseWritesMarkerNamesAndLeavesOutAbsentMarkers) {
  const fs::path dir = fs::temp_directory_path() / ("syncap_sim_trc_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "walk.trc") << "PathFileType\t4\t(X/Y/Z)\twalk.trc\n"
                                     "DataRate\tCameraRate\tNumFrames\tNumMarkers\tUnits\n"
                                     "10\t10\t3\t3\tmm\n"
                                     "Frame#\tTime\tA\t\t\tB\t\t\tC\t\t\n"
                                     "\t\tX1\tY1\tZ1\tX2\tY2\tZ2\tX3\tY3\tZ3\n\n"
                                     "1\t0\t0\t0\t1000\t100\t0\t1000\t0\t100\t1200\n"
                                     "2\t0.1\t10\t0\t1000\t\t\t\t10\t100\t1200\n"
                                     "3\t0.2\t20\t0\t1000\t120\t0\t1000\t20\t100\t1200\n";
  const fs::path out = run_sim(
      "cameras: {count: 2, width_px: 160, height_px: 120, pixel_size_mm: 0.02}\n"
      "frame_rate_hz: 10\n"
      "phases:\n"
      "  - {type: wand, frames: 2}\n"
      "  - type: mocap\n"
      "    frames: 3\n"
      "    trajectories: " +
          (dir / "walk.trc").string() +
          "\n"
          "    extra_markers: [{near: A, towards: C, distance_mm: 25}]\n",
      "mocap");
  EXPECT_EQ(read(out / "truth" / "marker_names.csv"),
            "phase,target,name\n1,0,A\n1,1,B\n1,2,C\n1,3,A+25mm>C\n");
  std::ifstream t(out / "truth" / "targets.csv");
  std::string line;
  std::getline(t, line);
  std::map<int, std::vector<int>> per_frame;
  while (std::getline(t, line)) {
    int frame = 0, target = 0;
    char c;
    std::istringstream(line) >> frame >> c >> target;
    per_frame[frame].push_back(target);
  }
  EXPECT_EQ(per_frame[2], (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(per_frame[3], (std::vector<int>{0, 2, 3}));
  EXPECT_EQ(per_frame[4], (std::vector<int>{0, 1, 2, 3}));
  fs::remove_all(dir);
}

TEST(SimOptions, BadValuesAreUsageErrorsNamingOptionAndValue) {
  for (const std::string value : {"0", "2xyz", "nan", "1.5"}) {
    const auto run = syncap::test::run_program(
        std::string(SYNCAP_SIM_EXE) + " --scenario s.yaml --out o --max-phase-frames " + value);
    EXPECT_EQ(run.exit_code, 2) << value;
    EXPECT_NE(run.output.find("--max-phase-frames: '" + value + "'"), std::string::npos)
        << run.output;
  }
  const auto missing = syncap::test::run_program(std::string(SYNCAP_SIM_EXE) + " --out o");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.output.find("--scenario is required"), std::string::npos) << missing.output;
}

TEST(SimOptions, HelpIsComplete) {
  const auto run = syncap::test::run_program(std::string(SYNCAP_SIM_EXE) + " --help");
  EXPECT_EQ(run.exit_code, 0);
  syncap::test::expect_help_mentions(
      run.output, {"--scenario FILE", "scenario (YAML", "--out DIR", "cameras.json",
                   "--max-phase-frames N", "--quiet", "$SYNCAP_DATA", "Exit status: 0"});
}

}  // namespace
}  // namespace syncap::sim
