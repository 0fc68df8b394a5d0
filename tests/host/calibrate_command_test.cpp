// `syncap calibrate` run in-process: a simulated wand recording as CSV (frame,camera,x,y) in,
// the calibration folder out; usage errors name the option.
#include "calibrate_command.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "calibration/simulated_observations.hpp"
#include "estimators/bundle_adjustment_simulation.hpp"
#include "help_check.hpp"
#include "io/lcm_log_reader.hpp"
#include "malformed_messages.hpp"
#include "sensor/camera_file.hpp"
#include "subcommand.hpp"
#include "syncap/proto/channels.hpp"

namespace syncap::tools {
namespace {

namespace fs = std::filesystem;

int run(const std::vector<std::string>& args, std::string& out, std::string& err) {
  std::ostringstream o, e;
  const int status = calibrate_command(args, o, e);
  out = o.str();
  err = e.str();
  return status;
}

// A simulated network's measurements as the CSV `syncap calibrate --input csv:` reads.
void write_csv(const fs::path& file, const scene::Network& network) {
  std::ofstream csv(file);
  csv << "frame,camera,x,y\n";
  for (const auto& m : network.measurements) {
    csv << m.frame_number << ',' << m.station.substr(6) << ',' << m.u << ',' << m.v << '\n';
  }
}

TEST(CalibrateCommand, CsvWandRecordingGivesTheCalibrationFolder) {
  const fs::path dir = fs::temp_directory_path() / ("syncap-calcmd-" + std::to_string(getpid()));
  fs::create_directories(dir);
  estimators::WandSimulation sim;
  sim.frames = 60;
  const auto net = estimators::simulate_wand_network(sim);
  write_csv(dir / "wand.csv", net.network);
  // A CSV carries no image sizes: without --image-size the camera is named.
  std::string out, err;
  EXPECT_EQ(run({"--input", "csv:" + (dir / "wand.csv").string(), "--wand-length-mm", "1000",
                 "--out", (dir / "out").string()},
                out, err),
            kExitReportedErrors);
  EXPECT_NE(err.find("camera 0 of csv:"), std::string::npos) << err;
  EXPECT_NE(err.find("has no image size"), std::string::npos) << err;

  EXPECT_EQ(run({"--input", "csv:" + (dir / "wand.csv").string(), "--wand-length-mm", "1000",
                 "--image-size", "1280x1024", "--pixel-size", "0.0067", "--sigma-px", "0.2",
                 "--out", (dir / "out").string()},
                out, err),
            kExitOk)
      << err;
  EXPECT_NE(out.find("calibrated 3 cameras"), std::string::npos) << out;
  // Issue 37: progress on stderr by default, also when it is no terminal (a string here).
  EXPECT_NE(err.find("syncap calibrate: observations: 60 frames"), std::string::npos) << err;
  EXPECT_NE(err.find("syncap calibrate: verdict: "), std::string::npos) << err;
  std::string quiet_err;
  EXPECT_EQ(run({"--input", "csv:" + (dir / "wand.csv").string(), "--wand-length-mm", "1000",
                 "--image-size", "1280x1024", "--pixel-size", "0.0067", "--sigma-px", "0.2",
                 "--out", (dir / "out").string(), "--quiet"},
                out, quiet_err),
            kExitOk);
  EXPECT_EQ(quiet_err.find("observations:"), std::string::npos) << quiet_err;
  for (const char* file : {"cameras.json", "report.txt", "report.html", "residuals.csv",
                           "points.csv", "cameras.opencv.yaml", "calibration.toml"}) {
    EXPECT_TRUE(fs::exists(dir / "out" / file)) << file;
  }
  const sensor::CameraSet set = sensor::read_camera_set(dir / "out" / "cameras.json");
  ASSERT_EQ(set.cameras.size(), 3u);
  ASSERT_TRUE(set.quality.has_value());
  EXPECT_NEAR(set.quality->sigma0_px, 0.2, 0.04);
  EXPECT_NEAR(*set.quality->wand_length_mean_mm, 1000.0, 0.5);
  EXPECT_NEAR(set.cameras[0].interior.c, 6.0, 0.03);
  fs::remove_all(dir);
}

// The weak LED replica (tests/host/calibration/simulated_observations.hpp) as CSV: by default
// the verdict is good and the exit status 0; the old way (--model all from 60 degrees alone) ends
// (and the principal point held as loosely as before) in a wrong minimum that the checks call
// failed: exit status 1, the files written, the verdict
// in cameras.json and at the top of report.txt.
TEST(CalibrateCommand, AFailedVerdictExitsWithStatusOne) {
  const fs::path dir =
      fs::temp_directory_path() / ("syncap-calverdict-" + std::to_string(getpid()));
  fs::create_directories(dir);
  const auto net = estimators::simulate_wand_network(calibration::weak_led_network(400, 11));
  write_csv(dir / "led.csv", net.network);
  const std::vector<std::string> common{"--input", "csv:" + (dir / "led.csv").string(),
                                        "--led",   "--image-size",
                                        "659x494", "--pixel-size",
                                        "0.0074",  "--sigma-px",
                                        "0.15"};
  std::vector<std::string> old_way = common;
  old_way.insert(old_way.end(), {"--model", "all", "--start-fovs", "none",
                                 "--principal-point-sigma", "0", "--out", (dir / "old").string()});
  std::string out, err;
  EXPECT_EQ(run(old_way, out, err), kExitReportedErrors) << out << err;
  EXPECT_NE(err.find("the calibration failed its checks"), std::string::npos) << err;
  EXPECT_NE(out.find("verdict: failed"), std::string::npos) << out;
  EXPECT_EQ(sensor::read_camera_set(dir / "old" / "cameras.json").quality->verdict, "failed");
  std::ifstream report(dir / "old" / "report.txt");
  std::string title, rule, verdict;
  std::getline(report, title);
  std::getline(report, rule);
  std::getline(report, verdict);
  EXPECT_EQ(verdict, "verdict: failed");

  std::vector<std::string> by_default = common;
  by_default.insert(by_default.end(), {"--out", (dir / "new").string()});
  EXPECT_EQ(run(by_default, out, err), kExitOk) << out << err;
  const sensor::CameraSet set = sensor::read_camera_set(dir / "new" / "cameras.json");
  EXPECT_EQ(set.quality->verdict, "good");
  EXPECT_TRUE(set.quality->verdict_reasons.empty());
  fs::remove_all(dir);
}

TEST(CalibrateCommand, UsageErrorsNameTheOption) {
  std::string out, err;
  EXPECT_EQ(run({"--input", "csv:x.csv", "--out", "d"}, out, err), kExitUsage);
  EXPECT_NE(err.find("give exactly one of --wand-length-mm MM and --led"), std::string::npos);
  EXPECT_EQ(run({"--input", "tcp:x", "--led", "--out", "d"}, out, err), kExitUsage);
  EXPECT_NE(err.find("unknown source 'tcp'"), std::string::npos) << err;
  EXPECT_EQ(run({"--input", "csv:x", "--led", "--out", "d", "--interior", "c,q"}, out, err),
            kExitUsage);
  EXPECT_NE(err.find("--interior: 'q' is not one of"), std::string::npos);
  EXPECT_EQ(run({"--input", "csv:x", "--led", "--out", "d", "--model", "some"}, out, err),
            kExitUsage);
  EXPECT_NE(err.find("--model: 'some' is not one of auto, all"), std::string::npos) << err;
  EXPECT_EQ(run({"--input", "csv:x", "--led", "--out", "d", "--start-fovs", "40,x"}, out, err),
            kExitUsage);
  EXPECT_NE(err.find("--start-fovs: 'x' is not a number"), std::string::npos) << err;
  EXPECT_EQ(run({"--input", "csv:x", "--led", "--out", "d", "--check-share", "0.7"}, out, err),
            kExitUsage);
  EXPECT_NE(err.find("--check-share: '0.7' is not a number in [0, 0.5]"), std::string::npos) << err;
  EXPECT_EQ(
      run({"--input", "lcm:udpm://239.255.76.67:7667?ttl=0", "--led", "--out", "d"}, out, err),
      kExitUsage);
  EXPECT_NE(err.find("lcm: needs --camera-ids"), std::string::npos) << err;
  EXPECT_EQ(run({"--input", "csv:x", "--led", "--out", "d", "--bogus"}, out, err), kExitUsage);
  EXPECT_NE(err.find("unknown option '--bogus'"), std::string::npos) << err;
  EXPECT_EQ(run({"--input", "csv:x", "--led", "--out", "d", "--k", "nan"}, out, err), kExitUsage);
  EXPECT_NE(err.find("unknown option '--k'"), std::string::npos) << err;
  EXPECT_EQ(run({"--led", "--out", "d"}, out, err), kExitUsage);
  EXPECT_NE(err.find("--input is required"), std::string::npos) << err;
}

// Not finite, not whole, not in range, trailing junk: each named with its option and value.
TEST(CalibrateCommand, BadNumbersAreUsageErrorsNamingOptionAndValue) {
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"--wand-ratio", "nan"},     {"--sigma-px", "inf"},
      {"--pixel-size", "0"},       {"--fov", "60deg"},
      {"--wand-targets", "4"},     {"--wand-targets", "2.5"},
      {"--frames", "-1"},          {"--bootstrap", "1.5"},
      {"--idle-timeout-s", "nan"}, {"--camera-ids", "100"},
      {"--image-size", "640x"},    {"--scale-from", "0,0,100"},
      {"--wand-ends", "color"},    {"--principal-point-sigma", "-1"}};
  for (const auto& [option, value] : bad) {
    std::string out, err;
    EXPECT_EQ(run({"--input", "csv:x", "--led", "--out", "d", option, value}, out, err), kExitUsage)
        << option << ' ' << value;
    EXPECT_NE(err.find(option + ": '"), std::string::npos) << err;
    EXPECT_NE(err.find(value), std::string::npos) << err;
  }
}

