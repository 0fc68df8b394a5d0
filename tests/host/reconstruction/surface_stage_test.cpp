// The live surface stage on a textured sphere rendered exactly (tests/host/surface's
// scene): the edges' image patches and silhouettes as the grouper hands them out, the sphere's
// stand-in hull as the hull stage leaves it. Points on the true sphere, files written, and the
// frames it cannot take (busy, no hull, too few cameras) counted, never waited for.
#include "reconstruction/surface_stage.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <future>
#include <opencv2/imgproc.hpp>

#include "surface/textured_scene.hpp"
#include "syncap/proto/image_patch.hpp"

namespace syncap::reconstruction {
namespace {

namespace st = surface::test;

// The contours an edge sends for a mask: through the boundary pixels' centres.
proto::Silhouette silhouette_of(const cv::Mat& mask, int camera_id, int64_t frame) {
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(mask.clone(), contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
  proto::Silhouette s;
  s.camera_id = camera_id;
  s.frame_number = frame;
  s.image_width = mask.cols;
  s.image_height = mask.rows;
  for (const auto& c : contours) {
    proto::Contour contour;
    for (const cv::Point& p : c) contour.points.push_back({p.x, p.y});
    s.contours.push_back(contour);
  }
  return s;
}

class SurfaceStageTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    cameras_ = new std::vector<sensor::CameraModel>(st::arc_cameras(4, 15.0, st::Sphere{}));
    images_ = new std::vector<cv::Mat>();
    masks_ = new std::vector<cv::Mat>();
    for (std::size_t i = 0; i < cameras_->size(); ++i) {
      cv::Mat mask;
      images_->push_back(
          st::render((*cameras_)[i], st::Sphere{}, 1.0, 17u + static_cast<unsigned>(i), &mask));
      masks_->push_back(mask);
    }
  }
  static void TearDownTestSuite() {
    delete cameras_;
    delete images_;
    delete masks_;
  }

  // A frame as the grouper and the hull stage leave it: every camera's silhouette and patch
  // (the first `patches` cameras'), the sphere's stand-in hull (unless `hull` is false).
  pipeline::FrameWork frame(int64_t number, std::size_t patches = 4, bool hull = true) const {
    pipeline::FrameWork work;
    work.group.frame_number = number;
    for (std::size_t i = 0; i < cameras_->size(); ++i) {
      const int id = (*cameras_)[i].id;
      work.group.silhouettes[id] = silhouette_of((*masks_)[i], id, number);
      if (i < patches)
        work.group.patches[id] = proto::encode_image_patch(id, number, (*images_)[i], (*masks_)[i]);
    }
    if (hull) {
      work.hull.emplace();
      std::vector<std::array<Eigen::Vector3d, 3>> triangles;
      const st::Sphere sphere;
      for (const auto& f : st::icosphere(sphere.centre, sphere.radius + 20, 3))
        triangles.push_back({f.a, f.b, f.c});
      work.hull->triangles =
          std::make_shared<const std::vector<std::array<Eigen::Vector3d, 3>>>(triangles);
    }
    return work;
  }

  static SurfaceStageOptions options() {
    SurfaceStageOptions o;
    o.min_cameras = 3;
    return o;
  }

  static std::vector<sensor::CameraModel>* cameras_;
  static std::vector<cv::Mat>* images_;
  static std::vector<cv::Mat>* masks_;
};

std::vector<sensor::CameraModel>* SurfaceStageTest::cameras_ = nullptr;
std::vector<cv::Mat>* SurfaceStageTest::images_ = nullptr;
std::vector<cv::Mat>* SurfaceStageTest::masks_ = nullptr;

TEST_F(SurfaceStageTest, MatchesTheFramesPatchesOntoTheTrueSurfaceAndWritesThePoints) {
  const std::filesystem::path dir = ::testing::TempDir() + "surface_stage_points";
  std::filesystem::remove_all(dir);
  SurfaceStageOptions o = options();
  o.out_dir = dir;
  SurfaceStage stage(*cameras_, o);
  pipeline::FrameWork work = frame(30);
  stage.process(work);
  stage.finish();
  const SurfaceStageStats s = stage.stats();
  EXPECT_EQ(s.frames_with_patches, 1);
  ASSERT_EQ(s.matched, 1) << s.last_error;
  ASSERT_EQ(s.frames.size(), 1u);
  EXPECT_EQ(s.frames[0].frame_number, 30);
  EXPECT_EQ(s.frames[0].cameras, 4);
  EXPECT_GT(s.frames[0].points, 200u);
  EXPECT_GT(s.frames[0].median_sigma_mm, 0.0);
  EXPECT_LT(s.frames[0].median_sigma_mm, 1.0);
  EXPECT_EQ(s.frames[0].outside_silhouettes, 0u) << "every point inside every silhouette";
  // The points lie on the true sphere (the hull is 20 mm outside it).
  std::ifstream csv(dir / "surface_30.csv");
  ASSERT_TRUE(csv.good());
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line.rfind("x,y,z,sigma_ray_mm", 0), 0u);
  double sum2 = 0;
  int n = 0;
  const st::Sphere sphere;
  while (std::getline(csv, line)) {
    Eigen::Vector3d x;
    char comma = 0;
    std::istringstream row(line);
    row >> x.x() >> comma >> x.y() >> comma >> x.z();
    const double e = (x - sphere.centre).norm() - sphere.radius;
    sum2 += e * e;
    ++n;
  }
  EXPECT_EQ(static_cast<std::size_t>(n), s.frames[0].points);
  EXPECT_LT(std::sqrt(sum2 / n), 0.5);
  EXPECT_TRUE(std::filesystem::exists(dir / "surface_30.ply"));
  EXPECT_NE(stage.summary().find("1 matched, 0 dropped"), std::string::npos) << stage.summary();
}

