#include "sensor/reconnecting_source.hpp"

#include <gtest/gtest.h>

#include <set>
#include <vector>

#include "app/edge_node.hpp"

namespace syncap::edge {
namespace {

// A camera that numbers its exposures from `first` and vanishes (grab throws) at `dies_at`.
class FlakyCamera : public FrameSource {
 public:
  FlakyCamera(int64_t first, int64_t dies_at) : first_(first), dies_at_(dies_at) {}
  std::optional<Frame> grab(int64_t frame_number) override {
    if (frame_number >= dies_at_) throw FrameSourceError("cam: VIDIOC_DQBUF: No such device");
    if (frame_number < first_) return std::nullopt;  // before acquisition started
    if (missing.contains(frame_number)) return std::nullopt;
    Frame frame;
    frame.frame_number = frame_number;
    frame.exposure_us = static_cast<int32_t>(exposure_us);
    frame.image = cv::Mat(24, 32, CV_8UC1, cv::Scalar(0));
    frame.image(cv::Rect(10, 10, 3, 3)).setTo(cv::Scalar(250));
    if (!roi.empty()) frame.image = frame.image(roi).clone(), frame.origin = roi.tl();
    return frame;
  }
  std::string describe() const override { return "flaky camera"; }
  cv::Rect set_roi(const cv::Rect& r) override { return roi = r; }
  void set_exposure_us(double us) override { exposure_us = us; }
  void set_gain_db(double db) override { gain_db = db; }
  double exposure_us = 0, gain_db = -1;
  int64_t frames_incomplete() const override { return 2; }
  cv::Rect roi;
  std::set<int64_t> missing;  // lost exposures

