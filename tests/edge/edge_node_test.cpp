#include "app/edge_node.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <map>
#include <thread>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include "app/edge_options.hpp"
#include "syncap/proto/contour_codec.hpp"
#include "syncap/proto/image_patch.hpp"

namespace syncap::edge {
namespace {

// A source with a fixed image per frame number; frame numbers without one are lost frames.
class FakeSource : public FrameSource {
 public:
  std::map<int64_t, cv::Mat> images;
  bool corrupt = false;
  cv::Rect roi;                // crops like a sensor window
  std::string trouble;         // problem()
  std::vector<int64_t> noted;  // note_trigger
  std::optional<Frame> grab(int64_t frame_number) override {
    if (corrupt) throw FrameSourceError("fake image " + std::to_string(frame_number) + " corrupt");
    auto it = images.find(frame_number);
    if (it == images.end()) return std::nullopt;
    Frame f;
    f.frame_number = frame_number;
    f.image = it->second;
    if (!roi.empty()) {
      f.sensor_size = f.image.size();
      f.origin = roi.tl();
      f.image = f.image(roi).clone();
    }
    return f;
  }
  std::string describe() const override { return "fake"; }
  cv::Rect set_roi(const cv::Rect& r) override {
    if (r.x < 0) throw FrameSourceError("fake: region refused");
    return roi = r;
  }
  std::string problem() const override { return trouble; }
  std::vector<double> exposures, gains;  // set_exposure_us, set_gain_db
  void set_exposure_us(double us) override {
    if (us > 1e6) throw FrameSourceError("fake: exposure refused");
    exposures.push_back(us);
  }
  void set_gain_db(double db) override { gains.push_back(db); }
  void note_trigger(int64_t frame_number, int64_t) override { noted.push_back(frame_number); }
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
                      [this](const camera_status_t& s) { statuses_.push_back(s); },
                      [this](const silhouette_part_t& p) { silhouettes_.push_back(p); },
                      {}},
        key_);
  }
  trigger_t trigger(int64_t k, bool last = false) {
    trigger_t t{};
    t.frame_number = k;
    t.flags = last ? trigger_t::FLAG_LAST : 0;
    return t;
  }
  // As the host does: every command and clip polygon signed with the installation's key.
  template <class Message>
  Message signed_(Message message) {
    signer_.sign(message);
    return message;
  }
  proto::CommandKey key_ = proto::CommandKey::generate();
  proto::CommandSigner signer_{key_};
  EdgeOptions options_;
  FakeSource source_;
  std::vector<blob_frame_t> frames_;
  std::vector<camera_status_t> statuses_;
  std::vector<silhouette_part_t> silhouettes_;
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

TEST_F(EdgeNodeTest, SetRoiKeepsBlobsInSensorCoordinates) {
  cv::Mat image(240, 320, CV_8UC1, cv::Scalar(0));
  image(cv::Rect(200, 150, 3, 3)).setTo(cv::Scalar(200));  // centre (201, 151)
  image(cv::Rect(20, 20, 3, 3)).setTo(cv::Scalar(200));    // outside the window below
  source_.images[0] = image;
  source_.images[1] = image;
  node_->on_trigger(trigger(0));
  ASSERT_EQ(frames_.back().num_blobs, 2);
  edge_command_t roi{};
  roi.camera_id = 4;
  roi.command = edge_command_t::SET_ROI;
  roi.roi_x = 160;
  roi.roi_y = 128;
  roi.roi_width = 96;
  roi.roi_height = 64;
  EXPECT_FALSE(node_->on_command(signed_(roi)));
  EXPECT_EQ(source_.roi, cv::Rect(160, 128, 96, 64));
  node_->on_trigger(trigger(1));
  const blob_frame_t& f = frames_.back();
  ASSERT_EQ(f.num_blobs, 1);
  EXPECT_NEAR(f.blobs[0].x, 201.0f, 0.01f);
  EXPECT_NEAR(f.blobs[0].y, 151.0f, 0.01f);
  EXPECT_EQ(f.blobs[0].bbox_x, 200);
  EXPECT_EQ(f.blobs[0].bbox_y, 150);
  EXPECT_EQ(f.image_width, 320);  // the sensor, not the window
  EXPECT_EQ(f.image_height, 240);
  roi.roi_width = 0;  // back to the whole sensor
  node_->on_command(signed_(roi));
  EXPECT_TRUE(source_.roi.empty());
  roi.roi_x = -5;
  roi.roi_width = 10;
  node_->on_command(signed_(roi));  // its acknowledgement carries the refusal
  EXPECT_EQ(statuses_.back().state, camera_status_t::STATE_ERROR);
  EXPECT_NE(statuses_.back().message.find("SET_ROI refused: fake: region refused"),
            std::string::npos)
      << statuses_.back().message;
}