TEST_F(SurfaceStageTest, AFrameWhileTheMatcherIsBusyIsDroppedNotWaitedFor) {
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  SurfaceStageOptions o = options();
  o.on_match_start = [released](int64_t) { released.wait(); };
  SurfaceStage stage(*cameras_, o);
  pipeline::FrameWork first = frame(30), second = frame(60);
  stage.process(first);
  stage.process(second);  // returns at once: the matcher is held on frame 30
  EXPECT_EQ(stage.stats().dropped_busy, 1);
  release.set_value();
  stage.finish();
  const SurfaceStageStats s = stage.stats();
  EXPECT_EQ(s.matched, 1);
  EXPECT_EQ(s.frames.at(0).frame_number, 30);
  EXPECT_EQ(s.frames_with_patches, 2);
}

TEST_F(SurfaceStageTest, FramesWithoutHullPatchesOrEnoughCamerasAreCounted) {
  SurfaceStage stage(*cameras_, options());
  pipeline::FrameWork no_patches = frame(1, 0), no_hull = frame(2, 4, false), two = frame(3, 2);
  stage.process(no_patches);
  stage.process(no_hull);
  stage.process(two);
  stage.finish();
  const SurfaceStageStats s = stage.stats();
  EXPECT_EQ(s.frames_with_patches, 2);
  EXPECT_EQ(s.no_hull, 1);
  EXPECT_EQ(s.few_cameras, 1);
  EXPECT_EQ(s.matched, 0);
}

TEST_F(SurfaceStageTest, ALostPatchPartIsCountedAndTheRestMatched) {
  SurfaceStage stage(*cameras_, options());
  pipeline::FrameWork work = frame(5);
  auto& parts = work.group.patches.begin()->second;
  ASSERT_GT(parts.size(), 2u);
  parts.erase(parts.begin() + 1);
  stage.process(work);
  stage.finish();
  const SurfaceStageStats s = stage.stats();
  EXPECT_EQ(s.matched, 1) << s.last_error;
  EXPECT_EQ(s.patches_partial, 1);
  EXPECT_GT(s.frames.at(0).points, 100u);
}

// A camera whose silhouette disagrees with the others (cut 15 px short all round): the points
// the others match near its outline fall outside it, and the stage says so.
TEST_F(SurfaceStageTest, PointsOutsideASilhouetteAreReportedImplausible) {
  SurfaceStage stage(*cameras_, options());
  pipeline::FrameWork work = frame(9);
  cv::Mat cut;
  cv::erode((*masks_)[3], cut, cv::getStructuringElement(cv::MORPH_ELLIPSE, {31, 31}));
  work.group.silhouettes[3] = silhouette_of(cut, 3, 9);
  stage.process(work);
  stage.finish();
  const SurfaceStageStats s = stage.stats();
  ASSERT_EQ(s.matched, 1) << s.last_error;
  EXPECT_GT(s.frames.at(0).outside_silhouettes, 0u);
  EXPECT_EQ(s.frames_implausible, 1);
  EXPECT_NE(stage.summary().find("implausible: "), std::string::npos) << stage.summary();
}

TEST_F(SurfaceStageTest, APatchForAnotherSensorSizeFailsTheFrameNamingTheCamera) {
  SurfaceStage stage(*cameras_, options());
  pipeline::FrameWork work = frame(7);
  for (auto& p : work.group.patches.at(2)) p.image_width = 1280;
  stage.process(work);
  stage.finish();
  const SurfaceStageStats s = stage.stats();
  EXPECT_EQ(s.failed, 1);
  EXPECT_NE(s.last_error.find("frame 7: camera 2: a 1280x480 patch for a 640x480 camera"),
            std::string::npos)
      << s.last_error;
}

}  // namespace
}  // namespace syncap::reconstruction