// --help lists every option with its meaning and default, the sources and the exit statuses.
TEST(CalibrateCommand, HelpIsComplete) {
  std::string out, err;
  EXPECT_EQ(run({"--help"}, out, err), kExitOk);
  EXPECT_EQ(err, "");
  syncap::test::expect_help_mentions(out, {"usage: syncap calibrate",
                                           "lcm:URL",
                                           "lcmlog:FILE",
                                           "csv:FILE",
                                           "mcsc:DIR",
                                           "--input SOURCE",
                                           "--out-dir DIR",
                                           "--wand-length-mm MM",
                                           "--led",
                                           "--scale-from A,B,MM",
                                           "--wand-targets N",
                                           "(default 3)",
                                           "--wand-ratio R",
                                           "(default 0.4)",
                                           "--wand-ends size|continuity",
                                           "--pixel-size MM",
                                           "(default 0.005",
                                           "--image-size WxH",
                                           "--fov DEG",
                                           "(default 60)",
                                           "--start-fovs LIST",
                                           "40,50,60,70,80,90,100",
                                           "--principal-point-sigma S",
                                           "--check-share S",
                                           "(default 0.1",
                                           "--interior LIST",
                                           "--shared-interior",
                                           "--model auto|all",
                                           "--sigma-px PX",
                                           "(0.1)",
                                           "--wand-sigma MM",
                                           "(0.2)",
                                           "--critical-w W",
                                           "(3.29)",
                                           "--max-frames N",
                                           "--bootstrap N",
                                           "--camera-ids LIST",
                                           "--frame-range A-B",
                                           "--frames N",
                                           "--idle-timeout-s S",
                                           "(default 5)",
                                           "--quiet",
                                           "Exit status: 0 calibrated"});
}