TEST_F(EdgeNodeTest, TellsTheSourceEveryTriggerAndReportsItsProblem) {
  source_.images[3] = image_with_spots(1);
  node_->on_trigger(trigger(3));
  node_->on_trigger(trigger(4));
  EXPECT_EQ(source_.noted, (std::vector<int64_t>{3, 4}));
  node_->publish_status();
  EXPECT_NE(statuses_.back().message.find("no exposure for frame 4"), std::string::npos);
  source_.trouble = "camera lost (unplugged); reopening in 0.5 s";
  node_->on_trigger(trigger(5));
  node_->publish_status();
  EXPECT_EQ(statuses_.back().state, camera_status_t::STATE_ERROR);
  EXPECT_EQ(statuses_.back().message, source_.trouble);
  source_.trouble.clear();
  source_.images[6] = image_with_spots(1);
  node_->on_trigger(trigger(6));
  node_->publish_status();
  EXPECT_EQ(statuses_.back().state, camera_status_t::STATE_ACQUIRING);
  EXPECT_EQ(statuses_.back().last_frame_number, 6);
}

TEST_F(EdgeNodeTest, HeartbeatCarriesThePublishingQueue) {
  node_ = std::make_unique<EdgeNode>(
      options_, source_,
      EdgePublisher{[this](const blob_frame_t& f) { frames_.push_back(f); },
                    [this](const camera_status_t& s) { statuses_.push_back(s); },
                    [this](const silhouette_part_t& p) { silhouettes_.push_back(p); },
                    [] {
                      return PublishQueueStats{5, 64, 17, 1000};
                    }},
      key_);
  node_->publish_status();
  EXPECT_EQ(statuses_.back().message, "queue 5/64, 17 dropped");
  node_->on_trigger(trigger(1));  // lost
  node_->publish_status();
  EXPECT_EQ(statuses_.back().message.rfind("no exposure for frame 1", 0), 0u);
  EXPECT_NE(statuses_.back().message.find("; queue 5/64, 17 dropped"), std::string::npos);
}

TEST_F(EdgeNodeTest, StopIgnoresTriggersUntilStart) {
  source_.images[0] = image_with_spots(1);
  source_.images[1] = image_with_spots(1);
  edge_command_t stop{};
  stop.camera_id = edge_command_t::ALL_CAMERAS;
  stop.command = edge_command_t::STOP;
  EXPECT_FALSE(node_->on_command(signed_(stop)));
  node_->on_trigger(trigger(0));
  EXPECT_TRUE(frames_.empty());
  node_->publish_status();
  EXPECT_EQ(statuses_.back().state, camera_status_t::STATE_IDLE);
  EXPECT_EQ(statuses_.back().frames_lost, 0) << "a stopped camera loses nothing";
  edge_command_t start = stop;
  start.command = edge_command_t::START;
  node_->on_command(signed_(start));
  node_->on_trigger(trigger(1));
  ASSERT_EQ(frames_.size(), 1u);
  EXPECT_EQ(frames_[0].frame_number, 1);
  node_->publish_status();
  EXPECT_EQ(statuses_.back().state, camera_status_t::STATE_ACQUIRING);
}

// Issue 15: any process on the segment could stop an edge and it obeyed without a word.
TEST_F(EdgeNodeTest, EveryCommandIsLoggedCountedAndAcknowledged) {
  edge_command_t c{};
  c.camera_id = edge_command_t::ALL_CAMERAS;
  c.command = edge_command_t::STOP;
  options_.quiet = true;  // the command log is written even then
  node_ = std::make_unique<EdgeNode>(
      options_, source_,
      EdgePublisher{{}, [this](const camera_status_t& s) { statuses_.push_back(s); }, {}, {}},
      key_);
  testing::internal::CaptureStderr();
  node_->on_command(signed_(c));
  c.camera_id = 4;
  c.command = edge_command_t::SET_THRESHOLD;
  c.int_value = 40;
  node_->on_command(signed_(c));
  c.camera_id = 5;  // another camera's: neither logged nor counted
  node_->on_command(signed_(c));
  const std::string log = testing::internal::GetCapturedStderr();
  const std::string sender = "(sender " + std::to_string(signer_.sender());
  EXPECT_NE(log.find("syncap-edge camera 4: command STOP to all cameras " + sender +
                     ", sequence 1) at 20"),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("command SET_THRESHOLD 40 to this camera " + sender + ", sequence 2) at "),
            std::string::npos)
      << log;
  EXPECT_NE(log.find(": accepted"), std::string::npos) << log;
  EXPECT_EQ(log.find("sequence 3"), std::string::npos) << log;
  EXPECT_EQ(node_->commands_accepted(), 2);
  // Each obeyed command is acknowledged at once by a status naming it.
  ASSERT_EQ(statuses_.size(), 2u);
  EXPECT_EQ(statuses_[0].state, camera_status_t::STATE_IDLE);
  EXPECT_EQ(statuses_[1].last_command_sender, signer_.sender());
  EXPECT_EQ(statuses_[1].last_command_sequence, 2);
  EXPECT_EQ(statuses_[1].last_command_result, camera_status_t::COMMAND_ACCEPTED);
  EXPECT_EQ(statuses_[1].commands_accepted, 2);
}

