// syncap/cli/config_file.hpp: --config's file, a program's own (flat) or the rig file (its
// shared keys, its program's section, its camera's entry), as arguments before the command
// line; every problem named with the file, line, column and key.
#include "syncap/cli/config_file.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "syncap/cli/options.hpp"

namespace syncap::cli {
namespace {

// A program with a number, a text, a flag and a camera id list, bound to scratch values.
struct Program {
  int threshold = 10;
  std::string calibration, source, cameras;
  bool quiet = false;
  std::unique_ptr<App> app = std::make_unique<App>("prog", "test program", "");
  Program() {
    app->add_option("--threshold", threshold)->check(number_in(1, 255));
    app->add_option("--calibration", calibration);
    app->add_option("--source", source);
    app->add_option("--cameras", cameras);
    app->add_option("--camera-id", threshold);
    app->add_flag("--quiet", quiet);
    app->add_option("--config", source);
  }
};

class ConfigFileTest : public ::testing::Test {
 protected:
  void write(const std::string& text) { std::ofstream(file_) << text; }
  std::vector<std::string> arguments(const RigPart& part) {
    return config_arguments("prog", file_.string(), part, [this] {
      programs_.push_back(std::make_unique<Program>());
      return std::unique_ptr<CLI::App>(std::move(programs_.back()->app));
    });
  }
  std::string error_of(const RigPart& part) {
    try {
      arguments(part);
    } catch (const ConfigError& e) {
      return e.what();
    }
    return "no error";
  }
  // One file per test and process: ctest runs the cases side by side.
  const std::filesystem::path file_ =
      std::filesystem::path(::testing::TempDir()) /
      ("config_file_test_" + std::to_string(::getpid()) + "_" +
       ::testing::UnitTest::GetInstance()->current_test_info()->name() + ".yaml");
  std::vector<std::unique_ptr<Program>> programs_;
};

using Args = std::vector<std::string>;

TEST_F(ConfigFileTest, AFlatFileIsEveryKeyAsAnOption) {
  write("threshold: 20\nquiet: true\nsource: -dash\n");
  EXPECT_EQ(arguments({"host"}), (Args{"--threshold=20", "--quiet", "--source=-dash"}));
  write("quiet: false\n");
  EXPECT_EQ(arguments({"host"}), Args{});
  write("");
  EXPECT_EQ(arguments({"host"}), Args{});
}

TEST_F(ConfigFileTest, ARigFileGivesSharedKeysTheSectionAndTheCamerasEntry) {
  write(
      "calibration: /etc/syncap/cameras.json\n"
      "lcm-url: udpm://239.255.76.67:7667?ttl=1\n"  // an option prog lacks: another program's
      "host:\n"
      "  threshold: 30\n"
      "edges:\n"
      "  threshold: 40\n"
      "cameras:\n"
      "  - camera-id: 3\n"
      "    board: cam3.local\n"
      "    source: aravis:10.0.0.3\n"
      "  - camera-id: 5\n"
      "    source: aravis:10.0.0.5\n");
  EXPECT_EQ(arguments({"host", std::nullopt, "--cameras"}),
            (Args{"--calibration=/etc/syncap/cameras.json", "--cameras=3,5", "--threshold=30"}));
  EXPECT_EQ(arguments({"edges", 5, ""}),
            (Args{"--calibration=/etc/syncap/cameras.json", "--threshold=40", "--camera-id=5",
                  "--source=aravis:10.0.0.5"}));
  EXPECT_EQ(arguments({"edges", 7, ""}),
            (Args{"--calibration=/etc/syncap/cameras.json", "--threshold=40"}));
}

TEST_F(ConfigFileTest, ProblemsNameFileLineColumnAndKey) {
  const std::string f = file_.string();
  write("threshold: 300\n");
  EXPECT_EQ(error_of({"host"}),
            "prog: " + f + ":1:1: key 'threshold': '300' is not a number in [1, 255]");
  write("quiet: true\nthresold: 3\n");
  EXPECT_EQ(error_of({"host"}),
            "prog: " + f + ":2:1: key 'thresold': unknown key (keys are prog's long options)");
  write("host:\n  thresold: 3\n");
  EXPECT_EQ(error_of({"host"}),
            "prog: " + f + ":2:3: key 'thresold': unknown key (keys are prog's long options)");
  write("quiet: maybe\n");
  EXPECT_EQ(error_of({"host"}), "prog: " + f + ":1:1: key 'quiet' 'maybe': expected true or false");
  write("source: [a, b]\n");
  EXPECT_EQ(error_of({"host"}), "prog: " + f + ":1:1: key 'source': expected a single value");
  write("config: other.yaml\n");
  EXPECT_EQ(error_of({"host"}),
            "prog: " + f + ":1:1: key 'config': a config file cannot include another");
  write("cameras:\n  - source: x\n");
  EXPECT_NE(error_of({"edges", 1, ""}).find(f + ":2:5: a camera without its camera-id"),
            std::string::npos)
      << error_of({"edges", 1, ""});
  write("threshold: [\n");
  EXPECT_NE(error_of({"host"}).find("prog: " + f + ":"), std::string::npos);
  std::filesystem::remove(file_);
  EXPECT_EQ(error_of({"host"}), "prog: --config " + f + ": cannot be read");
}

TEST_F(ConfigFileTest, TheCommandLineComesAfterTheFileSoItWins) {
  write("threshold: 20\n");
  const std::vector<std::string> args{"--config", file_.string(), "--threshold", "50"};
  std::vector<std::unique_ptr<Program>> scratch;
  const std::vector<std::string> all = with_config("prog", args, {"host"}, [&scratch] {
    scratch.push_back(std::make_unique<Program>());
    return std::unique_ptr<CLI::App>(std::move(scratch.back()->app));
  });
  EXPECT_EQ(all, (Args{"--threshold=20", "--config", file_.string(), "--threshold", "50"}));
  Program p;
  std::ostringstream out, err;
  EXPECT_EQ(parse(*p.app, all, out, err), std::nullopt) << err.str();
  EXPECT_EQ(p.threshold, 50);
}

TEST(ConfigPath, TheLastConfigOptionInEitherForm) {
  EXPECT_EQ(config_path(Args{"--quiet"}), std::nullopt);
  EXPECT_EQ(config_path(Args{"--config", "a.yaml", "--config=b.yaml"}), "b.yaml");
  EXPECT_EQ(config_path(Args{"--config=b.yaml", "--config", "a.yaml"}), "a.yaml");
}

TEST(DeprecatedName, IsTakenAsTheNewNameOnTheCommandLineAndInAFile) {
  Program p;
  p.app->deprecated_name("--limit", "--threshold");
  std::ostringstream out, err;
  EXPECT_EQ(parse(*p.app, Args{"--limit", "40"}, out, err), std::nullopt) << err.str();
  EXPECT_EQ(p.threshold, 40);
  EXPECT_EQ(parse(*p.app, Args{"--limit=300"}, out, err), kExitUsage);
  EXPECT_NE(err.str().find("--threshold: '300'"), std::string::npos) << err.str();
  EXPECT_EQ(p.app->help().find("--limit"), std::string::npos);
  EXPECT_EQ(p.app->current_name("--limit"), "--threshold");
  EXPECT_EQ(p.app->current_name("--quiet"), "--quiet");
}

TEST_F(ConfigFileTest, AnOldNameIsTakenAsItsNewOneInAFile) {
  write("limit: 20\n");
  const std::vector<std::string> args = config_arguments("prog", file_.string(), {"host"}, [this] {
    programs_.push_back(std::make_unique<Program>());
    programs_.back()->app->deprecated_name("--limit", "--threshold");
    return std::unique_ptr<CLI::App>(std::move(programs_.back()->app));
  });
  EXPECT_EQ(args, Args{"--threshold=20"});
}

}  // namespace
}  // namespace syncap::cli