// Issue 15: one record whose num_blobs reads -1 made the decoder throw, and `syncap calibrate`
// dropped the whole log ("vector::_M_default_append", exit 2). Now it is skipped and named.
// The simulated wand network's measurements as blob frames, by (frame, camera).
std::map<std::pair<int64_t, int>, blob_frame_t> blob_frames_of(const scene::Network& network) {
  std::map<std::pair<int64_t, int>, blob_frame_t> frames;
  for (const auto& m : network.measurements) {
    const int camera = std::stoi(m.station.substr(6));
    blob_frame_t& f = frames[{m.frame_number, camera}];
    f.camera_id = static_cast<int16_t>(camera);
    f.frame_number = m.frame_number;
    f.image_width = 1280;
    f.image_height = 1024;
    f.part_count = 1;
    blob_t blob{};
    blob.x = static_cast<float>(m.u);
    blob.y = static_cast<float>(m.v);
    f.blobs.push_back(blob);
    f.num_blobs = f.total_blobs = static_cast<int16_t>(f.blobs.size());
  }
  return frames;
}

void write_log(const fs::path& file,
               const std::map<std::pair<int64_t, int>, blob_frame_t>& frames) {
  std::vector<std::uint8_t> log;
  std::int64_t event = 0;
  for (const auto& [key, frame] : frames) {
    const auto record =
        io::encode_log_record(event++, 0, proto::blob_channel(key.second), test::encoded(frame));
    log.insert(log.end(), record.begin(), record.end());
  }
  std::ofstream out(file, std::ios::binary);
  out.write(reinterpret_cast<const char*>(log.data()), static_cast<std::streamsize>(log.size()));
}

