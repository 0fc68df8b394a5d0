#include "syncap/segmentation/scene_eval.hpp"
#include "bare_medi_picture_options.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>

#include <opencv2/imgcodecs.hpp>

namespace syncap::segmentation {
namespace {

std::filesystem::path fresh_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("syncap_scene_eval_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir / "camera00");
  std::filesystem::create_directories(dir / "truth" / "masks" / "camera00");
  return dir;
}

std::string numbered(const char* prefix, int frame, const char* suffix) {
  char name[64];
  std::snprintf(name, sizeof name, "%s%06d%s", prefix, frame, suffix);
  return name;
}

// Two room frames (0, 1), two person frames (2, 3) with a bright 20x20 square; frame 2's true
// mask is that square, frame 3's the square shifted right by 10 px.
std::filesystem::path write_scene(const std::string& name) {
  const auto dir = fresh_dir(name);
  std::ofstream(dir / "truth" / "frames.csv") << "frame,time_s,phase,phase_type,led_on,gain\n"
                                                 "0,0,0,room,0,1\n1,0.03,0,room,0,1\n"
                                                 "2,0.07,1,person,0,1\n3,0.1,1,person,0,1\n";
  const cv::Mat room(40, 60, CV_8UC1, cv::Scalar(100));
  cv::Mat person = room.clone();
  person(cv::Rect(10, 10, 20, 20)).setTo(200);
  for (int frame = 0; frame < 4; ++frame) {
    cv::imwrite((dir / "camera00" / numbered("frame_", frame, ".pgm")).string(),
                frame < 2 ? room : person);
  }
  cv::Mat truth = cv::Mat::zeros(room.size(), CV_8UC1);
  truth(cv::Rect(10, 10, 20, 20)).setTo(255);
  cv::imwrite((dir / "truth" / "masks" / "camera00" / numbered("mask_", 2, ".png")).string(),
              truth);
  truth.setTo(0);
  truth(cv::Rect(20, 10, 20, 20)).setTo(255);
  cv::imwrite((dir / "truth" / "masks" / "camera00" / numbered("mask_", 3, ".png")).string(),
              truth);
  return dir;
}

using testing::bare_options;

TEST(SceneEval, ScoresEachPersonFrameAgainstItsTrueMask) {
  const auto dir = write_scene("scores");
  const auto scores = evaluate_scene(dir, bare_options());
  ASSERT_EQ(scores.size(), 1u);
  EXPECT_EQ(scores[0].camera, 0);
  EXPECT_EQ(scores[0].frames, 2);
  // Frame 2: IoU 1; frame 3: 200 common of 600 pixels.
  EXPECT_NEAR(scores[0].iou_mean, (1.0 + 1.0 / 3.0) / 2, 1e-9);
  EXPECT_NEAR(scores[0].iou_min, 1.0 / 3.0, 1e-9);
  EXPECT_DOUBLE_EQ(scores[0].false_positives, 100.0);
  EXPECT_DOUBLE_EQ(scores[0].false_negatives, 100.0);
  EXPECT_DOUBLE_EQ(scores[0].truth_pixels, 400.0);
  std::filesystem::remove_all(dir);
}

// The host's regions: a clip over the square's left half; a search region for frame 3 only.
TEST(SceneEval, RegionsApplyToTheirCameraAndFrames) {
  const auto dir = write_scene("regions");
  SceneRegion clip{0, SceneRegion::Kind::kClip, 0, 0, {{0, 0}, {19, 0}, {19, 39}, {0, 39}}};
  SceneRegion other_camera = clip;
  other_camera.camera = 1;
  other_camera.polygon = {{0, 0}, {1, 0}, {1, 1}};
  auto scores = evaluate_scene(dir, bare_options(), {clip, other_camera});
  // Frame 2: the mask is x 10..19 of the true 10..29; frame 3: x 10..19 against 20..39.
  EXPECT_NEAR(scores[0].iou_mean, (0.5 + 0.0) / 2, 1e-9);
  EXPECT_EQ(scores[0].frames_searched, 0);
  // A search region for frame 3 only, around the square (x 10..29): the same masks, one frame
  // searched.
  SceneRegion search{0, SceneRegion::Kind::kSearch, 3, 1, {{2, 2}, {40, 2}, {40, 38}, {2, 38}}};
  scores = evaluate_scene(dir, bare_options(), {search});
  EXPECT_NEAR(scores[0].iou_mean, (1.0 + 1.0 / 3.0) / 2, 1e-9);
  EXPECT_EQ(scores[0].frames_searched, 1);
  std::filesystem::remove_all(dir);
}

TEST(SceneEval, NamesTheFileWithoutARoomPhase) {
  const auto dir = write_scene("no_room");
  std::ofstream(dir / "truth" / "frames.csv") << "frame,time_s,phase,phase_type,led_on,gain\n"
                                                 "0,0,0,person,0,1\n";
  try {
    evaluate_scene(dir, bare_options());
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("frames.csv has no room phase"), std::string::npos)
        << e.what();
  }
  std::ofstream(dir / "truth" / "frames.csv") << "frame,time_s,phase,phase_type,led_on,gain\n"
                                                 "x,0,0,room,0,1\n";
  try {
    evaluate_scene(dir, bare_options());
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("frames.csv:2: frame 'x'"), std::string::npos) << e.what();
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace syncap::segmentation
