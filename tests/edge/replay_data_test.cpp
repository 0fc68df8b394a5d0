// Replays real camera images (CDnet 2014 'highway', 320x240 colour JPEG) through the replay
// source and the detector: the source must index and decode them, the detector must run on them.
#include <gtest/gtest.h>

#include "detection/blob_detector.hpp"
#include "sensor/replay_source.hpp"
#include "syncap_test_data.hpp"

namespace syncap::edge {
namespace {

TEST(ReplayRealData, IndexesAndDecodesTheHighwaySequence) {
  SYNCAP_REQUIRE_DATA(input, "segmentation/cdnet2014-highway/input");
  ReplaySource source(input, 1);
  EXPECT_EQ(source.size(), 1700u);
  EXPECT_EQ(source.first_frame(), 1);
  EXPECT_EQ(source.last_frame(), 1700);
  for (int64_t k : {1, 470, 1700}) {
    const auto frame = source.grab(k);
    ASSERT_TRUE(frame.has_value()) << k;
    EXPECT_EQ(frame->image.cols, 320);
    EXPECT_EQ(frame->image.rows, 240);
    EXPECT_EQ(frame->image.type(), CV_8UC1);  // colour is read as grey
    // Bright highlights exist on a sunny highway: the detector runs and keeps area limits.
    BlobDetectorConfig config;
    config.threshold = 250;
    config.max_area = 500;
    for (const auto& b : detect_blobs(frame->image, config)) {
      EXPECT_GE(b.area, config.min_area);
      EXPECT_LE(b.area, config.max_area);
      // The centroid weighs the box grown by window_margin: it stays inside that window.
      EXPECT_GE(b.x, b.bbox_x - config.window_margin);
      EXPECT_LE(b.x, b.bbox_x + b.bbox_w - 1 + config.window_margin);
      EXPECT_GE(b.y, b.bbox_y - config.window_margin);
      EXPECT_LE(b.y, b.bbox_y + b.bbox_h - 1 + config.window_margin);
    }
  }
}

}  // namespace
}  // namespace syncap::edge
