// The edge's detection stage: windowed mode finds what the full frame finds, in sensor pixels,
// also when frames are sensor windows; the ROI it asks for covers the next windows.
#include "app/detection_stage.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "../detection/disc_scene.hpp"

namespace syncap::edge {
namespace {

using testing::Disc;

const cv::Size kSensor(640, 480);

// Four discs moving at constant velocity: frame k.
std::vector<Disc> discs_at(int k) {
  std::vector<Disc> d;
  for (int i = 0; i < 4; ++i) {
    d.push_back({100.0 + 110 * i + 1.5 * k, 120.0 + 60 * i + 0.75 * k, 4.0});
  }
  return d;
}

Frame full_frame(int k, cv::RNG& rng) {
  Frame f;
  f.frame_number = k;
  f.image = testing::render(kSensor, discs_at(k), 20, 230, 2.0, rng);
  return f;
}

// The same exposure read out through a sensor window.
Frame windowed(const Frame& full, const cv::Rect& roi) {
  Frame f = full;
  f.image = full.image(roi).clone();
  f.origin = roi.tl();
  f.sensor_size = kSensor;
  return f;
}

const blob_t* nearest(const std::vector<blob_t>& blobs, float x, float y) {
  const blob_t* best = nullptr;
  float best_d = 1e9f;
  for (const blob_t& b : blobs) {
    const float d = std::hypot(b.x - x, b.y - y);
    if (d < best_d) best_d = d, best = &b;
  }
  return best;
}

void expect_same_blobs(const std::vector<blob_t>& got, const std::vector<blob_t>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (const blob_t& w : want) {
    const blob_t* g = nearest(got, w.x, w.y);
    ASSERT_NE(g, nullptr);
    EXPECT_NEAR(g->x, w.x, 1e-3);
    EXPECT_NEAR(g->y, w.y, 1e-3);
    EXPECT_EQ(g->area, w.area);
    EXPECT_EQ(g->bbox_x, w.bbox_x);
    EXPECT_EQ(g->bbox_y, w.bbox_y);
  }
}

DetectionStageConfig config(DetectionMode mode) {
  DetectionStageConfig c;
  c.mode = mode;
  c.detector.threshold = 128;
  c.full_scan_every = 10;
  return c;
}

TEST(DetectionStage, WindowedFindsWhatTheFullFrameFinds) {
  DetectionStage full(config(DetectionMode::kFull));
  DetectionStage windowed_stage(config(DetectionMode::kWindowed));
  cv::RNG rng(7);
  int windowed_frames = 0;
  for (int k = 0; k < 25; ++k) {
    const Frame f = full_frame(k, rng);
    const std::vector<blob_t> want = full.process(f);
    ASSERT_EQ(want.size(), 4u) << "frame " << k;
    const std::vector<blob_t> got = windowed_stage.process(f);
    expect_same_blobs(got, want);
    for (const blob_t& b : got) windowed_frames += (b.flags & blob_t::FLAG_WINDOWED) ? 1 : 0;
  }
  EXPECT_GT(windowed_frames, 4 * 15);  // most frames were window searches
}

TEST(DetectionStage, SensorWindowsGiveSensorPixelsInBothModes) {
  cv::RNG rng(11);
  const Frame f = full_frame(3, rng);
  const cv::Rect roi(64, 80, 512, 360);
  for (DetectionMode mode : {DetectionMode::kFull, DetectionMode::kWindowed}) {
    DetectionStage whole(config(DetectionMode::kFull));
    DetectionStage stage(config(mode));
    const std::vector<blob_t> want = whole.process(f);
    expect_same_blobs(stage.process(windowed(f, roi)), want);
  }
}

TEST(DetectionStage, TheRoiFollowsTheWindowsAndBlobsStayRight) {
  DetectionStageConfig c = config(DetectionMode::kWindowed);
  c.roi_follows_windows = true;
  c.full_scan_every = 1000;
  DetectionStage stage(c);
  DetectionStage reference(config(DetectionMode::kFull));
  cv::RNG rng(3);
  cv::Rect roi;  // the whole sensor at first
  for (int k = 0; k < 12; ++k) {
    const Frame f = full_frame(k, rng);
    const std::vector<blob_t> want = reference.process(f);
    const std::vector<blob_t> got = stage.process(roi.empty() ? f : windowed(f, roi));
    expect_same_blobs(got, want);
    const std::optional<cv::Rect> next = stage.next_roi();
    ASSERT_TRUE(next.has_value());
    roi = *next;
    ASSERT_FALSE(roi.empty()) << "frame " << k << ": all blobs are tracked";
    EXPECT_LT(roi.area(), kSensor.area());
    // Every disc of the next frame lies inside the window asked for.
    for (const Disc& d : discs_at(k + 1)) {
      EXPECT_TRUE(roi.contains(cv::Point(static_cast<int>(d.cx), static_cast<int>(d.cy))))
          << "frame " << k + 1;
    }
  }
}

TEST(DetectionStage, FullModeAsksForNoRoi) {
  DetectionStage stage(config(DetectionMode::kFull));
  EXPECT_FALSE(stage.next_roi().has_value());
  DetectionStage windowed_stage(config(DetectionMode::kWindowed));
  EXPECT_FALSE(windowed_stage.next_roi().has_value()) << "without roi_follows_windows";
}

TEST(DetectionStage, ANewThresholdAppliesAtOnceInWindowedMode) {
  DetectionStage stage(config(DetectionMode::kWindowed));
  cv::RNG rng(5);
  for (int k = 0; k < 3; ++k) ASSERT_EQ(stage.process(full_frame(k, rng)).size(), 4u);
  stage.set_threshold(250);  // above the discs' 230 DN
  EXPECT_TRUE(stage.process(full_frame(3, rng)).empty());
}

}  // namespace
}  // namespace syncap::edge
