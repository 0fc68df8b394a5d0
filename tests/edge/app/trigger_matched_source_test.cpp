#include "sensor/trigger_matched_source.hpp"

#include <gtest/gtest.h>

#include <map>

namespace syncap::edge {
namespace {

constexpr int64_t kMs = 1'000'000;

TEST(TriggerMatcher, GivesTheClosestTriggerWithinTheTolerance) {
  TriggerMatcher matcher(5 * kMs, 4);
  for (int64_t k = 10; k < 14; ++k) matcher.add(k, 1000 * kMs + (k - 10) * 33 * kMs);
  // Triggers at 1000, 1033, 1066, 1099 ms.
  EXPECT_EQ(matcher.match(1000 * kMs), 10);
  EXPECT_EQ(matcher.match(1037 * kMs), 11);
  EXPECT_EQ(matcher.match(1062 * kMs), 12);
  EXPECT_EQ(matcher.match(1050 * kMs), std::nullopt);  // between two, near neither
  EXPECT_EQ(matcher.match(1105 * kMs), std::nullopt);  // 6 ms after the last
  EXPECT_EQ(matcher.match(995 * kMs), 10);             // exactly at the tolerance
  matcher.add(14, 1132 * kMs);                         // capacity 4: trigger 10 is forgotten
  EXPECT_EQ(matcher.match(1000 * kMs), std::nullopt);
  EXPECT_EQ(matcher.time_of(14), 1132 * kMs);
  EXPECT_EQ(matcher.time_of(10), std::nullopt);
}

// A free-running camera: its own frame numbers 0, 1, 2 ... with the given timestamps; numbers
// without a timestamp are frames the driver skipped.
class FreeRunningCamera : public FrameSource {
 public:
  std::map<int64_t, int64_t> timestamps;  // camera frame number -> monotonic ns
  std::optional<Frame> grab(int64_t frame_number) override {
    // Like V4L2: the next frame the driver has, held back if it is later than asked.
    auto it = timestamps.lower_bound(frame_number);
    if (it == timestamps.end() || it->first != frame_number) return std::nullopt;
    Frame frame;
    frame.frame_number = it->first;
    frame.monotonic_ns = it->second;
    frame.image = cv::Mat(4, 4, CV_8UC1, cv::Scalar(static_cast<double>(it->first)));
    return frame;
  }
  std::string describe() const override { return "uvc"; }
};

TEST(TriggerMatchedSource, NumbersFramesByTheirTrigger) {
  auto camera = std::make_unique<FreeRunningCamera>();
  // Triggers every 33 ms from t = 1 s. The camera runs a little fast (32 ms) and 3 ms late, so
  // its frames drift against the triggers: camera frame 5 (at 1163 ms) lies between trigger 5
  // (1165) and 4 ... and frame 8 is skipped by the driver.
  for (int64_t n = 0; n < 12; ++n) {
    if (n != 8) camera->timestamps[n] = 1003 * kMs + n * 32 * kMs;
  }
  FreeRunningCamera* raw = camera.get();
  TriggerMatchedSource source(std::move(camera), 4 * kMs);
  std::map<int64_t, int> got;  // trigger frame number -> camera frame (the pixel value)
  int64_t lost = 0;
  for (int64_t k = 100; k < 111; ++k) {
    source.note_trigger(k, 1000 * kMs + (k - 100) * 33 * kMs);
    auto frame = source.grab(k);
    if (!frame) {
      ++lost;
      continue;
    }
    EXPECT_EQ(frame->frame_number, k);
    got[k] = frame->image.at<uint8_t>(0, 0);
  }
  // Camera frame n at 1003 + 32 n ms, trigger k at 1000 + 33 (k - 100) ms: |3 - (k-100-n)... |
  // frames 0..4 are 3, 2, 1, 0, 1 ms from triggers 100..104; frame 5 is 2 ms from 105, 6 is
  // 3 ms from 106, 7 is 4 ms from 107 (the tolerance), 9 is 6 ms from 109: unmatched, and so on.
  const std::map<int64_t, int> expected{{100, 0}, {101, 1}, {102, 2}, {103, 3},
                                        {104, 4}, {105, 5}, {106, 6}, {107, 7}};
  EXPECT_EQ(got, expected);
  EXPECT_EQ(lost, 3);  // 108 (camera frame 8 skipped), 109 and 110 (drifted too far)
  EXPECT_EQ(source.frames_unmatched(), 2);  // camera frames 9 and 10
  EXPECT_NE(source.describe().find("uvc, frames numbered by trigger time (tolerance 4000 us)"),
            std::string::npos);
  (void)raw;
}

TEST(TriggerMatchedSource, AFrameOfALaterTriggerWaitsForIt) {
  auto camera = std::make_unique<FreeRunningCamera>();
  camera->timestamps = {{0, 1066 * kMs}, {1, 1099 * kMs}};
  TriggerMatchedSource source(std::move(camera), 5 * kMs);
  source.note_trigger(7, 1000 * kMs);  // the camera started late: nothing for trigger 7 ...
  EXPECT_FALSE(source.grab(7).has_value());
  source.note_trigger(8, 1033 * kMs);  // ... nor 8
  EXPECT_FALSE(source.grab(8).has_value());
  source.note_trigger(9, 1066 * kMs);  // the frame held since trigger 7 belongs to 9
  auto frame = source.grab(9);
  ASSERT_TRUE(frame.has_value());
  EXPECT_EQ(frame->image.at<uint8_t>(0, 0), 0);
  source.note_trigger(10, 1099 * kMs);
  frame = source.grab(10);
  ASSERT_TRUE(frame.has_value());
  EXPECT_EQ(frame->image.at<uint8_t>(0, 0), 1);
  EXPECT_EQ(source.frames_unmatched(), 0);
  EXPECT_FALSE(source.grab(11).has_value());  // a trigger never announced: nothing to match
}

}  // namespace
}  // namespace syncap::edge
