#include "detection/blob_tracker.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include "disc_scene.hpp"

namespace syncap::edge {
namespace {

using testing::Disc;
using testing::render;

const cv::Size kSize(320, 240);

cv::Mat frame(const std::vector<Disc>& discs, cv::RNG& rng) {
  return render(kSize, discs, 20, 200, 2.0, rng);
}

const blob_t* near(const std::vector<blob_t>& blobs, double x, double y, double tol = 0.1) {
  for (const blob_t& b : blobs) {
    if (std::hypot(b.x - x, b.y - y) < tol) return &b;
  }
  return nullptr;
}

TEST(BlobTracker, FollowsMovingBlobsInWindowsAroundTheirPrediction) {
  BlobTrackerConfig config;
  config.full_scan_every = 10;
  BlobTracker tracker(config);
  cv::RNG rng(1);
  int full = 0;
  for (int f = 0; f < 30; ++f) {
    const Disc a{40.0 + 4.5 * f, 50.0 + 1.2 * f, 4}, b{280.0 - 3.1 * f, 200.0 - 2.0 * f, 3};
    const auto& blobs = tracker.process(frame({a, b}, rng));
    ASSERT_EQ(blobs.size(), 2u) << "frame " << f;
    ASSERT_TRUE(near(blobs, a.cx, a.cy)) << "frame " << f;
    ASSERT_TRUE(near(blobs, b.cx, b.cy)) << "frame " << f;
    full += tracker.last_was_full_scan();
    for (const blob_t& blob : blobs) {
      EXPECT_EQ((blob.flags & blob_t::FLAG_WINDOWED) != 0, !tracker.last_was_full_scan());
    }
    EXPECT_EQ(tracker.last_was_full_scan(), f % 10 == 0) << "frame " << f;
    if (!tracker.last_was_full_scan()) {
      ASSERT_EQ(tracker.windows().size(), 2u);
      for (const cv::Rect& w : tracker.windows()) EXPECT_LT(w.area(), 40 * 40);
    }
    // The next frame's blobs lie inside the windows it will search (after the second frame,
    // once the velocity is known).
    const cv::Rect roi = tracker.next_roi();
    if (f >= 1 && !roi.empty()) {
      const Disc na{40.0 + 4.5 * (f + 1), 50.0 + 1.2 * (f + 1), 4};
      bool inside = false;
      for (const cv::Rect& w : tracker.next_windows()) {
        inside |= w.contains({static_cast<int>(na.cx), static_cast<int>(na.cy)});
      }
      EXPECT_TRUE(inside) << "frame " << f;
      EXPECT_TRUE(roi.contains({static_cast<int>(na.cx), static_cast<int>(na.cy)}));
    }
  }
  EXPECT_EQ(full, 3);
  EXPECT_EQ(tracker.tracked(), 2u);
}

TEST(BlobTracker, ScansTheFullFrameWhenABlobIsLostAndReacquiresIt) {
  BlobTrackerConfig config;
  config.full_scan_every = 100;
  BlobTracker tracker(config);
  cv::RNG rng(2);
  const Disc a{100, 100, 4}, b{200, 150, 4};
  tracker.process(frame({a, b}, rng));
  EXPECT_TRUE(tracker.last_was_full_scan());
  tracker.process(frame({a, b}, rng));
  EXPECT_FALSE(tracker.last_was_full_scan());
  // b is hidden: the window misses it, the same frame is scanned in full, b's track ends.
  auto blobs = tracker.process(frame({a}, rng));
  EXPECT_TRUE(tracker.last_was_full_scan());
  ASSERT_EQ(blobs.size(), 1u);
  EXPECT_TRUE(near(blobs, 100, 100));
  EXPECT_EQ(tracker.tracked(), 1u);
  // b comes back: a's windows do not see it until the next full scan.
  blobs = tracker.process(frame({a, b}, rng));
  EXPECT_FALSE(tracker.last_was_full_scan());
  EXPECT_EQ(blobs.size(), 1u);
  // a jumps away (lost), which forces a full scan that re-acquires both.
  blobs = tracker.process(frame({{40, 30, 4}, b}, rng));
  EXPECT_TRUE(tracker.last_was_full_scan());
  ASSERT_EQ(blobs.size(), 2u);
  EXPECT_TRUE(near(blobs, 40, 30));
  EXPECT_TRUE(near(blobs, 200, 150));
  blobs = tracker.process(frame({{40, 30, 4}, b}, rng));
  EXPECT_FALSE(tracker.last_was_full_scan());
  EXPECT_EQ(blobs.size(), 2u);
}

TEST(BlobTracker, ScansEveryFrameWhileNothingIsTracked) {
  BlobTracker tracker({});
  cv::RNG rng(3);
  for (int f = 0; f < 3; ++f) {
    EXPECT_TRUE(tracker.process(frame({}, rng)).empty());
    EXPECT_TRUE(tracker.last_was_full_scan());
    EXPECT_TRUE(tracker.next_roi().empty());
  }
  EXPECT_EQ(tracker.process(frame({{160, 120, 5}}, rng)).size(), 1u);
  EXPECT_FALSE(tracker.next_roi().empty());
  EXPECT_TRUE(tracker.next_roi().contains({160, 120}));
}

TEST(BlobTracker, MergesOverlappingWindowsSoNoBlobIsReportedTwice) {
  BlobTracker tracker({});
  cv::RNG rng(4);
  const std::vector<Disc> close{{100, 100, 3}, {112, 103, 3}};
  tracker.process(frame(close, rng));
  const auto& blobs = tracker.process(frame(close, rng));
  EXPECT_FALSE(tracker.last_was_full_scan());
  EXPECT_EQ(tracker.windows().size(), 1u);
  EXPECT_EQ(blobs.size(), 2u);
}

TEST(BlobTracker, NarrowsItsWindowsOnceTheMotionIsPredicted) {
  BlobTrackerConfig config;
  config.full_scan_every = 100;
  BlobTracker tracker(config);
  cv::RNG rng(5);
  std::vector<int> margins;
  int last_box_width = 0;
  for (int f = 0; f < 10; ++f) {
    const Disc d{60.0 + 3.3 * f, 80.0 + 1.7 * f, 4};
    const auto& blobs = tracker.process(frame({d}, rng));
    ASSERT_EQ(blobs.size(), 1u) << "frame " << f;
    EXPECT_NEAR(blobs[0].x, d.cx, 0.1) << "frame " << f;
    EXPECT_NEAR(blobs[0].y, d.cy, 0.1) << "frame " << f;
    EXPECT_EQ(tracker.last_was_full_scan(), f == 0) << "frame " << f;
    // The window around last frame's box: half the box + margin + window_margin 3 + 1 a side.
    if (f > 0) margins.push_back((tracker.windows().at(0).width - 1) / 2 - last_box_width / 2 - 4);
    last_box_width = blobs[0].bbox_w;
  }
  // search_margin 8 while the velocity is unknown, then min_search_margin 2 plus twice the
  // prediction error, which halves every frame down to the noise's (well under 0.5 px).
  EXPECT_EQ(margins.front(), 8);
  EXPECT_EQ(margins.back(), 3);
  EXPECT_TRUE(std::is_sorted(margins.rbegin(), margins.rend()));
}

TEST(BlobTracker, ScansTheFullFrameWhenABlobLeavesItsNarrowWindow) {
  BlobTrackerConfig config;
  config.full_scan_every = 100;
  BlobTracker tracker(config);
  BlobDetector full;
  cv::RNG rng(6);
  for (int f = 0; f < 8; ++f) tracker.process(frame({{100.0 + 2 * f, 100, 4}}, rng));
  ASSERT_FALSE(tracker.last_was_full_scan());
  const int narrow = tracker.windows().at(0).width;
  ASSERT_LE(narrow, 2 * (9 / 2 + 3 + 3 + 1) + 1);  // margin 3 around a box of at most 9 px
  // 4 px ahead of its prediction: within max_jump, but its centroid window and background ring
  // would be cut by the search window. It is measured on the full frame instead, in full.
  const cv::Mat image = frame({{100.0 + 2 * 8 + 4, 100, 4}}, rng);
  const auto& blobs = tracker.process(image);
  EXPECT_TRUE(tracker.last_was_full_scan());
  ASSERT_EQ(blobs.size(), 1u);
  const auto& expected = full.detect(image);
  ASSERT_EQ(expected.size(), 1u);
  EXPECT_EQ(blobs[0].x, expected[0].x);
  EXPECT_EQ(blobs[0].y, expected[0].y);
  EXPECT_EQ(blobs[0].flags & blob_t::FLAG_AT_BORDER, 0);
  // The miss widens the next window: the blob, 6 px past the old prediction, is found in it.
  tracker.process(frame({{100.0 + 2 * 9 + 4 + 6, 100, 4}}, rng));
  EXPECT_FALSE(tracker.last_was_full_scan());
  EXPECT_GT(tracker.windows().at(0).width, narrow + 4);
}

// A target crossing the image at 12 px a frame (a wand at 24 Hz): farther than max_jump from
// where a new track was, so the first full scans take it up at max_first_jump, and from the
// third frame on its windows hold it.
TEST(BlobTracker, TakesUpABlobFasterThanMaxJump) {
  BlobTrackerConfig config;
  config.full_scan_every = 100;
  BlobTracker tracker(config);
  cv::RNG rng(8);
  int windowed = 0;
  for (int f = 0; f < 12; ++f) {
    const Disc d{30.0 + 12.0 * f, 60.0 + 5.0 * f, 3};
    const auto& blobs = tracker.process(frame({d}, rng));
    ASSERT_EQ(blobs.size(), 1u) << "frame " << f;
    EXPECT_NEAR(blobs[0].x, d.cx, 0.1) << "frame " << f;
    windowed += !tracker.last_was_full_scan();
    if (f >= 2) {
      EXPECT_FALSE(tracker.last_was_full_scan()) << "frame " << f;
    }
  }
  EXPECT_EQ(windowed, 10);
  // Without the wider first jump the track is born anew at every full scan and never windowed.
  config.max_first_jump = 0.0f;
  BlobTracker strict(config);
  for (int f = 0; f < 12; ++f) strict.process(frame({{30.0 + 12.0 * f, 60.0 + 5.0 * f, 3}}, rng));
  EXPECT_TRUE(strict.last_was_full_scan());
}

}  // namespace
}  // namespace syncap::edge
