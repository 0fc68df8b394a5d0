#include "app/host_options.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "syncap/proto/command_auth.hpp"

namespace syncap::host_app {
namespace {

ParsedHostOptions parse(std::vector<std::string> args, std::string* err_text = nullptr) {
  std::ostringstream out, err;
  ParsedHostOptions p = parse_host_options(args, out, err);
  if (err_text != nullptr) *err_text = err.str() + out.str();
  return p;
}

TEST(HostOptions, MarkersOptionsAreParsed) {
  const ParsedHostOptions p = parse(
      {"--cameras", "0,2,5", "--volume", "-1000,-1000,0,1000,1000,2000", "--sigma-px", "0.3",
       "--tolerance-px", "1.5", "--no-marker-message", "--max-lag", "30", "--keep-not-round",
       "--acceleration", "25", "--partial-spot-ratio", "0.9", "--partial-spot-min-rays", "4"});
  ASSERT_TRUE(p.options.has_value());
  EXPECT_EQ(p.options->cameras, (std::set<int>{0, 2, 5}));
  ASSERT_TRUE(p.options->pipeline.markers.matching.volume.has_value());
  EXPECT_EQ(p.options->pipeline.markers.matching.volume->max().z(), 2000);
  EXPECT_DOUBLE_EQ(p.options->pipeline.markers.matching.sigma_px, 0.3);
  EXPECT_DOUBLE_EQ(p.options->pipeline.markers.matching.tolerance_px, 1.5);
  EXPECT_FALSE(p.options->messages.markers);
  EXPECT_EQ(p.options->max_lag, 30);
  EXPECT_TRUE(p.options->pipeline.markers.stage.keep_not_round);
  EXPECT_DOUBLE_EQ(p.options->pipeline.markers.stage.partial_spots.min_width_ratio, 0.9);
  EXPECT_EQ(p.options->pipeline.markers.stage.partial_spots.min_whole_rays, 4);
  EXPECT_EQ(parse({"--partial-spot-ratio", "1.5"}).exit_status, 2);
  EXPECT_EQ(parse({"--partial-spot-min-rays", "1"}).exit_status, 2);
  EXPECT_DOUBLE_EQ(p.options->pipeline.markers.tracker.motion.quiet_acceleration_mm_s2, 25000);
}

TEST(HostOptions, HullOptionsAreParsedAndTheHullNeedsTheCalibration) {
  std::string err;
  EXPECT_EQ(parse({"--hull"}, &err).exit_status, 2);
  EXPECT_NE(err.find("--hull: needs --calibration"), std::string::npos) << err;
  const std::string calibration = ::testing::TempDir() + "/hull_options_cameras.json";
  std::ofstream(calibration) << "{}";
  const ParsedHostOptions p =
      parse({"--calibration", calibration, "--hull", "--hull-method", "exact", "--hull-resolution",
             "48", "--hull-every", "3", "--hull-max-wait-ms", "0", "--hull-iou", "--hull-min-iou",
             "0.8", "--hull-meshes", "out/meshes", "--no-hull-message"});
  ASSERT_TRUE(p.options.has_value());
  const controllers::HullOptions& h = p.options->pipeline.hull;
  EXPECT_TRUE(h.enabled);
  EXPECT_EQ(h.stage.method, reconstruction::HullMethod::kExact);
  EXPECT_EQ(h.stage.voxel_resolution, 48);
  EXPECT_EQ(h.stage.every, 3);
  EXPECT_EQ(h.stage.max_wait_ms, 0.0);
  EXPECT_TRUE(h.stage.view_iou);
  EXPECT_DOUBLE_EQ(h.stage.min_view_iou, 0.8);
  EXPECT_EQ(h.stage.mesh_dir, "out/meshes");
  EXPECT_FALSE(p.options->messages.hull);
  EXPECT_EQ(parse({"--hull-method", "octree"}, &err).exit_status, 2);
  EXPECT_NE(err.find("--hull-method"), std::string::npos) << err;
  EXPECT_FALSE(parse({}).options->pipeline.hull.enabled);
  EXPECT_EQ(parse({}).options->pipeline.hull.stage.method, reconstruction::HullMethod::kPolyhedral);
}

// --search-regions needs the tracked body and a readable key, and names what is missing.
TEST(HostOptions, SearchRegionsNeedTheBodyAndTheKey) {
  const std::string calibration = ::testing::TempDir() + "/search_options_cameras.json";
  std::ofstream(calibration) << "{}";
  std::string err;
  EXPECT_EQ(parse({"--calibration", calibration, "--search-regions"}, &err).exit_status, 2);
  EXPECT_NE(err.find("--search-regions: needs --body"), std::string::npos) << err;
  EXPECT_EQ(parse({"--calibration", calibration, "--body", "--search-regions"}, &err).exit_status,
            2);
  EXPECT_NE(err.find("--search-regions: needs --command-key FILE"), std::string::npos) << err;
  EXPECT_EQ(parse({"--calibration", calibration, "--body", "--search-regions", "--command-key",
                   "/nonexistent.key"},
                  &err)
                .exit_status,
            2);
  EXPECT_NE(err.find("/nonexistent.key"), std::string::npos) << err;
  const std::string key = ::testing::TempDir() + "/search_options.key";
  std::remove(key.c_str());
  proto::CommandKey::generate().save(key, /*replace=*/true);
  const ParsedHostOptions p =
      parse({"--calibration", calibration, "--body", "--search-regions", "--command-key", key,
             "--search-margin", "30", "--search-frames", "20"});
  ASSERT_TRUE(p.options.has_value()) << err;
  EXPECT_TRUE(p.options->pipeline.search_regions.enabled);
  EXPECT_DOUBLE_EQ(p.options->pipeline.search_regions.stage.region.margin_px, 30);
  EXPECT_EQ(p.options->pipeline.search_regions.stage.valid_frames, 20);
  EXPECT_EQ(parse({"--search-frames", "0"}).exit_status, 2);
  std::remove(key.c_str());
}

// The rig file (docs/guide/rig.md): its shared keys, its cameras' ids and its host: section,
// with the command line over them; the old --key still works, saying it is deprecated.
TEST(HostOptions, TheRigFileGivesTheHostItsCamerasSharedKeysAndSection) {
  const std::string dir = ::testing::TempDir();
  const std::string calibration = dir + "/rig_cameras.json", key = dir + "/rig_command.key";
  std::ofstream(calibration) << "{}";
  std::remove(key.c_str());
  proto::CommandKey::generate().save(key, /*replace=*/true);
  const std::string rig = dir + "/rig.yaml";
  std::ofstream(rig) << "calibration: " << calibration << "\ncommand-key: " << key
                     << "\ntrigger:\n  rate: 30\nedges:\n  mode: both\n"
                        "cameras:\n  - camera-id: 1\n    board: cam1\n  - camera-id: 4\n"
                        "host:\n  body: true\n  search-regions: true\n  max-lag: 20\n";
  std::string err;
  ParsedHostOptions p = parse({"--config", rig, "--max-lag", "25"}, &err);
  ASSERT_TRUE(p.options.has_value()) << err;
  EXPECT_EQ(p.options->cameras, (std::set<int>{1, 4}));
  EXPECT_EQ(p.options->calibration, calibration);
  EXPECT_TRUE(p.options->pipeline.body.enabled);
  EXPECT_TRUE(p.options->pipeline.search_regions.enabled);
  EXPECT_TRUE(p.options->files.key.has_value());
  EXPECT_EQ(p.options->max_lag, 25);
  std::ofstream(rig) << "host:\n  max-lag: many\n";
  EXPECT_EQ(parse({"--config", rig}, &err).exit_status, 2);
  EXPECT_NE(err.find(rig + ":2:3: key 'max-lag': "), std::string::npos) << err;
  p = parse({"--key", key}, &err);
  ASSERT_TRUE(p.options.has_value()) << err;
  EXPECT_EQ(p.options->files.key_path, key);
  std::remove(key.c_str());
}

// The rig file's example (docs/guide/rig.md), its /etc/syncap files put where the test can make
// them: the host takes the shared keys, the cameras' ids and its section.
TEST(HostOptions, TheShippedRigExampleParses) {
  std::ifstream example(SYNCAP_SOURCE_DIR "/docs/examples/rig-8cam.yaml");
  std::string text((std::istreambuf_iterator<char>(example)), std::istreambuf_iterator<char>());
  ASSERT_FALSE(text.empty());
  const std::string dir = ::testing::TempDir() + "/rig_example";
  std::filesystem::create_directories(dir);
  for (std::size_t at; (at = text.find("/etc/syncap")) != std::string::npos;)
    text.replace(at, 11, dir);
  std::ofstream(dir + "/rig.yaml") << text;
  std::ofstream(dir + "/cameras.json") << "{}";
  std::remove((dir + "/command.key").c_str());
  proto::CommandKey::generate().save(dir + "/command.key", /*replace=*/true);
  std::string err;
  const ParsedHostOptions p = parse({"--config", dir + "/rig.yaml"}, &err);
  ASSERT_TRUE(p.options.has_value()) << err;
  EXPECT_EQ(p.options->cameras, (std::set<int>{0, 1, 2, 3, 4, 5, 6, 7}));
  EXPECT_EQ(p.options->max_lag, 10);
  EXPECT_TRUE(p.options->pipeline.hull.enabled);
  EXPECT_TRUE(p.options->pipeline.body.enabled);
  EXPECT_TRUE(p.options->pipeline.search_regions.enabled);
  ASSERT_TRUE(p.options->pipeline.markers.matching.volume.has_value());
  EXPECT_EQ(p.options->pipeline.markers.matching.volume->max().z(), 2500);
  EXPECT_EQ(p.options->lcm_url, "udpm://239.255.76.67:7667?ttl=1");
}

TEST(HostOptions, BadValuesExitTwoNamingTheOption) {
  std::string err;
  EXPECT_EQ(parse({"--cameras", "0,x"}, &err).exit_status, 2);
  EXPECT_NE(err.find("'x' is not a camera id"), std::string::npos) << err;
  EXPECT_EQ(parse({"--volume", "1,2,3,0,0,0"}, &err).exit_status, 2);
  EXPECT_NE(err.find("--volume"), std::string::npos) << err;
  EXPECT_EQ(parse({"--calibration", "/nonexistent/cameras.json"}, &err).exit_status, 2);
  EXPECT_NE(err.find("/nonexistent/cameras.json"), std::string::npos) << err;
  EXPECT_EQ(parse({"--max-lag", "-1"}, &err).exit_status, 2);
  EXPECT_EQ(parse({"--acceleration", "0"}, &err).exit_status, 2);
  EXPECT_NE(err.find("--acceleration"), std::string::npos) << err;
  EXPECT_EQ(parse({"--colour"}, &err).exit_status, 2);
  EXPECT_NE(err.find("--colour"), std::string::npos) << err;
}

// CLI::Range let NaN through: --idle-timeout nan never timed out.
TEST(HostOptions, NotANumberIsRefusedNamingOptionAndValue) {
  for (const char* option : {"--idle-timeout-s", "--tolerance-px", "--sigma-px"}) {
    std::string err;
    EXPECT_EQ(parse({option, "nan"}, &err).exit_status, 2) << option;
    EXPECT_NE(err.find(std::string(option) + ": 'nan' is not a number in ["), std::string::npos)
        << err;
  }
}

TEST(HostOptions, HelpNamesEveryOption) {
  std::string text;
  const ParsedHostOptions p = parse({"--help"}, &text);
  EXPECT_FALSE(p.options.has_value());
  EXPECT_EQ(p.exit_status, 0);
  for (const char* option : {"--camera-ids",
                             "--max-lag",
                             "--frames",
                             "--until-last",
                             "--idle-timeout",
                             "--out",
                             "--lcm-url",
                             "--quiet",
                             "--calibration",
                             "--volume",
                             "--tolerance-px",
                             "--sigma-px",
                             "--no-marker-message",
                             "--keep-not-round",
                             "--acceleration",
                             "--search-regions",
                             "--command-key",
                             "--config",
                             "--search-margin",
                             "--search-frames"})
    EXPECT_NE(text.find(option), std::string::npos) << option;
}

}  // namespace
}  // namespace syncap::host_app
