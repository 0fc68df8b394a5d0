// The calibration accuracy study's short form (docs/design/calibration-accuracy.md): the claims the
// page makes, on a few Monte Carlo runs with fixed seeds. The full study: syncap-calib-study.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "calibration_study.hpp"
#include "help_check.hpp"
#include "scenario.hpp"
#include "study_report.hpp"

namespace syncap::study {
namespace {

const std::filesystem::path kScenarios = SYNCAP_SOURCE_DIR "/hil/scenarios";

void expect_claims_hold(const std::vector<Claim>& claims) {
  for (const Claim& claim : claims) EXPECT_TRUE(claim.passed) << claim.what << ": " << claim.figure;
}

TEST(SigmaCount, CountsNormalisedErrorsWithinKSigmas) {
  SigmaCount count{2.0};
  count.add(0.1, 0.1);   // 1 sigma
  count.add(-0.3, 0.1);  // 3 sigma: outside
  count.add(2.0, 1.0);   // exactly 2: inside
  EXPECT_EQ(count.within, 2);
  EXPECT_EQ(count.total, 3);
  EXPECT_NEAR(count.rms(), std::sqrt((1.0 + 9.0 + 4.0) / 3.0), 1e-12);
  SigmaCount other{2.0};
  other.add(0.0, 1.0);
  count.merge(other);
  EXPECT_EQ(count.within, 3);
  EXPECT_DOUBLE_EQ(count.rate(), 0.75);
  EXPECT_NEAR(normal_within(3.0), 0.9973, 1e-4);
  EXPECT_NEAR(normal_within(2.0), 0.9545, 1e-4);
}

// Thesis Table 4.3 in short: where the network is stable (>= 40 wands at 0.2 px) the true
// interior errors lie within 3 estimated sigmas, the points' everywhere; the thesis' sigma of c
// (1 px) within a third of its value, its point sigmas (0.2 px) within a factor of two.
TEST(CalibrationStudy, Table43TrueErrorsWithinThreeSigmaAndTheThesisSigmas) {
  const sim::Scenario basler = sim::load_scenario(kScenarios / "wand-3cam-basler.yaml");
  Table43Options options;
  options.runs = 4;
  options.wands = {40, 100};
  options.noise_px = {0.2};
  options.bootstrap_samples = 0;  // the linearised claims; the bootstrap has tests of its own
  const std::vector<Table43Row> precise = run_table_4_3(basler, options);
  ASSERT_EQ(precise.size(), 2u);
  expect_claims_hold(table_4_3_claims(precise, {}));
  for (const Table43Row& row : precise) {
    for (int k = 5; k < 8; ++k) {  // stdX, stdY, stdZ
      EXPECT_GT(row.ours[k], row.thesis[k] / 2.0) << row.wands << " wands, column " << k;
      EXPECT_LT(row.ours[k], row.thesis[k] * 2.0) << row.wands << " wands, column " << k;
    }
  }
  EXPECT_LT(precise[1].ours[0], precise[0].ours[0]);  // more wands, smaller sigma c

  options.wands = {100};
  options.noise_px = {1.0};
  const std::vector<Table43Row> coarse = run_table_4_3(basler, options);
  ASSERT_EQ(coarse.size(), 1u);
  EXPECT_NEAR(coarse[0].ours[0], coarse[0].thesis[0], coarse[0].thesis[0] / 3.0);
  EXPECT_GE(coarse[0].points_3.rate(), 0.99) << coarse[0].points_3.within;
  EXPECT_EQ(coarse[0].failed, 0);
}

// Section 4.4.1 in short: c, xp, yp within 2 sigma, image noise within 10 %, wand length sd at
// most 0.1 % of its length.
TEST(CalibrationStudy, SixCameraNetworkMeetsItsClaims) {
  const sim::Scenario ring = sim::load_scenario(kScenarios / "ring-6cam-person.yaml");
  RingOptions options;
  options.runs = 3;
  const RingStudy study = run_ring_study(ring, options);
  expect_claims_hold(ring_claims(study, {}));
  EXPECT_EQ(study.results.size(), 3u);
  EXPECT_GE(study.principal_3.rate(), 0.99);
  // The estimated cameras measure the wand hardly worse than the true ones.
  EXPECT_LT(calibration_share_mm(study), 0.5 * study.pooled_wand_sd_true_cameras_mm);
}

// A claim fails when the estimates are off: the same errors against sigmas half as large.
TEST(CalibrationStudy, ClaimsFailWhenTheSigmasAreTooSmall) {
  Table43Row row;
  row.wands = 40;
  row.noise_px = 0.2;
  for (int i = 0; i < 100; ++i) {
    const double error = (i % 10 - 4.5) / 3.0;  // spread of about 1
    row.interior_3.add(error, 1.0);
    row.points_3.add(error, 0.25);
  }
  const std::vector<Claim> claims = table_4_3_claims({row}, {});
  ASSERT_EQ(claims.size(), 3u);
  EXPECT_TRUE(claims[0].passed) << claims[0].figure;
  EXPECT_FALSE(claims[1].passed) << claims[1].figure;
  StudyReport report;
  report.table_4_3 = {row};
  EXPECT_NE(format_markdown(report).find("| FAIL |"), std::string::npos);
}

std::string run_program(const std::string& arguments, int& status) {
  const std::filesystem::path out =
      std::filesystem::temp_directory_path() / ("calib-study-" + std::to_string(::getpid()));
  const std::string command =
      std::string(SYNCAP_STUDY_EXE) + " " + arguments + " > " + out.string() + " 2>&1";
  status = std::system(command.c_str());
  std::ifstream file(out);
  std::stringstream text;
  text << file.rdbuf();
  std::filesystem::remove(out);
  return text.str();
}

TEST(CalibrationStudy, ProgramWritesTheWholePage) {
  int status = 0;
  const std::string page = run_program("--short --runs 1", status);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_LE(WEXITSTATUS(status), 1) << page;  // 1: a claim fails, with one run that may happen
  for (const char* section :
       {"# Calibration accuracy", "## 1. Thesis Table 4.3", "| 100 | thesis | 0.041 |",
        "## 2. The six-camera industrial network", "## 3. Real data", "PASS"}) {
    EXPECT_NE(page.find(section), std::string::npos) << section << "\n" << page;
  }
}

TEST(CalibrationStudy, ProgramNamesABadArgument) {
  int status = 0;
  const std::string output = run_program("--runs zero", status);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 2);
  EXPECT_NE(output.find("--runs: 'zero' is not a whole number"), std::string::npos) << output;
  EXPECT_EQ(
      WEXITSTATUS(std::system((std::string(SYNCAP_STUDY_EXE) + " --runs 0 2>/dev/null").c_str())),
      2);
}

// --help: every option with its meaning and default, the exit statuses.
TEST(CalibrationStudy, ProgramHelpIsComplete) {
  int status = 0;
  const std::string help = run_program("--help", status);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  syncap::test::expect_help_mentions(
      help, {"Table 4.3", "--short", "--out FILE", "(default: standard output)", "--scenarios DIR",
             "hil/scenarios", "--runs N", "(default: 50 and 20", "--data DIR", "$SYNCAP_DATA",
             "Exit status: 0 every claim holds"});
}

}  // namespace
}  // namespace syncap::study