// Anyone on the segment can publish on SYNCAP_EDGE_CMD: only the installation's key commands.
TEST_F(EdgeNodeTest, ForgedReplayedAndStaleCommandsAreRefusedAndReported) {
  source_.images[1] = image_with_spots(2);
  edge_command_t stop{};
  stop.camera_id = 4;
  stop.command = edge_command_t::STOP;
  proto::CommandSigner attacker(proto::CommandKey::generate());  // another key
  edge_command_t forged = stop;
  attacker.sign(forged);
  EXPECT_FALSE(node_->on_command(forged));
  edge_command_t unsigned_stop = stop;  // no MAC at all
  unsigned_stop.sequence = 99;
  node_->on_command(unsigned_stop);
  edge_command_t tampered = signed_(stop);  // signed, then its value changed
  tampered.command = edge_command_t::SHUTDOWN;
  EXPECT_FALSE(node_->on_command(tampered));
  node_->on_trigger(trigger(1));
  ASSERT_EQ(frames_.size(), 1u) << "a refused STOP stopped the camera";

  const edge_command_t genuine = signed_(stop);
  node_->on_command(genuine);
  node_->on_command(genuine);  // captured and sent again
  edge_command_t stale = stop;
  stale.sender = signer_.sender();
  stale.sequence = 1000;
  stale.sent_realtime_ns = proto::realtime_now_ns() - 60'000'000'000;  // a minute old
  const proto::CommandMac mac = proto::mac_of_encoding(proto::encoding_without_mac(stale), key_);
  std::memcpy(stale.mac, mac.data(), mac.size());
  node_->on_command(stale);
  node_->publish_status();
  const camera_status_t& s = statuses_.back();
  EXPECT_EQ(s.commands_accepted, 1);
  EXPECT_EQ(s.commands_rejected, 5);
  EXPECT_EQ(s.last_command_result, camera_status_t::COMMAND_OUTSIDE_WINDOW);
  EXPECT_EQ(node_->commands_rejected(), 5);
}

TEST_F(EdgeNodeTest, WithoutAKeyEveryCommandIsRefused) {
  node_ = std::make_unique<EdgeNode>(
      options_, source_,
      EdgePublisher{{}, [this](const camera_status_t& s) { statuses_.push_back(s); }, {}, {}});
  edge_command_t shutdown{};
  shutdown.camera_id = 4;
  shutdown.command = edge_command_t::SHUTDOWN;
  EXPECT_FALSE(node_->on_command(signed_(shutdown)));
  node_->publish_status();
  EXPECT_EQ(statuses_.back().last_command_result, camera_status_t::COMMAND_NO_KEY);
  EXPECT_EQ(statuses_.back().commands_rejected, 1);
}

TEST_F(EdgeNodeTest, ExposureAndGainGoToTheCameraAndRefusalsAreReported) {
  edge_command_t c{};
  c.camera_id = 4;
  c.command = edge_command_t::SET_EXPOSURE;
  c.real_value = 2500;
  node_->on_command(signed_(c));
  c.command = edge_command_t::SET_GAIN;
  c.real_value = 6;
  node_->on_command(signed_(c));
  EXPECT_EQ(source_.exposures, std::vector<double>{2500});
  EXPECT_EQ(source_.gains, std::vector<double>{6});
  c.command = edge_command_t::SET_EXPOSURE;
  c.real_value = -1;              // out of range: never reaches the camera
  node_->on_command(signed_(c));  // its acknowledgement carries the refusal
  EXPECT_EQ(source_.exposures.size(), 1u);
  EXPECT_EQ(statuses_.back().state, camera_status_t::STATE_ERROR);
  EXPECT_NE(statuses_.back().message.find("SET_EXPOSURE refused"), std::string::npos)
      << statuses_.back().message;
  c.real_value = 5e6;  // the camera refuses
  node_->on_command(signed_(c));
  EXPECT_NE(statuses_.back().message.find("fake: exposure refused"), std::string::npos)
      << statuses_.back().message;
}

TEST_F(EdgeNodeTest, RemembersTheLastPulse) {
  source_.images[9] = image_with_spots(1);
  EXPECT_FALSE(node_->saw_last_pulse());
  node_->on_trigger(trigger(9, /*last=*/true));
  EXPECT_TRUE(node_->saw_last_pulse());
}

// A textured empty scene with a little noise, and the same scene with a person-sized block.
cv::Mat scene(int seed, bool with_person) {
  cv::Mat image(240, 320, CV_8UC1);
  cv::RNG rng(static_cast<uint64_t>(seed));
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) {
      image.at<uint8_t>(y, x) =
          cv::saturate_cast<uint8_t>(60 + (x / 16 + y / 16) % 2 * 40 + rng.gaussian(1.5));
    }
  }
  if (with_person) image(cv::Rect(100, 40, 60, 150)).setTo(cv::Scalar(230));
  return image;
}

