// The built syncap-segment-eval on bad arguments and bad input: exit 2, the option and value named.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "help_check.hpp"
#include "program_run.hpp"

namespace {

using syncap::test::ProgramRun;

ProgramRun run_segment_eval(const std::string& arguments) {
  return syncap::test::run_program(std::string(SYNCAP_SEGMENT_EVAL_PATH) + " " + arguments);
}

void expect_usage_error(const std::string& arguments, const std::string& message) {
  const ProgramRun run = run_segment_eval(arguments);
  EXPECT_EQ(run.exit_code, 2) << arguments << "\n" << run.output;
  EXPECT_EQ(run.output.rfind("syncap-segment-eval: " + message + "\n", 0), 0u) << arguments << "\n"
                                                                               << run.output;
}

// Issue 15: --k nan and --frame-step 2xyz were taken, a bad number said only "stoi",
// --closing 99999 failed after 28 s, an unknown last option "needed a value", and a missing
// folder exited 1.
TEST(SegmentEvalProgram, BadValuesUnknownOptionsAndBadInputExitTwoNamingThem) {
  const std::string scene = "--scene /nonexistent/scene";
  expect_usage_error(scene + " --k nan", "--k: 'nan': expected a number in 0.100000..100.000000");
  expect_usage_error(scene + " --frame-step 2xyz",
                     "--frame-step: '2xyz' is not a whole number in [1, 16777216]");
  expect_usage_error(scene + " --min-area-px x",
                     "--min-area-px: 'x': expected a number in 0..16777216");
  expect_usage_error(scene + " --closing-px 99999",
                     "--closing-px: '99999': expected a number in 0..255");
  expect_usage_error(scene + " --method mog2", "--scene scores medi-picture only");
  expect_usage_error("--cdnet /nonexistent/cdnet", "--method is required");
  expect_usage_error("--cdnet /nonexistent/cdnet --method x",
                     "--method: unknown method 'x' (medipicture, mog2 or knn)");
  expect_usage_error(scene + " --x", "unknown option '--x'");
  expect_usage_error(scene + " --x 1", "unknown option '--x'");
  const ProgramRun missing = run_segment_eval(scene);
  EXPECT_EQ(missing.exit_code, 2) << missing.output;
  EXPECT_NE(missing.output.find("/nonexistent/scene"), std::string::npos) << missing.output;
}

// A bad line of --regions is named with its file and line, and nothing is scored.
TEST(SegmentEvalProgram, BadRegionsLineIsNamed) {
  const std::string path = ::testing::TempDir() + "syncap_bad_regions.jsonl";
  std::ofstream(path) << R"({"camera_id":0,"region":"clip","x":[0,9,9],"y":[0,0,9]})"
                      << "\n"
                      << R"({"camera_id":0,"region":"wall","x":[],"y":[]})"
                      << "\n";
  const ProgramRun run = run_segment_eval("--scene /tmp --regions " + path);
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(run.output.find(path + ":2: region 'wall'"), std::string::npos) << run.output;
  std::remove(path.c_str());
}

// --help: both forms, every option with its meaning and default, the exit statuses.
TEST(SegmentEvalProgram, HelpIsComplete) {
  const ProgramRun run = run_segment_eval("--help");
  EXPECT_EQ(run.exit_code, 0);
  syncap::test::expect_help_mentions(run.output, {"syncap segment-eval --cdnet DIR --method",
                                                  "syncap segment-eval --scene DIR",
                                                  "--cdnet DIR",
                                                  "--scene DIR",
                                                  "--method medipicture|mog2|knn",
                                                  "--thesis",
                                                  "--train-frames N",
                                                  "--frame-step N",
                                                  "(default 1)",
                                                  "--k K",
                                                  "(default 1.5)",
                                                  "--min-difference-dn D",
                                                  "(default 6)",
                                                  "--ncc L",
                                                  "(default 0.98)",
                                                  "--no-shadows",
                                                  "--shadow-test T",
                                                  "--shadow-sigmas S",
                                                  "(default 3)",
                                                  "--fill-holes-px A",
                                                  "(default 100)",
                                                  "--closing-px D",
                                                  "(default 5)",
                                                  "--min-area-px A",
                                                  "(default 40)",
                                                  "--update-rate R",
                                                  "--illumination M",
                                                  "--regions FILE",
                                                  "(default lsm)",
                                                  "Exit status: 0"});
}

}  // namespace
