// The body check (body_check.hpp) on hand-written truth and frame lines: the joint errors, and
// the fit's predicted sigmas set against those errors.
#include "body_check.hpp"

#include <gtest/gtest.h>

#include "scratch_files.hpp"

namespace syncap::compare {
namespace {

// Two frames of a two-joint body; the fit is 3 mm off along x at every joint, and claims
// `sigma_mm` for each.
void write_run(const testing::ScratchDir& dir, double sigma_mm, bool with_sigmas) {
  dir.write("truth/body.jsonl",
            R"({"frame": 10, "joints": {"HumanoidRoot": [0, 0, 1000], "l_knee": [100, 0, 500]}})"
            "\n"
            R"({"frame": 11, "joints": {"HumanoidRoot": [0, 0, 1000], "l_knee": [100, 0, 500]}})"
            "\n");
  std::string lines;
  for (const int frame : {10, 11}) {
    const std::string sigmas = with_sigmas
                                   ? R"(, "sigma0": 1.1, "joint_sigmas_mm": {"HumanoidRoot": )" +
                                         std::to_string(sigma_mm) + R"(, "l_knee": )" +
                                         std::to_string(sigma_mm) + "}"
                                   : "";
    lines += R"({"frame": )" + std::to_string(frame) +
             R"(, "complete": true, "cameras": {}, "body": {"flags": 2, "joints": )"
             R"({"HumanoidRoot": [3, 0, 1000], "l_knee": [103, 0, 500]})" +
             sigmas + "}}\n";
  }
  dir.write("groups.jsonl", lines);
}

TEST(BodyCheck, SetsThePredictedSigmasAgainstTheErrors) {
  const testing::ScratchDir dir;
  // A 3 mm error on a joint of sigma sqrt(3) mm per coordinate: 3D sigma 3 mm, error / sigma 1.
  write_run(dir, std::sqrt(3.0), true);
  const BodyCheck c = check_body(dir.path(), dir.path() / "groups.jsonl");
  EXPECT_EQ(c.fitted, 2);
  EXPECT_NEAR(c.rms_mm(), 3.0, 1e-9);
  ASSERT_EQ(c.normalized_errors.size(), 4u);
  for (const double z : c.normalized_errors) EXPECT_NEAR(z, 1.0, 1e-5);
  EXPECT_NEAR(c.sigma_ratio(), 1.0, 1e-5);
  ASSERT_EQ(c.sigma0.size(), 2u);
  EXPECT_DOUBLE_EQ(c.sigma0[0], 1.1);
  const std::string text = format_body_check(c);
  EXPECT_NE(text.find("error / predicted sigma RMS 1.00 (1: honest), within 3 sigma 100.0 %"),
            std::string::npos)
      << text;
}

TEST(BodyCheck, AnOverconfidentFitShowsAsLargeNormalizedErrors) {
  const testing::ScratchDir dir;
  write_run(dir, 0.1, true);
  const BodyCheck c = check_body(dir.path(), dir.path() / "groups.jsonl");
  const std::string text = format_body_check(c);
  EXPECT_NE(text.find("within 3 sigma 0.0 %"), std::string::npos) << text;
}

TEST(BodyCheck, RecordsWithoutSigmasLeaveThePrecisionLineOut) {
  const testing::ScratchDir dir;
  write_run(dir, 1.0, false);
  const BodyCheck c = check_body(dir.path(), dir.path() / "groups.jsonl");
  EXPECT_EQ(c.fitted, 2);
  EXPECT_TRUE(c.normalized_errors.empty());
  EXPECT_EQ(c.sigma_ratio(), 0.0);
  EXPECT_EQ(format_body_check(c).find("precision"), std::string::npos);
}

}  // namespace
}  // namespace syncap::compare
