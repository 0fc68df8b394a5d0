// A recording reconstructed as the live system would have (controllers/recording_reconstruction
// .hpp): four cameras' image folders of the synthetic person in front of a textured room, each
// masked as the edge masks against its clip of the empty room, the masks through the host's node
// and stage chain: every frame's hull agrees with every view, and recordings it cannot use are
// named.
#include "controllers/recording_reconstruction.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "recording_scene.hpp"

namespace syncap::controllers {
namespace {

namespace fs = std::filesystem;

// Keeps every frame's hull summary.
class HullRecord : public pipeline::Stage {
 public:
  explicit HullRecord(std::vector<pipeline::HullSummary>& hulls) : hulls_(hulls) {}
  const char* name() const override { return "record"; }
  void process(pipeline::FrameWork& work) override {
    if (work.hull) hulls_.push_back(*work.hull);
  }

 private:
  std::vector<pipeline::HullSummary>& hulls_;
};

class RecordingReconstructionTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("syncap_recording_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    cameras_ = hull::test::person_cameras(4);
    const std::vector<test::RecordingFolders> folders =
        test::write_person_recording(dir_, cameras_);
    for (std::size_t i = 0; i < cameras_.size(); ++i)
      recordings_.push_back({cameras_[i].id, folders[i].capture, folders[i].background});
  }
  void TearDown() override { fs::remove_all(dir_); }

  ReconstructionOptions options() const {
    ReconstructionOptions o;
    o.recordings = recordings_;
    o.masking.train_frames = 8;
    o.pipeline.markers.enabled = false;
    o.pipeline.hull.enabled = true;
    o.pipeline.hull.stage.max_wait_ms = 0;
    o.pipeline.hull.stage.view_iou = true;
    return o;
  }

  fs::path dir_;
  std::vector<sensor::CameraModel> cameras_;
  std::vector<CameraRecording> recordings_;
};

TEST_F(RecordingReconstructionTest, EveryFramesHullAgreesWithEveryView) {
  std::vector<pipeline::HullSummary> hulls;
  std::vector<std::unique_ptr<pipeline::Stage>> extra;
  extra.push_back(std::make_unique<HullRecord>(hulls));
  ReconstructionOptions o = options();
  o.mask_dir = dir_ / "masks";
  int64_t started_first = -1, started_last = -1, progressed = 0;
  ReconstructionCallbacks callbacks;
  callbacks.started = [&](int64_t first, int64_t last) {
    started_first = first;
    started_last = last;
  };
  callbacks.progress = [&](int64_t processed, int64_t fed, int64_t total) {
    EXPECT_LE(processed, fed);
    progressed = processed;
    EXPECT_EQ(total, 3);
  };
  const Reconstruction run = reconstruct_recording(cameras_, o, {}, std::move(extra), callbacks);
  EXPECT_EQ(started_first, 10);  // the folders' first common frame
  EXPECT_EQ(started_last, 12);
  EXPECT_EQ(progressed, 3);
  EXPECT_EQ(run.frames_fed, 3);
  EXPECT_EQ(run.node->stats().complete, 3);
  ASSERT_EQ(hulls.size(), 3u);
  for (const pipeline::HullSummary& h : hulls) {
    EXPECT_EQ(h.cameras, 4);
    ASSERT_EQ(h.view_iou.size(), 4u);
    for (const auto& [id, iou] : h.view_iou) EXPECT_GT(iou, 0.97) << "camera " << id;
    // The person stands from z 40 to 1795 mm; four views leave the hull a little larger.
    EXPECT_NEAR(h.min_mm.z(), 40, 60);
    EXPECT_NEAR(h.max_mm.z(), 1795, 60);
  }
  EXPECT_EQ(run.alignments.size(), 4u);
  EXPECT_TRUE(fs::exists(dir_ / "masks" / "cam0" / "mask_000011.png"));
  EXPECT_GT(run.mask_ms_per_frame, 0.0);
}

TEST_F(RecordingReconstructionTest, FramesAskedForOnly) {
  ReconstructionOptions o = options();
  o.first_frame = 11;
  o.frames = 1;
  const Reconstruction run = reconstruct_recording(cameras_, o, {}, {});
  EXPECT_EQ(run.frames_fed, 1);
  EXPECT_EQ(run.chain.hull->stats().hulls, 1);
}

TEST_F(RecordingReconstructionTest, RecordingsItCannotUseAreNamed) {
  ReconstructionOptions o = options();
  o.recordings[1].camera_id = 9;
  try {
    reconstruct_recording(cameras_, o, {}, {});
    FAIL() << "camera 9 is not calibrated";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("camera 9"), std::string::npos) << e.what();
  }
  o = options();
  o.recordings[2].background = dir_ / "absent";
  try {
    reconstruct_recording(cameras_, o, {}, {});
    FAIL() << "no background";
  } catch (const segmentation::ImageSequenceError& e) {
    EXPECT_NE(std::string(e.what()).find("absent"), std::string::npos) << e.what();
  }
  // A background of another size than its capture.
  fs::create_directories(dir_ / "small");
  for (int k = 0; k < 3; ++k)
    cv::imwrite((dir_ / "small" / ("f_" + std::to_string(k) + ".png")).string(),
                cv::Mat(48, 64, CV_8UC1, cv::Scalar(90)));
  o = options();
  o.recordings[0].background = dir_ / "small";
  try {
    reconstruct_recording(cameras_, o, {}, {});
    FAIL() << "sizes differ";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("640x480 pixels, its background"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace syncap::controllers
