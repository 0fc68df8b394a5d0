#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "app/edge_options.hpp"
#include "help_check.hpp"

namespace syncap::edge {
namespace {

class EdgeConfigTest : public ::testing::Test {
 protected:
  void SetUp() override {
    file_ = std::filesystem::temp_directory_path() /
            ("syncap_edge_config_" + std::to_string(::getpid()) + "_" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name() + ".yaml");
  }
  void TearDown() override { std::filesystem::remove(file_); }
  void write(const std::string& text) { std::ofstream(file_) << text; }
  // The UsageError's text for these arguments after --config FILE.
  std::string error_of(std::vector<std::string> args = {}) {
    args.insert(args.begin(), {"--config", file_.string()});
    try {
      parse_edge_options(args);
    } catch (const UsageError& e) {
      return e.what();
    }
    return "no error";
  }
  std::filesystem::path file_;
};

TEST_F(EdgeConfigTest, KeysAreTheLongOptions) {
  write(
      "# camera 3 of the lab ring\n"
      "camera-id: 3\n"
      "source: aravis:192.168.1.10\n"
      "mode: both\n"
      "threshold-dn: 200\n"
      "lcm-url: udpm://239.255.76.67:7667?ttl=1\n"
      "train-frames: 30\n"
      "train-from-frame: 100\n"
      "roi: 0,64,1280,896\n"
      "udp-socket: true\n"
      "quiet: false\n"
      "reopen-max-s: 20\n");
  const EdgeOptions o = parse_edge_options({"--config", file_.string()});
  EXPECT_EQ(o.camera_id, 3);
  EXPECT_EQ(o.source, "aravis:192.168.1.10");
  EXPECT_TRUE(o.blobs && o.mask);
  EXPECT_EQ(o.detector.threshold, 200);
  EXPECT_EQ(o.lcm_url, "udpm://239.255.76.67:7667?ttl=1");
  EXPECT_EQ(o.train_frames, 30);
  EXPECT_EQ(o.train_from_frame, 100);
  EXPECT_EQ(o.roi, cv::Rect(0, 64, 1280, 896));
  EXPECT_TRUE(o.udp_socket);
  EXPECT_FALSE(o.quiet);
  EXPECT_DOUBLE_EQ(o.reopen_max_s, 20);
}

TEST_F(EdgeConfigTest, CommandLineOverridesTheFile) {
  write("camera-id: 3\nsource: replay:/tmp/a\nthreshold-dn: 200\n");
  // Before or after --config: the command line wins either way, under an old name too
  // (--threshold for --threshold-dn).
  const EdgeOptions o = parse_edge_options(
      {"--threshold", "90", "--config", file_.string(), "--source", "replay:/tmp/b", "--quiet"});
  EXPECT_EQ(o.camera_id, 3);
  EXPECT_EQ(o.detector.threshold, 90);
  EXPECT_EQ(o.source, "replay:/tmp/b");
  EXPECT_TRUE(o.quiet);
}

// The masking starts from medi-picture's defaults; --mask-* options (or their keys) change them.
TEST_F(EdgeConfigTest, MaskOptionsChangeTheDefaults) {
  write("camera-id: 1\nsource: replay:/tmp/a\nmode: mask\nmask-fill-holes-px: 0\n");
  const EdgeOptions preset = parse_edge_options({"--camera-id", "1", "--source", "replay:/x"});
  EXPECT_EQ(preset.masking.k, segmentation::MediPictureOptions{}.k);
  EXPECT_EQ(preset.masking.shadow_test, segmentation::ShadowTest::kCommonRatio);
  EXPECT_TRUE(preset.masking.correct_illumination);
  const EdgeOptions o = parse_edge_options(
      {"--config", file_.string(), "--mask-k", "2.5", "--mask-shadow-test", "correlation",
       "--mask-ncc", "0.95", "--mask-no-shadows", "--mask-closing-px", "9", "--mask-update-rate",
       "0.01", "--mask-illumination", "off"});
  EXPECT_FLOAT_EQ(o.masking.k, 2.5f);
  EXPECT_EQ(o.masking.shadow_test, segmentation::ShadowTest::kCorrelation);
  EXPECT_FLOAT_EQ(o.masking.ncc_threshold, 0.95f);
  EXPECT_FALSE(o.masking.remove_shadows);
  EXPECT_EQ(o.masking.closing_diameter, 9);
  EXPECT_EQ(o.masking.max_hole_area, 0);  // from the file
  EXPECT_FLOAT_EQ(o.masking.update_rate, 0.01f);
  EXPECT_FALSE(o.masking.correct_illumination);
  EXPECT_EQ(o.masking.min_component_area, segmentation::MediPictureOptions{}.min_component_area);
  write("camera-id: 1\nsource: replay:/x\nmask-shadow-test: ratio\n");
  EXPECT_NE(error_of().find(":3:1: key 'mask-shadow-test': 'ratio': expected correlation or "
                            "common-ratio"),
            std::string::npos)
      << error_of();
}

TEST_F(EdgeConfigTest, ErrorsNameFileLineAndKey) {
  write("camera-id: 3\nsource: replay:/x\n\nthreshold-dn: 300\n");
  EXPECT_EQ(error_of(), "syncap-edge: " + file_.string() +
                            ":4:1: key 'threshold-dn': '300' is not a whole number in [1, 255]");
  write("camera-id: 3\n  thresold: 20\n");
  EXPECT_NE(error_of().find(file_.string() + ":2:"), std::string::npos) << error_of();
  write("camera-id: 3\nsource: replay:/x\nthresold: 20\n");
  EXPECT_EQ(error_of(), "syncap-edge: " + file_.string() +
                            ":3:1: key 'thresold': unknown key (keys are syncap-edge's long "
                            "options)");
  write("camera-id: 3\nsource: [replay:/x]\n");
  EXPECT_EQ(error_of(),
            "syncap-edge: " + file_.string() + ":2:1: key 'source': expected a single value");
  write("camera-id: 3\nsource: replay:/x\nquiet: maybe\n");
  EXPECT_NE(error_of().find(":3:1: key 'quiet' 'maybe': expected true or false"), std::string::npos)
      << error_of();
  write("- camera-id\n");
  EXPECT_NE(error_of().find("expected `key: value` lines"), std::string::npos) << error_of();
  std::filesystem::remove(file_);
  EXPECT_EQ(error_of(), "syncap-edge: --config " + file_.string() + ": cannot be read");
}

// Found by the edge config fuzz target (issue 15): yaml-cpp's BadConversion escaped for a key
// that is not text, and ended syncap-edge with an uncaught exception.
TEST_F(EdgeConfigTest, AKeyThatIsNotTextIsAUsageError) {
  write("camera-id: 3\n[1, 2]: 3\n");
  EXPECT_EQ(error_of(), "syncap-edge: " + file_.string() + ":2:1: a key must be text");
}

TEST_F(EdgeConfigTest, TheFileStillNeedsACameraAndASource) {
  write("threshold-dn: 50\n");
  EXPECT_EQ(error_of(), "syncap-edge: --camera-id is required");
  EXPECT_EQ(error_of({"--camera-id", "1"}),
            "syncap-edge: --source '': expected replay:FOLDER, aravis:ADDRESS or v4l2:DEVICE");
  EXPECT_EQ(error_of({"--camera-id", "1", "--source", "replay:/x"}), "no error");
}

// Every kind of option (number, text, choice, flag, region, masking) set in the file is
// overridden by the command line, wherever --config stands; what the command line leaves is the
// file's.
TEST_F(EdgeConfigTest, TheCommandLineWinsForEveryKindOfOption) {
  write(
      "camera-id: 3\nsource: replay:/tmp/a\nmode: both\ndetection: full\nroi: 0,0,64,64\n"
      "mask-k: 2\ngain-db: 12\nheartbeat-s: 4\nudp-socket: true\nlcm-url: udpm://a\n");
  const EdgeOptions o = parse_edge_options({"--mode", "blobs", "--detection", "windowed", "--roi",
                                            "8,8,32,32", "--mask-k", "1.5", "--gain-db", "6",
                                            "--config", file_.string(), "--camera-id", "4"});
  EXPECT_EQ(o.camera_id, 4);
  EXPECT_TRUE(o.blobs && !o.mask);
  EXPECT_EQ(o.detection, DetectionMode::kWindowed);
  EXPECT_EQ(o.roi, cv::Rect(8, 8, 32, 32));
  EXPECT_FLOAT_EQ(o.masking.k, 1.5f);
  EXPECT_DOUBLE_EQ(o.gain_db, 6);
  EXPECT_DOUBLE_EQ(o.heartbeat_s, 4);  // from the file
  EXPECT_TRUE(o.udp_socket);           // from the file
  EXPECT_EQ(o.lcm_url, "udpm://a");    // from the file
  EXPECT_EQ(o.source, "replay:/tmp/a");
}

// A flag set false in the file stays off; the command line turns it on.
TEST_F(EdgeConfigTest, AFlagOffInTheFileIsOnFromTheCommandLine) {
  write("camera-id: 3\nsource: replay:/tmp/a\nquiet: false\nmask-no-shadows: no\n");
  EXPECT_FALSE(parse_edge_options({"--config", file_.string()}).quiet);
  EXPECT_TRUE(parse_edge_options({"--config", file_.string()}).masking.remove_shadows);
  const EdgeOptions o = parse_edge_options({"--config", file_.string(), "--quiet"});
  EXPECT_TRUE(o.quiet);
}

// A value that starts with a dash is the key's value, not an option.
TEST_F(EdgeConfigTest, AValueThatStartsWithADashIsAValue) {
  write("camera-id: 3\nsource: replay:/tmp/a\ntrigger-source: -Line1\nhelp: true\n");
  EXPECT_EQ(error_of(), "syncap-edge: " + file_.string() +
                            ":4:1: key 'help': unknown key (keys are syncap-edge's long options)");
  write("camera-id: 3\nsource: replay:/tmp/a\ntrigger-source: -Line1\n");
  EXPECT_EQ(parse_edge_options({"--config", file_.string()}).trigger_source, "-Line1");
}

// What edge/systemd/syncap-edge@.service runs with the installed example.
TEST(EdgeConfigExample, TheShippedExampleParses) {
  const std::string example = SYNCAP_SOURCE_DIR "/edge/systemd/edge.yaml.example";
  const EdgeOptions o = parse_edge_options({"--config", example, "--camera-id", "3"});
  EXPECT_EQ(o.camera_id, 3);
  EXPECT_EQ(o.source, "aravis:192.168.1.10");
  EXPECT_EQ(o.trigger_source, "Line1");
  EXPECT_EQ(o.detector.threshold, 200);
  EXPECT_EQ(o.lcm_url, "udpm://239.255.76.67:7667?ttl=1");
}

std::string command_line_error(const std::vector<std::string>& args);

// The rig file's example (docs/guide/rig.md): an edge takes the shared keys it has, the edges:
// section and its camera's entry over it, and passes over the host's and the trigger's parts.
TEST(EdgeConfigExample, TheShippedRigExampleGivesEachEdgeItsPart) {
  const std::string rig = SYNCAP_SOURCE_DIR "/docs/examples/rig-8cam.yaml";
  EdgeOptions o = parse_edge_options({"--config", rig, "--camera-id", "3"});
  EXPECT_EQ(o.camera_id, 3);
  EXPECT_EQ(o.source, "aravis:192.168.1.13");
  EXPECT_EQ(o.exposure_us, 3000);  // its own entry over the edges: section's 2000
  EXPECT_EQ(o.trigger_source, "Line1");
  EXPECT_TRUE(o.blobs && o.mask);
  EXPECT_EQ(o.command_key_path, "/etc/syncap/command.key");
  EXPECT_EQ(o.lcm_url, "udpm://239.255.76.67:7667?ttl=1");
  o = parse_edge_options({"--config", rig, "--camera-id", "6", "--exposure-us", "500"});
  EXPECT_EQ(o.source, "aravis:192.168.1.16");
  EXPECT_EQ(o.exposure_us, 500);
  EXPECT_EQ(command_line_error({"--config", rig}), "syncap-edge: --camera-id is required");
}

std::string command_line_error(const std::vector<std::string>& args) {
  try {
    parse_edge_options(args);
  } catch (const UsageError& e) {
    return e.what();
  }
  return "no error";
}

TEST(EdgeOptions, AnUnknownOptionOrAStrayArgumentIsNamed) {
  EXPECT_EQ(command_line_error({"--camera-id", "1", "--source", "replay:/x", "--thresold", "9"}),
            "syncap-edge: unknown option '--thresold'");
  EXPECT_EQ(command_line_error({"--camera-id", "1", "--source", "replay:/x", "stray"}),
            "syncap-edge: unexpected argument 'stray'");
}

TEST(EdgeOptions, ABackgroundClipNeedsTheMaskAndIsOneWayToTrain) {
  EXPECT_EQ(command_line_error(
                {"--camera-id", "1", "--source", "replay:/x", "--background", "/data/empty.avi"}),
            "syncap-edge: --background needs --mode mask or both");
  EXPECT_EQ(command_line_error({"--camera-id", "1", "--source", "replay:/x", "--mode", "mask",
                                "--background", "/data/empty.avi", "--train-frames", "20",
                                "--train-from-frame", "5"}),
            "syncap-edge: --background and --train-from-frame are two ways to train: give one");
  const EdgeOptions o = parse_edge_options({"--camera-id", "1", "--source", "replay:/x", "--mode",
                                            "mask", "--background", "/data/empty.avi"});
  EXPECT_EQ(o.background, "/data/empty.avi");
}

TEST(EdgeOptions, ABadNumberNamesTheOptionAndTheValue) {
  const std::vector<std::string> camera{"--camera-id", "1", "--source", "replay:/x"};
  const auto error = [&](const std::string& option, const std::string& value) {
    std::vector<std::string> args = camera;
    args.insert(args.end(), {option, value});
    return command_line_error(args);
  };
  EXPECT_EQ(error("--threshold-dn", "12x"),
            "syncap-edge: --threshold-dn: '12x' is not a whole number in [1, 255]");
  EXPECT_EQ(error("--threshold-dn", "010"), "no error");  // decimal, not octal
  EXPECT_EQ(error("--gain-db", "nan"), "syncap-edge: --gain-db: 'nan' is not a number in [0, 100]");
  EXPECT_EQ(error("--reopen-max-s", "0"),
            "syncap-edge: --reopen-max-s: '0' is not a number in [0.01, 3600]");
  EXPECT_EQ(error("--roi", "1,2,3"),
            "syncap-edge: --roi: '1,2,3' is not X,Y,WIDTH,HEIGHT in sensor pixels, each 0..32767");
  EXPECT_EQ(error("--mode", "all"), "syncap-edge: --mode: 'all' is not one of blobs, mask, both");
  EXPECT_NE(error("--mask-closing-px", "-1").find("syncap-edge: --mask-closing-px: '-1': expected"),
            std::string::npos);
}

// --help: every option with its value's name and its default or meaning, the config file, the
// exit statuses.
TEST(EdgeOptions, HelpIsComplete) {
  EXPECT_EQ(command_line_error({"--help"}), "help");
  syncap::test::expect_help_mentions(edge_usage(),
                                     {"usage: syncap-edge --camera-id N --source SPEC",
                                      "syncap-edge --config FILE",
                                      "--config FILE",
                                      "--camera-id N",
                                      "--source SPEC",
                                      "aravis:ADDRESS",
                                      "v4l2:DEVICE",
                                      "--trigger-source S",
                                      "--exposure-us US",
                                      "--gain-db DB",
                                      "--udp-socket",
                                      "--roi X,Y,W,H",
                                      "--detection D",
                                      "--full-scan-every N",
                                      "(default 30)",
                                      "--roi-follows-windows",
                                      "--mode M",
                                      "--train-frames N",
                                      "--train-from-frame F",
                                      "--contour-tolerance-px PX",
                                      "(default 0.5)",
                                      "--mask-k K",
                                      "(default 1)",
                                      "--mask-min-difference-dn D",
                                      "(default 6)",
                                      "--mask-ncc L",
                                      "--mask-shadow-test T",
                                      "(default common-ratio)",
                                      "--mask-shadow-sigmas S",
                                      "--mask-fill-holes-px A",
                                      "(default 100)",
                                      "--mask-closing-px D",
                                      "(default 5)",
                                      "--mask-min-area-px A",
                                      "--mask-update-rate R",
                                      "--mask-no-shadows",
                                      "--threshold-dn DN",
                                      "(default 128)",
                                      "--min-area-px PX",
                                      "(default 2)",
                                      "--max-area-px PX",
                                      "(default 20000)",
                                      "--lcm-url URL",
                                      "udpm://239.255.76.67:7667?ttl=0",
                                      "--command-key FILE",
                                      "--command-window-s S",
                                      "(default 5)",
                                      "--heartbeat-s S",
                                      "(default 1)",
                                      "--publish-queue N",
                                      "(default 64)",
                                      "--camera-silent-s S",
                                      "--reopen-first-s S",
                                      "--reopen-max-s S",
                                      "(default 10)",
                                      "--match-tolerance-ms MS",
                                      "--exit-after-last",
                                      "--quiet",
                                      "Exit status: 0"});
}

}  // namespace
}  // namespace syncap::edge
