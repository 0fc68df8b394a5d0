// A real capture that starts with the person in view (../shared/data/multiview/
// uu-infomcv-4cam-person: four 644x486 cameras, a seated person, a clip of the empty studio per
// camera). Trained on the capture's own first frames the model takes the seated person for
// background; trained on the background clip (--background) the person is found. The masks are
// scored against a second method trained on the same clip: OpenCV's KNN background subtractor
// (shadows, its grey 127, counted as background). Prints the figures docs/results/
// segmentation.md records.
#include <gtest/gtest.h>

#include <cstdio>
#include <opencv2/core.hpp>
#include <opencv2/video/background_segm.hpp>

#include "sensor/replay_source.hpp"
#include "syncap/segmentation/background_clip.hpp"
#include "syncap/segmentation/medi_picture.hpp"
#include "syncap/segmentation/model_alignment.hpp"
#include "syncap_test_data.hpp"

namespace syncap::edge {
namespace {

constexpr int kScoredFrames[] = {0, 100, 200, 300, 400};

struct Agreement {
  double iou = 0;        // ours against the reference
  double recall = 0;     // share of the reference's foreground ours has
  double ours_area = 0;  // foreground pixels of ours, mean per frame
};

Agreement agreement(const std::vector<cv::Mat>& ours, const std::vector<cv::Mat>& reference) {
  double both = 0, either = 0, ref = 0, area = 0;
  for (std::size_t i = 0; i < ours.size(); ++i) {
    const cv::Mat a = ours[i] == 255, b = reference[i] == 255;
    both += cv::countNonZero(a & b);
    either += cv::countNonZero(a | b);
    ref += cv::countNonZero(b);
    area += cv::countNonZero(a);
  }
  return {either > 0 ? both / either : 0, ref > 0 ? both / ref : 0,
          area / static_cast<double>(ours.size())};
}

// Our masks of the scored frames, the model trained on `training` (and moved onto the capture's
// first frame with `align`, as syncap-edge --background and syncap mask do).
std::vector<cv::Mat> our_masks(const std::vector<cv::Mat>& training, VideoReplaySource& video,
                               bool align = false) {
  segmentation::MediPictureModel model =
      segmentation::train_medi_picture(training, segmentation::MediPictureOptions{});
  if (align) segmentation::align_model(model, video.grab(0)->image);
  segmentation::MediPicture masking(model, segmentation::MediPictureOptions{});
  std::vector<cv::Mat> masks;
  for (const int k : kScoredFrames) masks.push_back(masking.apply(video.grab(k)->image).clone());
  return masks;
}

TEST(BackgroundClipData, TheClipFindsThePersonTheCapturesOwnFramesLose) {
  SYNCAP_REQUIRE_DATA(dir, "multiview/uu-infomcv-4cam-person");
  for (int cam = 1; cam <= 4; ++cam) {
    const std::filesystem::path folder = dir / ("cam" + std::to_string(cam));
    const std::vector<cv::Mat> clip =
        segmentation::read_background_clip(folder / "background.avi", 50);
    VideoReplaySource video(folder / "video.avi", cam);
    // The reference: KNN with its defaults, learning the whole clip, then frozen.
    cv::Ptr<cv::BackgroundSubtractorKNN> knn = cv::createBackgroundSubtractorKNN();
    VideoReplaySource background(folder / "background.avi", cam);
    cv::Mat ignored;
    for (int64_t k = 0; const auto frame = background.grab(k); ++k)
      knn->apply(frame->image, ignored);
    std::vector<cv::Mat> reference;
    for (const int k : kScoredFrames) {
      cv::Mat fg;
      knn->apply(video.grab(k)->image, fg, 0.0);
      reference.push_back(fg);
    }
    // The capture's own first 50 frames: the seated person is in all of them.
    std::vector<cv::Mat> own;
    for (int k = 0; k < 50; ++k) own.push_back(video.grab(k)->image.clone());
    const Agreement from_clip = agreement(our_masks(clip, video), reference);
    const Agreement from_own = agreement(our_masks(own, video), reference);
    const Agreement aligned = agreement(our_masks(clip, video, true), reference);
    std::printf(
        "cam%d: trained on the background clip: IoU %.3f, recall %.3f, %.0f px; aligned to the "
        "capture: IoU %.3f, recall %.3f, %.0f px; on the capture's first 50 frames: IoU %.3f, "
        "recall %.3f, %.0f px\n",
        cam, from_clip.iou, from_clip.recall, from_clip.ours_area, aligned.iou, aligned.recall,
        aligned.ours_area, from_own.iou, from_own.recall, from_own.ours_area);
    // Aligning never costs (a camera that did not move is left), and finds the moved one's
    // person again among its wall edges (camera 2: 1.04 px; IoU measured 0.258 -> 0.378). The
    // reference learned the clip unaligned and calls the same wall edges foreground: against it
    // the moved camera's recall drops to 0.87 for edges that are no person.
    EXPECT_GT(aligned.iou, from_clip.iou - 0.01) << "camera " << cam;
    EXPECT_GT(aligned.recall, 0.85) << "camera " << cam;
    if (cam == 2) {
      EXPECT_GT(aligned.iou, from_clip.iou + 0.1);
    }
    EXPECT_GT(from_clip.recall, from_own.recall + 0.2) << "camera " << cam;
    EXPECT_GT(from_clip.recall, 0.7) << "camera " << cam;
    // Measured 0.26-0.51: the defaults keep the studio's shadows and edges (issue 36, masking).
    EXPECT_GT(from_clip.iou, 0.2) << "camera " << cam;
  }
}

}  // namespace
}  // namespace syncap::edge