std::string observations_in(const std::string& summary) {
  const auto end = summary.find(" observations");
  const auto start = summary.rfind(", ", end);
  return end == std::string::npos || start == std::string::npos
             ? "?"
             : summary.substr(start + 2, end - start - 2);
}

// A session's log holds the wand phase and then the capture. Here the capture (frames 60-99)
// shows three collinear spots per camera, as a wand would, but camera 0's are 40 px off: taken
// in, they change the calibration. --frame-range takes the wand phase alone, as if it were the log.
TEST(CalibrateCommand, FrameRangeTakesTheWandPhaseOfASessionsLog) {
  const fs::path dir = fs::temp_directory_path() / ("syncap-calrange-" + std::to_string(getpid()));
  fs::create_directories(dir);
  estimators::WandSimulation sim;
  sim.frames = 60;
  auto frames = blob_frames_of(estimators::simulate_wand_network(sim).network);
  write_log(dir / "wand.lcmlog", frames);
  for (int64_t frame = 60; frame < 100; ++frame) {
    for (int camera = 0; camera < 3; ++camera) {
      blob_frame_t f = frames.at({frame - 60, camera});
      f.frame_number = frame;
      for (blob_t& blob : f.blobs) blob.x += camera == 0 ? 40.0f : 0.0f;
      frames[{frame, camera}] = f;
    }
  }
  write_log(dir / "session.lcmlog", frames);
  const std::vector<std::string> common = {"--wand-length-mm", "1000", "--pixel-size",  "0.0067",
                                           "--sigma-px",       "0.2",  "--check-share", "0"};
  auto summary = [&](const std::string& log, const std::string& out_dir,
                     std::vector<std::string> more) {
    std::vector<std::string> a = {"--input", "lcmlog:" + (dir / log).string(), "--out",
                                  (dir / out_dir).string()};
    a.insert(a.end(), common.begin(), common.end());
    a.insert(a.end(), more.begin(), more.end());
    std::string out, err;
    run(a, out, err);
    return out.substr(0, out.find('\n'));
  };
  const std::string wand = summary("wand.lcmlog", "wand", {});
  const std::string ranged = summary("session.lcmlog", "ranged", {"--frame-range", "0-59"});
  const std::string whole = summary("session.lcmlog", "whole", {});
  EXPECT_NE(observations_in(wand), "?") << wand;
  EXPECT_EQ(ranged, wand);
  EXPECT_NE(whole, wand);  // the capture's spots were taken in
  EXPECT_NE(observations_in(whole), observations_in(wand)) << whole;
  fs::remove_all(dir);
}

