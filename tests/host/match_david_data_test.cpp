// Real data: `syncap match` on the 18 calibrated views of silhouettes/david
// (docs/design/matching.md, "Real data"): masks by thresholding the dark background (as the hull's
// test), the polyhedral hull as seeds. Measured when written: 439 points, median sigma along the
// normal 0.0041 (the .pa cameras' object units; the hull's bounding box has a diagonal of 4.8), 430
// of 439 inside every mask within 3 sigma and 0.71 px, the rest at most 0.64 px beyond (the masks
// themselves disagree at the statue's edges: the hull reprojects with IoU 0.944-0.960,
// docs/design/visual-hull.md).
#include <gtest/gtest.h>

#include <regex>
#include <sstream>

#include "match_command.hpp"
#include "subcommand.hpp"
#include "syncap_test_data.hpp"

namespace syncap::tools {
namespace {

TEST(DavidData, MatchedPointsLieOnTheHullWithinTheirSigmas) {
  SYNCAP_REQUIRE_DATA(folder, "silhouettes/david");
  const std::string out_dir =
      (std::filesystem::temp_directory_path() / "syncap_match_david").string();
  std::ostringstream out, err;
  const std::vector<std::string> args{"--cameras", folder.string(), "--images",    folder.string(),
                                      "--masks",   folder.string(), "--threshold", "120",
                                      "--largest", "--out",         out_dir};
  const int status = match_command(args, out, err);
  ASSERT_EQ(status, kExitOk) << err.str();
  const std::string text = out.str();
  std::smatch m;
  ASSERT_TRUE(std::regex_search(text, m, std::regex(R"(seeds: (\d+), points: (\d+))"))) << text;
  const int points = std::stoi(m[2]);
  EXPECT_GE(points, 300);
  ASSERT_TRUE(std::regex_search(
      text, m,
      std::regex(
          R"(inside the visual hull \(every mask\) within 3 sigma and 0.71 px: (\d+) of (\d+))")))
      << text;
  EXPECT_GE(std::stod(m[1]), 0.9 * std::stod(m[2]));
  if (std::regex_search(text, m, std::regex(R"(worst ([0-9.]+) px beyond)"))) {
    EXPECT_LE(std::stod(m[1]), 2.0) << text;
  }
  ASSERT_TRUE(
      std::regex_search(text, m, std::regex(R"(sigma along the normal: median ([0-9.e-]+))")));
  EXPECT_LT(std::stod(m[1]), 0.01);  // 0.2 % of the hull's diagonal
  // Every camera of the ring contributes.
  std::size_t cameras_with_points = 0;
  const std::regex per_camera(R"(camera \d+: (\d+) points)");
  for (std::sregex_iterator i(text.begin(), text.end(), per_camera), end; i != end; ++i)
    cameras_with_points += std::stoi((*i)[1]) > 0;
  EXPECT_EQ(cameras_with_points, 18u);
  std::filesystem::remove_all(out_dir);
}

}  // namespace
}  // namespace syncap::tools