// The outline of scene()'s person: the block at x 100..159, y 40..189, within the contour's
// tolerance.
void expect_the_persons_outline(const proto::Contour& contour) {
  int x0 = 1000, x1 = -1, y0 = 1000, y1 = -1;
  for (const auto& p : contour.points) {
    x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
  }
  EXPECT_NEAR(x0, 100, 2);
  EXPECT_NEAR(x1, 159, 2);
  EXPECT_NEAR(y0, 40, 2);
  EXPECT_NEAR(y1, 189, 2);
}

class EdgeNodeMaskTest : public EdgeNodeTest {
 protected:
  void SetUp() override {
    options_.mask = true;
    options_.blobs = false;
    options_.train_in_background = false;  // the model exists right after the last frame
    node_ = std::make_unique<EdgeNode>(
        options_, source_,
        EdgePublisher{[this](const blob_frame_t& f) { frames_.push_back(f); },
                      [this](const camera_status_t& s) { statuses_.push_back(s); },
                      [this](const silhouette_part_t& p) { silhouettes_.push_back(p); },
                      {}},
        key_);
  }
};

TEST_F(EdgeNodeMaskTest, TrainsOnCommandThenPublishesTheSilhouette) {
  for (int k = 0; k < 10; ++k) source_.images[k] = scene(k, false);
  source_.images[10] = scene(10, true);
  node_->on_trigger(trigger(0));
  EXPECT_TRUE(silhouettes_.empty());  // no model yet: nothing to mask against
  edge_command_t train{};
  train.camera_id = 4;
  train.command = edge_command_t::TRAIN_BACKGROUND;
  train.int_value = 8;
  EXPECT_FALSE(node_->on_command(signed_(train)));
  for (int k = 1; k <= 8; ++k) node_->on_trigger(trigger(k));
  node_->publish_status();
  EXPECT_EQ(statuses_.back().message, "masking");
  EXPECT_TRUE(silhouettes_.empty());
  node_->on_trigger(trigger(10));
  ASSERT_FALSE(silhouettes_.empty());
  // mask mode: every frame's record is a blob frame without blobs; it announces the silhouette
  ASSERT_EQ(frames_.size(), 10u);
  EXPECT_TRUE(frames_.back().blobs.empty());
  EXPECT_EQ(frames_.back().frame_number, 10);
  EXPECT_EQ(frames_.back().silhouette_parts, static_cast<int16_t>(silhouettes_.size()));
  EXPECT_EQ(frames_.front().silhouette_parts, 0);  // before the model: nothing announced
  const proto::Silhouette s = proto::decode_silhouette(silhouettes_);
  EXPECT_EQ(s.frame_number, 10);
  EXPECT_EQ(s.camera_id, 4);
  ASSERT_EQ(s.contours.size(), 1u);
  expect_the_persons_outline(s.contours[0]);
}

// Issue 36: a capture that starts with the person in view. Trained on its own first frames the
// model takes the person for background; trained on a recording of the empty scene
// (--background) the person is masked from the first frame on.
TEST_F(EdgeNodeMaskTest, ABackgroundClipTrainsBeforeTheFirstFrame) {
  const std::filesystem::path clip = std::filesystem::temp_directory_path() /
                                     ("syncap_edge_background_" + std::to_string(::getpid()));
  std::filesystem::create_directories(clip);
  for (int k = 0; k < 10; ++k)
    cv::imwrite((clip / ("empty_" + std::to_string(k) + ".png")).string(), scene(100 + k, false));
  for (int k = 0; k < 12; ++k) source_.images[k] = scene(k, true);
  const auto make_node = [this] {
    return std::make_unique<EdgeNode>(
        options_, source_,
        EdgePublisher{[this](const blob_frame_t& f) { frames_.push_back(f); },
                      [this](const camera_status_t& s) { statuses_.push_back(s); },
                      [this](const silhouette_part_t& p) { silhouettes_.push_back(p); },
                      {}},
        key_);
  };
  // Without the clip: trained on frames 0..7, the person is background in frame 9.
  options_.train_frames = 8;
  node_ = make_node();
  for (int k = 0; k <= 9; ++k) node_->on_trigger(trigger(k));
  // Frames 8 and 9 are masked, and empty: the person standing still was learned as background.
  ASSERT_FALSE(silhouettes_.empty());
  EXPECT_TRUE(proto::decode_silhouette(silhouettes_).contours.empty());
  silhouettes_.clear();

  options_.train_frames = 0;
  options_.background = clip.string();
  node_ = make_node();
  node_->on_trigger(trigger(0));
  std::filesystem::remove_all(clip);
  ASSERT_FALSE(silhouettes_.empty()) << "frame 0 is masked against the clip's model";
  const proto::Silhouette s = proto::decode_silhouette(silhouettes_);
  EXPECT_EQ(s.frame_number, 0);
  ASSERT_EQ(s.contours.size(), 1u);
  expect_the_persons_outline(s.contours[0]);
}

