#include "syncap/segmentation/cdnet_eval.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include <opencv2/imgcodecs.hpp>

#include "syncap/segmentation/masking_options.hpp"

namespace syncap::segmentation {
namespace {

// A tiny CDnet folder: frames 1-4 train, 5-6 are scored; a square appears in frame 6.
std::filesystem::path make_folder(const std::string& name) {
  const auto folder = std::filesystem::path(testing::TempDir()) / name;
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder / "input");
  std::filesystem::create_directories(folder / "groundtruth");
  std::ofstream(folder / "temporalROI.txt") << "5 6\n";
  cv::imwrite((folder / "ROI.bmp").string(), cv::Mat(60, 80, CV_8UC1, cv::Scalar(255)));
  for (int frame = 1; frame <= 6; ++frame) {
    cv::Mat image(60, 80, CV_8UC3, cv::Scalar(90, 90, 90));
    cv::Mat truth = cv::Mat::zeros(60, 80, CV_8UC1);
    if (frame == 6) {
      image(cv::Rect(20, 20, 20, 20)).setTo(cv::Scalar(230, 230, 230));
      truth(cv::Rect(20, 20, 20, 20)).setTo(255);
      truth(cv::Rect(60, 0, 20, 10)).setTo(170);  // not scored
    }
    char name_in[32], name_gt[32];
    std::snprintf(name_in, sizeof name_in, "in%06d.jpg", frame);
    std::snprintf(name_gt, sizeof name_gt, "gt%06d.png", frame);
    cv::imwrite((folder / "input" / name_in).string(), image);
    cv::imwrite((folder / "groundtruth" / name_gt).string(), truth);
  }
  return folder;
}

TEST(CdnetEval, CountsBySquareOnSyntheticFolder) {
  CdnetEvalOptions options;
  options.medi_picture.min_component_area = 0;
  const CdnetScores scores = evaluate_cdnet(make_folder("cdnet_ok"), options);
  EXPECT_EQ(scores.scored_frames, 2);
  EXPECT_EQ(scores.true_positives, 400);
  EXPECT_EQ(scores.false_negatives, 0);
  EXPECT_EQ(scores.false_positives, 0);
  EXPECT_EQ(scores.true_negatives, 2 * 60 * 80 - 400 - 200);
  EXPECT_DOUBLE_EQ(scores.f_measure(), 1.0);
}

TEST(CdnetEval, MissingFolderIsNamed) {
  try {
    evaluate_cdnet("/nonexistent/cdnet", CdnetEvalOptions{});
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/cdnet"), std::string::npos) << e.what();
  }
}

TEST(CdnetEval, CorruptImageIsNamedWithItsFrame) {
  const auto folder = make_folder("cdnet_corrupt");
  std::ofstream(folder / "input" / "in000005.jpg") << "not a jpeg";
  try {
    evaluate_cdnet(folder, CdnetEvalOptions{});
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("frame 5"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("in000005.jpg"), std::string::npos) << e.what();
  }
}

// Issue 15: OpenCV decodes a truncated JPEG with only a warning; it was scored silently.
TEST(CdnetEval, TruncatedJpegIsNamedWithItsFrame) {
  const auto folder = make_folder("cdnet_truncated");
  const auto path = folder / "input" / "in000006.jpg";
  // The last bytes lost: OpenCV still decodes it, grey where the data ended.
  std::filesystem::resize_file(path, std::filesystem::file_size(path) - 20);
  try {
    evaluate_cdnet(folder, CdnetEvalOptions{});
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("frame 6 (" + path.string() + ") is a truncated JPEG"),
              std::string::npos)
        << e.what();
  }
}

// Issue 15: segment-eval took --k nan, --frame-step 2xyz and --closing 99999 (28 s, then a
// failure); its medi-picture options are now the edge's, checked alike.
TEST(MaskingOptions, RefuseNanTrailingTextAndOutOfRange) {
  MediPictureOptions m;
  EXPECT_THROW(apply_masking_option(m, "k", "nan"), BadValue);
  EXPECT_THROW(apply_masking_option(m, "closing-px", "99999"), BadValue);
  EXPECT_THROW(apply_masking_option(m, "min-area-px", "2xyz"), BadValue);
  try {
    apply_masking_option(m, "closing-px", "99999");
  } catch (const BadValue& e) {
    EXPECT_STREQ(e.what(), "'99999': expected a number in 0..255");
  }
  EXPECT_THROW(parse_number<int>("2xyz", 1, 100), BadValue);
  EXPECT_TRUE(apply_masking_option(m, "k", "2.5"));
  EXPECT_FLOAT_EQ(m.k, 2.5f);
  EXPECT_FALSE(apply_masking_option(m, "x", "1"));
}

TEST(CdnetEval, ParsesMethodNames) {
  EXPECT_EQ(parse_segmentation_method("mog2"), SegmentationMethod::kMog2);
  EXPECT_EQ(parse_segmentation_method("knn"), SegmentationMethod::kKnn);
  EXPECT_EQ(parse_segmentation_method("medipicture"), SegmentationMethod::kMediPicture);
  EXPECT_THROW(parse_segmentation_method("gmm"), std::invalid_argument);
}

}  // namespace
}  // namespace syncap::segmentation
