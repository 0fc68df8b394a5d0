#include "silhouettes.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "comparison.hpp"
#include "input_error.hpp"
#include "scratch_files.hpp"
#include "summary.hpp"

namespace syncap::compare {
namespace {

// A person-like mask: a disc with a hole (an arm against the body) and a separate blob.
cv::Mat person_mask(cv::Point shift = {0, 0}) {
  cv::Mat mask = cv::Mat::zeros(480, 640, CV_8UC1);
  cv::ellipse(mask, cv::Point(300, 240) + shift, {60, 150}, 0, 0, 360, 255, cv::FILLED);
  cv::circle(mask, cv::Point(300, 200) + shift, 20, 0, cv::FILLED);
  cv::rectangle(mask, cv::Rect(450, 300, 30, 40) + shift, 255, cv::FILLED);
  return mask;
}

// What the edge sends: the boundary-pixel contours cv::findContours traces.
std::vector<Outline> outlines_of(const cv::Mat& mask, double tolerance_px = 0) {
  std::vector<std::vector<cv::Point>> traced;
  std::vector<cv::Vec4i> hierarchy;
  cv::findContours(mask, traced, hierarchy, cv::RETR_CCOMP, cv::CHAIN_APPROX_SIMPLE);
  std::vector<Outline> outlines;
  for (std::size_t i = 0; i < traced.size(); ++i) {
    Outline o{hierarchy[i][3] >= 0, traced[i]};
    if (tolerance_px > 0) cv::approxPolyDP(traced[i], o.points, tolerance_px, true);
    outlines.push_back(o);
  }
  return outlines;
}

TEST(SilhouetteMask, FillsTracedOutlinesBackIntoTheSameMask) {
  const cv::Mat mask = person_mask();
  const cv::Mat filled = silhouette_mask(outlines_of(mask), {640, 480});
  EXPECT_EQ(cv::countNonZero(filled != mask), 0);
}

TEST(SilhouetteMask, ForegroundInsideAHoleSurvivesInAnyOrder) {
  cv::Mat mask = person_mask();
  cv::circle(mask, cv::Point(300, 200), 6, 255, cv::FILLED);  // an island in the hole
  std::vector<Outline> outlines = outlines_of(mask);
  for (int turn = 0; turn < 2; ++turn) {
    const cv::Mat filled = silhouette_mask(outlines, {640, 480});
    EXPECT_EQ(cv::countNonZero(filled != mask), 0) << "order " << turn;
    std::reverse(outlines.begin(), outlines.end());
  }
}

TEST(SilhouetteMask, OutlinesSimplifiedToOnePixelStayClose) {
  const cv::Mat mask = person_mask();
  const auto iou =
      intersection_over_union(silhouette_mask(outlines_of(mask, 1.0), {640, 480}), mask);
  ASSERT_TRUE(iou);
  EXPECT_GT(*iou, 0.98);
  EXPECT_LT(*iou, 1.0);
}

TEST(IntersectionOverUnion, CountsOverlapAgainstUnion) {
  cv::Mat a = cv::Mat::zeros(10, 10, CV_8UC1), b = a.clone();
  a(cv::Rect(0, 0, 4, 5)).setTo(255);  // 20 px
  b(cv::Rect(2, 0, 4, 5)).setTo(1);    // 20 px, 10 shared
  EXPECT_DOUBLE_EQ(*intersection_over_union(a, b), 10.0 / 30.0);
  EXPECT_FALSE(
      intersection_over_union(cv::Mat::zeros(10, 10, CV_8UC1), cv::Mat::zeros(10, 10, CV_8UC1)));
}

// Two person frames (0, 1) with true masks for camera 0; groups as the host writes them.
struct PersonRun {
  testing::ScratchDir dir;
  Truth truth;
  PersonRun() {
    std::filesystem::create_directories(dir.path() / "truth" / "masks" / "camera00");
    for (long k = 0; k < 2; ++k) {
      truth.frames[k] = {k, k / 30.0, 0, "person"};
      char name[32];
      std::snprintf(name, sizeof name, "mask_%06ld.png", k);
      cv::imwrite((dir.path() / "truth" / "masks" / "camera00" / name).string(), person_mask());
    }
    truth.images = {{0, {640, 480}}};
    truth.dir = dir.path();
  }
  static Group group(long k, std::optional<std::vector<Outline>> silhouette) {
    Group g;
    g.frame = k;
    g.complete = true;
    g.cameras[0] = {100, {}, std::move(silhouette)};
    return g;
  }
};

TEST(CompareSilhouettes, PassesWithTheTrueOutlines) {
  PersonRun run;
  const auto outlines = outlines_of(person_mask(), 1.0);
  const Report r = compare(run.truth, {run.group(0, outlines), run.group(1, outlines)}, {});
  EXPECT_TRUE(r.pass()) << verdict_line(r);
  EXPECT_EQ(r.cameras.at(0).silhouettes.expected, 2);
  EXPECT_EQ(r.cameras.at(0).silhouettes.received, 2);
  EXPECT_GT(*r.cameras.at(0).silhouettes.iou.min(), 0.98);
  EXPECT_NE(format_summary(r, "").find("silhouettes (frames with a true mask"), std::string::npos);
}

TEST(CompareSilhouettes, FailsOnAShiftedSilhouette) {
  PersonRun run;
  const auto shifted = outlines_of(person_mask({6, 0}));
  const Report r = compare(run.truth, {run.group(0, shifted), run.group(1, shifted)}, {});
  ASSERT_EQ(r.failures.size(), 1u) << verdict_line(r);
  EXPECT_EQ(r.failures[0].rfind("camera 0: silhouette IoU ", 0), 0u) << r.failures[0];
}

TEST(CompareSilhouettes, MissingSilhouettesFailOnlyWhenRequired) {
  PersonRun run;
  const auto outlines = outlines_of(person_mask());
  const std::vector<Group> groups{run.group(0, outlines), run.group(1, std::nullopt)};
  EXPECT_TRUE(compare(run.truth, groups, {}).pass());
  Thresholds required;
  required.require_silhouettes = true;
  const Report r = compare(run.truth, groups, required);
  ASSERT_EQ(r.failures.size(), 1u) << verdict_line(r);
  EXPECT_EQ(r.failures[0],
            "camera 0: silhouettes in 1/2 frames with a true mask (50.00% < 99.00%)");
}

TEST(CompareSilhouettes, AMaskOfTheWrongSizeIsNamed) {
  PersonRun run;
  cv::imwrite((run.dir.path() / "truth" / "masks" / "camera00" / "mask_000001.png").string(),
              cv::Mat::zeros(10, 10, CV_8UC1));
  try {
    compare(run.truth, {run.group(1, std::nullopt)}, {});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("camera00/mask_000001.png: expected an 8-bit 640x480"),
              std::string::npos)
        << e.what();
  }
}

TEST(GroupsWithSilhouettes, ParseContoursAndNameABadPoint) {
  const Group g = parse_group(
      R"({"frame":4,"complete":true,"cameras":{"2":{"blobs":[],"silhouette":{"width":640,
          "height":480,"contours":[{"hole":false,"points":[[1,2],[3,4],[5,2]]},
          {"hole":true,"points":[[2,2],[3,3],[4,2]]}]}}}})",
      "g.jsonl:1");
  ASSERT_TRUE(g.cameras.at(2).silhouette);
  ASSERT_EQ(g.cameras.at(2).silhouette->size(), 2u);
  EXPECT_TRUE((*g.cameras.at(2).silhouette)[1].hole);
  EXPECT_EQ((*g.cameras.at(2).silhouette)[0].points[1], cv::Point(3, 4));
  try {
    parse_group(R"({"frame":4,"complete":true,"cameras":{"2":{"blobs":[],"silhouette":
                   {"contours":[{"points":[[1,2],[3]]}]}}}})",
                "g.jsonl:7");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(),
                 "g.jsonl:7: cameras.2.silhouette.contours[0].points[1] is not [x, y] in whole "
                 "pixels");
  }
}

}  // namespace
}  // namespace syncap::compare