TEST_F(EdgeNodeMaskTest, ABackgroundClipItCannotReadIsNamed) {
  options_.background = "/nonexistent/background.avi";
  try {
    EdgeNode node(options_, source_, EdgePublisher{{}, {}, {}, {}}, key_);
    FAIL() << "the clip cannot be read";
  } catch (const FrameSourceError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/background.avi"), std::string::npos)
        << e.what();
  }
}

// Issue 21: every Nth frame the person's grey values go out as an image patch, before the
// frame's record; the host's SET_PATCH_EVERY changes N, and a blobs-only edge refuses it.
TEST_F(EdgeNodeMaskTest, SendsThePersonsGreyValuesEveryNthFrameBeforeTheRecord) {
  std::vector<std::string> order;  // what was published, in order
  std::vector<image_patch_t> patches;
  options_.patch_every = 3;
  options_.train_frames = 8;
  node_ = std::make_unique<EdgeNode>(
      options_, source_,
      EdgePublisher{[&](const blob_frame_t& f) {
                      order.push_back("record " + std::to_string(f.frame_number));
                    },
                    [this](const camera_status_t& st) { statuses_.push_back(st); },
                    [this](const silhouette_part_t& p) { silhouettes_.push_back(p); },
                    {},
                    [&](const image_patch_t& p) {
                      order.push_back("patch " + std::to_string(p.frame_number));
                      patches.push_back(p);
                    }},
      key_);
  for (int k = 0; k < 8; ++k) source_.images[k] = scene(k, false);
  for (int k = 8; k < 14; ++k) source_.images[k] = scene(k, true);
  for (int k = 0; k < 14; ++k) node_->on_trigger(trigger(k));
  // Frames 9 and 12 are masked and on the grid; 0, 3 and 6 trained the model.
  EXPECT_EQ(node_->patches_sent(), 2);
  ASSERT_FALSE(patches.empty());
  const auto record_9 = std::find(order.begin(), order.end(), "record 9");
  ASSERT_NE(record_9, order.end());
  EXPECT_EQ(*(record_9 - 1), "patch 9") << "the patch goes before the record";
  std::vector<image_patch_t> frame_12;
  for (const image_patch_t& p : patches)
    if (p.frame_number == 12) frame_12.push_back(p);
  const proto::ImagePatch patch = proto::decode_image_patch(frame_12);
  ASSERT_TRUE(patch.complete());
  // The person (x 100..159, y 40..189) and the margin of 4 pixels arrive with their grey values.
  const cv::Mat& image = source_.images[12];
  const cv::Rect person(100, 40, 60, 150);
  EXPECT_EQ(cv::countNonZero(patch.image(person) != image(person)), 0);
  EXPECT_EQ(patch.known.at<uchar>(115, 97), 255);
  EXPECT_EQ(patch.image.at<uchar>(115, 97), image.at<uchar>(115, 97));
  EXPECT_EQ(patch.known.at<uchar>(115, 90), 0);

  edge_command_t every{};
  every.camera_id = 4;
  every.command = edge_command_t::SET_PATCH_EVERY;
  every.int_value = 0;
  node_->on_command(signed_(every));
  EXPECT_EQ(node_->patch_every(), 0);
  source_.images[15] = scene(15, true);
  node_->on_trigger(trigger(15));
  EXPECT_EQ(node_->patches_sent(), 2);
  every.int_value = -2;
  node_->on_command(signed_(every));  // its acknowledgement carries the refusal
  EXPECT_NE(statuses_.back().message.find("SET_PATCH_EVERY -2 refused: outside 0..100000"),
            std::string::npos)
      << statuses_.back().message;
}

