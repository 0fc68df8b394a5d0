#include "app/edge_node.hpp"

#include <gtest/gtest.h>

#include <map>

#include "app/edge_options.hpp"

namespace syncap::edge {
namespace {

// A source with a fixed image per frame number; frame numbers without one are lost frames.
class FakeSource : public FrameSource {
 public:
  std::map<int64_t, cv::Mat> images;
  bool corrupt = false;
  std::optional<Frame> grab(int64_t frame_number) override {
    if (corrupt) throw FrameSourceError("fake image " + std::to_string(frame_number) + " corrupt");
    auto it = images.find(frame_number);
    if (it == images.end()) return std::nullopt;
    Frame f;
    f.frame_number = frame_number;
    f.image = it->second;
    return f;
  }
  std::string describe() const override { return "fake"; }
};

cv::Mat image_with_spots(int spots) {
  cv::Mat image(240, 320, CV_8UC1, cv::Scalar(0));
  for (int i = 0; i < spots; ++i) {
    image(cv::Rect(4 + (i % 30) * 10, 4 + (i / 30) * 10, 3, 3)).setTo(cv::Scalar(200));
  }
  return image;
}

class EdgeNodeTest : public ::testing::Test {
 protected:
  EdgeNodeTest() {
    options_.camera_id = 4;
    node_ = std::make_unique<EdgeNode>(
        options_, source_,
        EdgePublisher{[this](const blob_frame_t& f) { frames_.push_back(f); },
                      [this](const camera_status_t& s) { statuses_.push_back(s); }});
  }
  trigger_t trigger(int64_t k, bool last = false) {
    trigger_t t{};
    t.frame_number = k;
    t.flags = last ? trigger_t::FLAG_LAST : 0;
    return t;
  }
  EdgeOptions options_;
  FakeSource source_;
  std::vector<blob_frame_t> frames_;
  std::vector<camera_status_t> statuses_;
  std::unique_ptr<EdgeNode> node_;
};

TEST_F(EdgeNodeTest, PublishesTheBlobsOfTheTriggeredFrame) {
  source_.images[7] = image_with_spots(3);
  node_->on_trigger(trigger(7));
  ASSERT_EQ(frames_.size(), 1u);
  EXPECT_EQ(frames_[0].camera_id, 4);
  EXPECT_EQ(frames_[0].frame_number, 7);
  EXPECT_EQ(frames_[0].num_blobs, 3);
  EXPECT_EQ(frames_[0].image_width, 320);
}

TEST_F(EdgeNodeTest, ManyBlobsGoOutInParts) {
  source_.images[1] = image_with_spots(150);
  node_->on_trigger(trigger(1));
  ASSERT_EQ(frames_.size(), 3u);
  EXPECT_EQ(frames_[2].part_index, 2);
  EXPECT_EQ(frames_[0].total_blobs, 150);
}

TEST_F(EdgeNodeTest, LostAndCorruptFramesAreCountedAndReported) {
  source_.images[0] = image_with_spots(1);
  node_->on_trigger(trigger(0));
  node_->on_trigger(trigger(1));  // no image: lost
  node_->publish_status();
  ASSERT_EQ(statuses_.size(), 1u);
  EXPECT_EQ(statuses_[0].frames_received, 1);
  EXPECT_EQ(statuses_[0].frames_lost, 1);
  EXPECT_EQ(statuses_[0].last_frame_number, 0);
  EXPECT_EQ(statuses_[0].state, camera_status_t::STATE_ERROR);
  EXPECT_NE(statuses_[0].message.find("frame 1"), std::string::npos) << statuses_[0].message;
  source_.corrupt = true;
  node_->on_trigger(trigger(2));
  node_->publish_status(/*final=*/true);
  EXPECT_EQ(statuses_[1].state, camera_status_t::STATE_STOPPED);
  EXPECT_NE(statuses_[1].message.find("fake image 2 corrupt"), std::string::npos);
  EXPECT_EQ(statuses_[1].frames_lost, 2);
}

TEST_F(EdgeNodeTest, RemembersTheLastPulse) {
  source_.images[9] = image_with_spots(1);
  EXPECT_FALSE(node_->saw_last_pulse());
  node_->on_trigger(trigger(9, /*last=*/true));
  EXPECT_TRUE(node_->saw_last_pulse());
}

TEST(EdgeOptions, ParsesAndNamesBadOptions) {
  const auto o =
      parse_edge_options({"--camera-id", "3", "--source", "replay:/tmp/x", "--threshold", "90"});
  EXPECT_EQ(o.camera_id, 3);
  EXPECT_EQ(o.detector.threshold, 90);
  try {
    parse_edge_options({"--camera-id", "300", "--source", "replay:/x"});
    FAIL();
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("--camera-id '300'"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parse_edge_options({"--camera-id", "1", "--source", "gige:/dev/video0"}),
               UsageError);
  EXPECT_EQ(parse_edge_options({"--camera-id", "1", "--source", "v4l2:/dev/video0"}).source,
            "v4l2:/dev/video0");
  const auto camera = parse_edge_options(
      {"--camera-id", "2", "--source", "aravis:127.0.0.4", "--trigger-source", "Line1"});
  EXPECT_EQ(camera.source, "aravis:127.0.0.4");
  EXPECT_EQ(camera.trigger_source, "Line1");
  EXPECT_THROW(parse_edge_options({"--source", "replay:/x"}), UsageError);
  EXPECT_THROW(parse_edge_options({"--camera-id", "1", "--source", "replay:/x", "--bogus"}),
               UsageError);
}

}  // namespace
}  // namespace syncap::edge