 private:
  int64_t first_, dies_at_;
};

class ReconnectingSourceTest : public ::testing::Test {
 protected:
  // The camera dies at frame 3; the next two opens fail (still unplugged), the third works.
  ReconnectingSourceTest() {
    options_.first_delay_s = 0.5;
    options_.max_delay_s = 10;
    options_.silent_s = 0;
  }
  std::unique_ptr<ReconnectingSource> make() {
    return std::make_unique<ReconnectingSource>(
        [this](int64_t next) -> std::unique_ptr<FrameSource> {
          opens_.push_back({now_ns_, next});
          if (opens_.size() > 1 && opens_.size() <= failing_opens_ + 1)
            throw FrameSourceError("camera 10.0.0.7: opening: no answer");
          return std::make_unique<FlakyCamera>(next, opens_.size() == 1 ? 3 : 1'000'000);
        },
        options_, [this] { return now_ns_; });
  }
  void advance_s(double s) { now_ns_ += static_cast<int64_t>(s * 1e9); }
  struct Open {
    int64_t at_ns;
    int64_t next_frame;
  };
  ReconnectOptions options_;
  std::size_t failing_opens_ = 2;
  int64_t now_ns_ = 1'000'000'000;
  std::vector<Open> opens_;
};

TEST_F(ReconnectingSourceTest, ReopensWithDoublingDelaysAndContinuesTheNumbering) {
  auto source = make();
  ASSERT_EQ(opens_.size(), 1u);
  EXPECT_EQ(opens_[0].next_frame, 0);
  for (int64_t k = 0; k < 3; ++k) EXPECT_TRUE(source->grab(k).has_value());
  source->set_roi(cv::Rect(8, 8, 16, 16));
  EXPECT_FALSE(source->grab(3).has_value());  // the camera vanishes
  EXPECT_FALSE(source->connected());
  EXPECT_EQ(source->problem(),
            "camera lost (cam: VIDIOC_DQBUF: No such device); reopening in 0.5 s");
  // Triggers at 10 Hz: attempts at +0.5 s, then 1 s and 2 s after each failure.
  int64_t k = 4;
  std::vector<int64_t> attempts_at_frame;
  for (; k < 60 && source->reopened() == 0; ++k) {
    advance_s(0.1);
    const std::size_t before = opens_.size();
    EXPECT_FALSE(source->grab(k).has_value());
    if (opens_.size() > before) attempts_at_frame.push_back(k);
  }
  // Died at frame 3 (t=0): tries at 0.5 s (frame 8), 1.5 s (18), 3.5 s (38), the last succeeds.
  EXPECT_EQ(attempts_at_frame, (std::vector<int64_t>{8, 18, 38}));
  EXPECT_TRUE(source->connected());
  EXPECT_EQ(source->problem(), "");
  // Lost at t=0 (frame 3), back at 3.5 s on the third attempt; said for 10 s.
  EXPECT_EQ(source->note(), "camera reopened after 3.5 s away, on attempt 3");
  advance_s(9.9);
  EXPECT_EQ(source->note(), "camera reopened after 3.5 s away, on attempt 3");
  advance_s(0.1);
  EXPECT_EQ(source->note(), "");
  advance_s(-10);
  EXPECT_EQ(opens_.back().next_frame, 39);  // numbered from the trigger after the reopen
  const auto frame = source->grab(39);
  ASSERT_TRUE(frame.has_value());
  EXPECT_EQ(frame->frame_number, 39);
  EXPECT_EQ(frame->origin, cv::Point(8, 8));  // the region is applied again
  EXPECT_EQ(source->frames_incomplete(), 4);  // the lost camera's count is kept
}

TEST_F(ReconnectingSourceTest, ExposureAndGainSurviveAReopen) {
  failing_opens_ = 0;
  auto source = make();
  source->set_exposure_us(1800);
  source->set_gain_db(3);
  ASSERT_EQ(source->grab(0)->exposure_us, 1800);
  EXPECT_FALSE(source->grab(3).has_value());  // the camera vanishes
  advance_s(1);
  EXPECT_FALSE(source->grab(4).has_value());  // reopened at this trigger, numbering from 5
  ASSERT_EQ(source->reopened(), 1);
  const auto frame = source->grab(5);
  ASSERT_TRUE(frame.has_value());
  EXPECT_EQ(frame->exposure_us, 1800) << "the new camera got the commanded exposure";
}

TEST_F(ReconnectingSourceTest, BackOffStopsGrowingAtTheMaximum) {
  failing_opens_ = 100;
  options_.max_delay_s = 2;
  auto source = make();
  for (int64_t k = 0; k <= 3; ++k) source->grab(k);
  std::vector<int64_t> gaps_ms;
  int64_t last = now_ns_;
  for (int64_t k = 4; k < 200; ++k) {
    advance_s(0.1);
    const std::size_t before = opens_.size();
    source->grab(k);
    if (opens_.size() > before) gaps_ms.push_back((now_ns_ - last) / 1'000'000), last = now_ns_;
  }
  ASSERT_GE(gaps_ms.size(), 5u);
  EXPECT_EQ(std::vector<int64_t>(gaps_ms.begin(), gaps_ms.begin() + 5),
            (std::vector<int64_t>{500, 1000, 2000, 2000, 2000}));
  EXPECT_NE(source->problem().find("no answer"), std::string::npos) << source->problem();
}

TEST_F(ReconnectingSourceTest, SilenceWhileTriggeredCountsAsGone) {
  // A camera that never delivers again without an error (GigE link down: grabs time out).
  options_.silent_s = 1;
  auto source = std::make_unique<ReconnectingSource>(
      [this](int64_t next) -> std::unique_ptr<FrameSource> {
        opens_.push_back({now_ns_, next});
        return std::make_unique<FlakyCamera>(opens_.size() == 1 ? 1'000'000 : next, 1'000'000);
      },
      options_, [this] { return now_ns_; });
  int64_t k = 0;
  for (; k < 9; ++k, advance_s(0.1)) EXPECT_FALSE(source->grab(k).has_value());
  EXPECT_TRUE(source->connected());
  advance_s(0.1);
  source->grab(k++);  // 1 s without a frame
  EXPECT_FALSE(source->connected());
  EXPECT_NE(source->problem().find("no frame for 1.0 s while triggers kept coming"),
            std::string::npos)
      << source->problem();
  for (; !source->connected(); ++k) advance_s(0.1), source->grab(k);
  EXPECT_TRUE(source->grab(k).has_value());
}

TEST_F(ReconnectingSourceTest, APauseBetweenRunsIsNoSilence) {
  options_.silent_s = 1;
  FlakyCamera* camera = nullptr;
  ReconnectingSource source(
      [&](int64_t) -> std::unique_ptr<FrameSource> {
        auto made = std::make_unique<FlakyCamera>(0, 1'000'000);
        camera = made.get();
        return made;
      },
      options_, [this] { return now_ns_; });
  camera->missing = {4, 5, 6};
  for (int64_t k = 0; k < 4; ++k, advance_s(0.1)) EXPECT_TRUE(source.grab(k).has_value());
  advance_s(60);  // the run ended; the next starts a minute later
  for (int64_t k = 4; k < 7; ++k, advance_s(0.1)) source.grab(k);  // 3 lost, within 0.2 s
  EXPECT_TRUE(source.connected());
  EXPECT_TRUE(source.grab(7).has_value());
}

// The whole path: the node reports STATE_ERROR with the reason, then acquires again.
TEST_F(ReconnectingSourceTest, TheNodeReportsTheLossAndResumes) {
  failing_opens_ = 0;
  auto source = make();
  std::vector<camera_status_t> statuses;
  std::vector<blob_frame_t> frames;
  EdgeOptions options;
  options.quiet = true;
  EdgeNode node(options, *source,
                {[&](const blob_frame_t& f) { frames.push_back(f); },
                 [&](const camera_status_t& s) { statuses.push_back(s); },
                 [](const silhouette_part_t&) {},
                 {}});
  auto trigger = [&](int64_t k) {
    trigger_t t{};
    t.frame_number = k;
    node.on_trigger(t);
    advance_s(0.1);
  };
  for (int64_t k = 0; k < 5; ++k) trigger(k);
  node.publish_status();
  EXPECT_EQ(statuses.back().state, camera_status_t::STATE_ERROR);
  EXPECT_NE(statuses.back().message.find("camera lost (cam: VIDIOC_DQBUF: No such device)"),
            std::string::npos)
      << statuses.back().message;
  for (int64_t k = 5; k < 12; ++k) trigger(k);
  node.publish_status();  // frames of this interval were lost: still an error ...
  EXPECT_EQ(statuses.back().state, camera_status_t::STATE_ERROR);
  trigger(12);
  node.publish_status();  // ... the next interval is clean, and says the camera is back
  EXPECT_EQ(statuses.back().state, camera_status_t::STATE_ACQUIRING);
  EXPECT_EQ(statuses.back().message, "camera reopened after 0.5 s away, on attempt 1");
  EXPECT_EQ(frames.back().frame_number, 12);
  EXPECT_EQ(frames.back().num_blobs, 1);
  EXPECT_EQ(node.frames_received(), 3 + 4);   // 0..2, then 9..12 (reopened at 8)
  EXPECT_EQ(statuses.back().frames_lost, 6);  // 3..8
}

}  // namespace
}  // namespace syncap::edge