// The person box spans x 100..159; a clip polygon over x < 130 keeps only its left half, and
// removing the clip brings the whole box back.
TEST_F(EdgeNodeMaskTest, TheHostsClipPolygonLimitsTheSilhouette) {
  for (int k = 0; k < 8; ++k) source_.images[k] = scene(k, false);
  for (int k = 8; k < 12; ++k) source_.images[k] = scene(k, true);
  edge_command_t train{};
  train.camera_id = 4;
  train.command = edge_command_t::TRAIN_BACKGROUND;
  train.int_value = 8;
  node_->on_command(signed_(train));
  for (int k = 0; k < 8; ++k) node_->on_trigger(trigger(k));
  auto x_range = [&] {
    const proto::Silhouette s = proto::decode_silhouette(silhouettes_);
    int x0 = 1000, x1 = -1;
    for (const auto& c : s.contours) {
      for (const auto& p : c.points) x0 = std::min(x0, p.x), x1 = std::max(x1, p.x);
    }
    silhouettes_.clear();
    return std::pair{x0, x1};
  };
  clip_polygon_t clip{};
  clip.camera_id = 4;
  clip.image_width = 320;
  clip.image_height = 240;
  clip.num_points = 4;
  clip.x = {0, 129, 129, 0};
  clip.y = {0, 0, 239, 239};
  node_->on_clip(signed_(clip));
  node_->on_trigger(trigger(8));
  auto [x0, x1] = x_range();
  EXPECT_NEAR(x0, 100, 2);
  EXPECT_NEAR(x1, 129, 2);
  node_->publish_status();
  EXPECT_EQ(statuses_.back().message, "masking inside the clip polygon");

  clip.camera_id = 5;  // another camera's: ignored
  clip.x = {0, 1, 1};
  clip.y = {0, 0, 1};
  clip.num_points = 3;
  node_->on_clip(signed_(clip));
  node_->on_trigger(trigger(9));
  EXPECT_NEAR(x_range().second, 129, 2);

  clip.camera_id = 4;  // for another sensor size: not applied, and said so
  clip.image_width = 640;
  clip.image_height = 480;
  node_->on_clip(signed_(clip));
  node_->on_trigger(trigger(10));
  EXPECT_NEAR(x_range().second, 159, 2);
  node_->publish_status();
  EXPECT_NE(statuses_.back().message.find("clip polygon for a 640x480 sensor"), std::string::npos)
      << statuses_.back().message;

  clip.num_points = 0;  // no clip
  clip.x.clear();
  clip.y.clear();
  clip.image_width = 320;
  clip.image_height = 240;
  node_->on_clip(signed_(clip));
  node_->on_trigger(trigger(11));
  EXPECT_NEAR(x_range().second, 159, 2);
}

TEST_F(EdgeNodeMaskTest, AMalformedClipPolygonIsReported) {
  clip_polygon_t clip{};
  clip.camera_id = 4;
  clip.sequence = 17;
  clip.image_width = 320;
  clip.image_height = 240;
  clip.num_points = 2;
  clip.x = {0, 5};
  clip.y = {0, 5};
  node_->on_clip(signed_(clip));
  node_->publish_status();
  EXPECT_EQ(statuses_.back().state, camera_status_t::STATE_ERROR);
  EXPECT_NE(statuses_.back().message.find("clip polygon " +
                                          std::to_string(signer_.last_sequence()) + " refused"),
            std::string::npos)
      << statuses_.back().message;
}