TEST(CalibrateCommand, ABrokenFrameRangeIsAUsageError) {
  std::string out, err;
  for (const std::string range : {"5-2", "abc", "-", "3", "1.5-4"}) {
    EXPECT_EQ(run({"--input", "lcmlog:x", "--led", "--out", "d", "--frame-range", range}, out, err),
              kExitUsage)
        << range;
    EXPECT_NE(err.find("--frame-range"), std::string::npos) << err;
  }
}

TEST(CalibrateCommand, MalformedLogRecordIsSkippedAndTheRestCalibrates) {
  const fs::path dir = fs::temp_directory_path() / ("syncap-callog-" + std::to_string(getpid()));
  fs::create_directories(dir);
  estimators::WandSimulation sim;
  sim.frames = 60;
  const auto frames = blob_frames_of(estimators::simulate_wand_network(sim).network);
  std::vector<std::uint8_t> log;
  std::int64_t event = 0;
  std::uint64_t bad_offset = 0;
  for (const auto& [key, frame] : frames) {
    if (event == 40) {
      bad_offset = log.size();
      const auto bad =
          io::encode_log_record(event++, 0, proto::blob_channel(key.second),
                                test::blob_frame_with_negative_count(key.second, 1000));
      log.insert(log.end(), bad.begin(), bad.end());
    }
    const auto record =
        io::encode_log_record(event++, 0, proto::blob_channel(key.second), test::encoded(frame));
    log.insert(log.end(), record.begin(), record.end());
  }
  {
    std::ofstream file(dir / "wand.lcmlog", std::ios::binary);
    file.write(reinterpret_cast<const char*>(log.data()), static_cast<std::streamsize>(log.size()));
  }
  std::string out, err;
  EXPECT_EQ(run({"--input", "lcmlog:" + (dir / "wand.lcmlog").string(), "--wand-length-mm", "1000",
                 "--pixel-size", "0.0067", "--sigma-px", "0.2", "--out", (dir / "out").string()},
                out, err),
            kExitOk)
      << err;
  EXPECT_NE(err.find("event 40 at offset " + std::to_string(bad_offset) + " on SYNCAP_BLOBS_0"),
            std::string::npos)
      << err;
  EXPECT_NE(err.find("1 malformed records skipped"), std::string::npos) << err;
  EXPECT_NE(out.find("calibrated 3 cameras"), std::string::npos) << out;
  fs::remove_all(dir);
}

// Issue 15: --max-frames -5 used all frames; an unwritable --out failed only after the whole
// calibration.
TEST(CalibrateCommand, BadMaxFramesAndUnwritableOutAreUsageErrorsBeforeReading) {
  std::string out, err;
  EXPECT_EQ(run({"--input", "csv:/nonexistent.csv", "--led", "--out", "d", "--max-frames", "-5"},
                out, err),
            kExitUsage);
  EXPECT_NE(err.find("--max-frames: '-5' is not a whole number in [1, "), std::string::npos) << err;
  EXPECT_EQ(
      run({"--input", "csv:/nonexistent.csv", "--led", "--out", "/proc/syncap-out"}, out, err),
      kExitUsage);
  EXPECT_NE(err.find("--out-dir /proc/syncap-out: cannot"), std::string::npos) << err;
  EXPECT_EQ(err.find("nonexistent.csv"), std::string::npos) << "the input was read first: " << err;
}

}  // namespace
}  // namespace syncap::tools
