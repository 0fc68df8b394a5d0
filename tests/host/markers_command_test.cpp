// `syncap markers`: bad arguments and files are named (exit 2) before any log is read; --help is
// complete. Its reconstruction on a recorded log is checked by every hil run (the "offline" lines
// of hil/run, hil.run.* in ctest).
#include "markers_command.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "help_check.hpp"
#include "sensor/camera_file.hpp"
#include "sensor/test_cameras.hpp"
#include "subcommand.hpp"

namespace syncap::tools {
namespace {

namespace fs = std::filesystem;

struct MarkersRun {
  int status = -1;
  std::string out, err;
};

MarkersRun run(const std::vector<std::string>& args) {
  std::ostringstream out, err;
  MarkersRun r;
  r.status = markers_command(args, out, err);
  r.out = out.str();
  r.err = err.str();
  return r;
}

class MarkersCommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("syncap_markers_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    sensor::write_cameras(dir_ / "cameras.json", {sensor::test::basler_camera()});
    std::ofstream(dir_ / "empty.lcmlog").put('\0');
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::vector<std::string> args(std::vector<std::string> more) const {
    std::vector<std::string> a = {"--input",       "lcmlog:" + (dir_ / "empty.lcmlog").string(),
                                  "--calibration", (dir_ / "cameras.json").string(),
                                  "--out",         (dir_ / "out").string()};
    a.insert(a.end(), more.begin(), more.end());
    return a;
  }
  fs::path dir_;
};

TEST_F(MarkersCommandTest, BadNumbersAreNamedWithTheirOption) {
  for (const auto& [option, value] : std::vector<std::pair<std::string, std::string>>{
           {"--sigma-px", "nan"}, {"--tolerance-px", "-1"}, {"--acceleration", "0"}}) {
    const MarkersRun r = run(args({option, value}));
    EXPECT_EQ(r.status, kExitUsage) << option;
    EXPECT_NE(r.err.find(option), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "out" / "markers.jsonl")) << option;
  }
}

TEST_F(MarkersCommandTest, ABrokenRigidSetFileIsNamedWithItsLine) {
  std::ofstream(dir_ / "sets.yaml") << "rigid_sets:\n  - name: wand\n    markers:\n"
                                       "      - {name: a, position: [0, 0, 0]}\n";
  const MarkersRun r = run(args({"--rigid-sets", (dir_ / "sets.yaml").string()}));
  EXPECT_EQ(r.status, kExitUsage);
  EXPECT_NE(r.err.find("--rigid-sets"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find((dir_ / "sets.yaml").string() + ":"), std::string::npos) << r.err;
}

TEST_F(MarkersCommandTest, HelpIsComplete) {
  const MarkersRun r = run({"--help"});
  EXPECT_EQ(r.status, kExitOk);
  test::expect_help_mentions(
      r.out, {"--input", "--calibration", "--out", "--cameras", "--volume", "--sigma-px",
              "--tolerance-px", "--keep-not-round", "--acceleration", "--rigid-sets", "--max-lag"});
}

}  // namespace
}  // namespace syncap::tools