// On a board the model is computed beside acquisition. The first model is waited for (the
// next frame is masked); a retraining lets the old model serve until the new one is ready, and
// every frame is published meanwhile.
TEST_F(EdgeNodeMaskTest, RetrainingInTheBackgroundNeverHoldsUpAFrame) {
  options_.train_in_background = true;
  options_.train_frames = 8;
  node_ = std::make_unique<EdgeNode>(
      options_, source_,
      EdgePublisher{[this](const blob_frame_t& f) { frames_.push_back(f); },
                    [this](const camera_status_t& s) { statuses_.push_back(s); },
                    [this](const silhouette_part_t& p) { silhouettes_.push_back(p); },
                    {}},
      key_);
  for (int k = 0; k < 8; ++k) source_.images[k] = scene(k, false);
  for (int k = 0; k < 30; ++k) source_.images[8 + k] = scene(8 + k, true);
  for (int k = 0; k < 9; ++k) node_->on_trigger(trigger(k));
  ASSERT_FALSE(silhouettes_.empty()) << "the frame after the first training is masked";
  // Retrain on frames where the person stands still: once that model serves, it is background.
  edge_command_t train{};
  train.camera_id = 4;
  train.command = edge_command_t::TRAIN_BACKGROUND;
  train.int_value = 8;
  node_->on_command(signed_(train));
  for (int k = 9; k < 17; ++k) node_->on_trigger(trigger(k));
  int64_t k = 17;
  bool old_model_served = false, new_model_served = false;
  for (; k < 500 && !new_model_served; ++k) {
    source_.images[k] = scene(static_cast<int>(k), true);
    silhouettes_.clear();
    node_->on_trigger(trigger(k));
    ASSERT_EQ(frames_.back().frame_number, k) << "every frame is published meanwhile";
    const bool person =
        !silhouettes_.empty() && !proto::decode_silhouette(silhouettes_).contours.empty();
    (person ? old_model_served : new_model_served) = true;
    if (!new_model_served) std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  EXPECT_TRUE(new_model_served) << "the new background model never arrived";
  node_->publish_status();
  EXPECT_EQ(statuses_.back().message, "masking");
  (void)old_model_served;  // whether the old one served depends on the thread's speed
}

TEST_F(EdgeNodeMaskTest, ReportsTrainingProgressAndIgnoresOtherCameras) {
  for (int k = 0; k < 3; ++k) source_.images[k] = scene(k, false);
  edge_command_t train{};
  train.camera_id = 7;  // another camera's
  train.command = edge_command_t::TRAIN_BACKGROUND;
  train.int_value = 5;
  node_->on_command(signed_(train));
  node_->publish_status();
  EXPECT_EQ(statuses_.back().message, "no background model");
  train.camera_id = edge_command_t::ALL_CAMERAS;
  node_->on_command(signed_(train));
  for (int k = 0; k < 3; ++k) node_->on_trigger(trigger(k));
  node_->publish_status();
  EXPECT_EQ(statuses_.back().message, "training background 3/5");
  edge_command_t stop{};
  stop.camera_id = 4;
  stop.command = edge_command_t::SHUTDOWN;
  EXPECT_TRUE(node_->on_command(signed_(stop)));
}

TEST_F(EdgeNodeMaskTest, TrainsOnTheFramesFromTheGivenNumber) {
  options_.train_frames = 6;
  options_.train_from_frame = 20;
  node_ = std::make_unique<EdgeNode>(
      options_, source_,
      EdgePublisher{[this](const blob_frame_t& f) { frames_.push_back(f); },
                    [this](const camera_status_t& s) { statuses_.push_back(s); },
                    [this](const silhouette_part_t& p) { silhouettes_.push_back(p); },
                    {}},
      key_);
  // Frames 0..19 show the person: trained on them, the model would hide it.
  for (int k = 0; k < 20; ++k) source_.images[k] = scene(k, true);
  for (int k = 20; k < 26; ++k) source_.images[k] = scene(k, false);
  source_.images[26] = scene(26, true);
  source_.images.erase(23);  // a lost frame inside the range: trained without it
  for (int k = 0; k < 20; ++k) node_->on_trigger(trigger(k));
  node_->publish_status();
  EXPECT_EQ(statuses_.back().message, "waiting for frame 20 to train background");
  for (int k = 20; k < 23; ++k) node_->on_trigger(trigger(k));
  node_->publish_status();
  EXPECT_EQ(statuses_.back().message, "training background 3/6");
  for (int k = 23; k < 26; ++k) node_->on_trigger(trigger(k));
  node_->publish_status();
  EXPECT_EQ(statuses_.back().message, "no exposure for frame 23 in fake");  // the lost one
  node_->publish_status();
  EXPECT_EQ(statuses_.back().message, "masking");
  EXPECT_TRUE(silhouettes_.empty());
  node_->on_trigger(trigger(26));
  ASSERT_FALSE(silhouettes_.empty());
  const proto::Silhouette s = proto::decode_silhouette(silhouettes_);
  EXPECT_EQ(s.frame_number, 26);
  ASSERT_EQ(s.contours.size(), 1u);
}

TEST_F(EdgeNodeMaskTest, SilhouettesInAWindowAreInSensorPixels) {
  for (int k = 0; k < 4; ++k) source_.images[k] = scene(k, false);
  source_.images[4] = scene(4, true);
  source_.roi = cv::Rect(80, 20, 120, 200);  // holds the person block (100, 40, 60x150)
  edge_command_t train{};
  train.camera_id = 4;
  train.command = edge_command_t::TRAIN_BACKGROUND;
  train.int_value = 4;
  node_->on_command(signed_(train));
  for (int k = 0; k <= 4; ++k) node_->on_trigger(trigger(k));
  ASSERT_FALSE(silhouettes_.empty());
  const proto::Silhouette s = proto::decode_silhouette(silhouettes_);
  EXPECT_EQ(s.image_width, 320);
  ASSERT_EQ(s.contours.size(), 1u);
  int x0 = 1000, y0 = 1000;
  for (const auto& p : s.contours[0].points) x0 = std::min(x0, p.x), y0 = std::min(y0, p.y);
  EXPECT_NEAR(x0, 100, 2);
  EXPECT_NEAR(y0, 40, 2);
  // The window changes: the model (of 120x200 frames) no longer fits, masking pauses.
  source_.roi = cv::Rect(0, 0, 100, 100);
  source_.images[5] = scene(5, true);
  const std::size_t parts = silhouettes_.size();
  node_->on_trigger(trigger(5));
  EXPECT_EQ(silhouettes_.size(), parts);
  node_->publish_status();
  EXPECT_EQ(statuses_.back().message, "masking paused: frame 100x100, background model 120x200");
}

// Windowed detection with the sensor window following the targets: after the first frames the
// source reads only the windows' region, and the blobs are still published in sensor pixels.
TEST(EdgeNodeWindowed, TheSensorWindowFollowsTheTargets) {
  EdgeOptions options;
  options.camera_id = 2;
  options.detection = DetectionMode::kWindowed;
  options.roi_follows_windows = true;
  FakeSource source;
  std::vector<blob_frame_t> frames;
  EdgeNode node(options, source, {[&](const blob_frame_t& f) { frames.push_back(f); }, {}, {}, {}});
  for (int k = 0; k < 6; ++k) {
    cv::Mat image(240, 320, CV_8UC1, cv::Scalar(0));
    image(cv::Rect(150 + 2 * k, 100 + k, 3, 3)).setTo(cv::Scalar(200));  // centre (151+2k, 101+k)
    image(cv::Rect(170 + 2 * k, 110 + k, 3, 3)).setTo(cv::Scalar(200));
    source.images[k] = image;
    trigger_t t{};
    t.frame_number = k;
    node.on_trigger(t);
    ASSERT_EQ(frames.size(), static_cast<size_t>(k + 1));
    ASSERT_EQ(frames.back().num_blobs, 2) << "frame " << k;
    const blob_t& left = frames.back().blobs[0].x < frames.back().blobs[1].x
                             ? frames.back().blobs[0]
                             : frames.back().blobs[1];
    EXPECT_NEAR(left.x, 151 + 2 * k, 1e-3) << "frame " << k;
    EXPECT_NEAR(left.y, 101 + k, 1e-3) << "frame " << k;
    EXPECT_EQ(frames.back().image_width, 320);
  }
  EXPECT_FALSE(source.roi.empty()) << "the source was never windowed";
  EXPECT_LT(source.roi.area(), 320 * 240 / 4);
}

TEST(EdgeOptions, WindowedDetectionOptions) {
  const EdgeOptions o =
      parse_edge_options({"--camera-id", "1", "--source", "replay:/x", "--detection", "windowed",
                          "--full-scan-every", "15", "--roi-follows-windows", "--gain-db", "6"});
  EXPECT_EQ(o.detection, DetectionMode::kWindowed);
  EXPECT_EQ(o.full_scan_every, 15);
  EXPECT_TRUE(o.roi_follows_windows);
  EXPECT_DOUBLE_EQ(o.gain_db, 6.0);
  EXPECT_THROW(
      parse_edge_options({"--camera-id", "1", "--source", "replay:/x", "--detection", "sometimes"}),
      UsageError);
  try {
    parse_edge_options({"--camera-id", "1", "--source", "replay:/x", "--roi-follows-windows"});
    FAIL() << "--roi-follows-windows without windowed detection was accepted";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("--detection windowed"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parse_edge_options({"--camera-id", "1", "--source", "replay:/x", "--detection",
                                   "windowed", "--roi-follows-windows", "--mode", "both"}),
               UsageError);
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
    EXPECT_NE(std::string(e.what()).find("--camera-id: '300'"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parse_edge_options({"--camera-id", "1", "--source", "gige:/dev/video0"}),
               UsageError);
  EXPECT_EQ(parse_edge_options({"--camera-id", "1", "--source", "v4l2:/dev/video0"}).source,
            "v4l2:/dev/video0");
  const auto camera = parse_edge_options(
      {"--camera-id", "2", "--source", "aravis:127.0.0.4", "--trigger-source", "Line1"});
  EXPECT_EQ(camera.source, "aravis:127.0.0.4");
  EXPECT_EQ(camera.trigger_source, "Line1");
  const auto both = parse_edge_options(
      {"--camera-id", "2", "--source", "replay:/x", "--mode", "both", "--train-frames", "60"});
  EXPECT_TRUE(both.blobs && both.mask);
  EXPECT_EQ(both.train_frames, 60);
  EXPECT_THROW(parse_edge_options({"--camera-id", "2", "--source", "replay:/x", "--mode", "all"}),
               UsageError);
  EXPECT_THROW(parse_edge_options({"--source", "replay:/x"}), UsageError);
  try {
    parse_edge_options({"--camera-id", "1", "--source", "replay:/x", "--bogus"});
    FAIL();
  } catch (const UsageError& e) {
    EXPECT_STREQ(e.what(), "syncap-edge: unknown option '--bogus'");
  }
  const auto trained = parse_edge_options({"--camera-id", "2", "--source", "replay:/x", "--mode",
                                           "both", "--train-from-frame", "40", "--train-frames",
                                           "20", "--roi", "8,16,640,480"});
  EXPECT_EQ(trained.train_from_frame, 40);
  EXPECT_EQ(trained.roi, cv::Rect(8, 16, 640, 480));
  EXPECT_THROW(parse_edge_options({"--camera-id", "2", "--source", "replay:/x", "--mode", "both",
                                   "--train-from-frame", "40"}),
               UsageError);  // from which frame, but how many?
  EXPECT_THROW(parse_edge_options({"--camera-id", "2", "--source", "replay:/x", "--roi", "1,2,3"}),
               UsageError);
  const auto patches =
      parse_edge_options({"--camera-id", "2", "--source", "replay:/x", "--mode", "mask",
                          "--patch-every", "30", "--patch-margin-px", "6"});
  EXPECT_EQ(patches.patch_every, 30);
  EXPECT_EQ(patches.patch_margin_px, 6);
  try {
    parse_edge_options({"--camera-id", "2", "--source", "replay:/x", "--patch-every", "30"});
    FAIL();
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("--patch-every needs --mode mask or both"),
              std::string::npos);
  }
}

}  // namespace
}  // namespace syncap::edge
