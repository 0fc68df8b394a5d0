// The hull stage on frame groups of the synthetic person (hull_scenes.hpp): silhouettes as the
// edges send them, a hull and its measures per group, the flags for missing and few cameras, a
// failure that does not stop the pipeline, the message, the JSON line and the mesh file.
#include "reconstruction/hull_stage.hpp"

#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>
#include <opencv2/imgproc.hpp>

#include "hull/mesh.hpp"
#include "hull_scenes.hpp"
#include "io/frame_json.hpp"
#include "outputs/hull_message_stage.hpp"
#include "syncap/hull_frame_t.hpp"

namespace syncap::reconstruction {
namespace {

// The person's silhouettes from 8 cameras as the edges send them: each mask's contours through
// the boundary pixels' centres (cv::findContours), simplified to 0.5 px (syncap-edge's default).
struct PersonScene {
  std::vector<sensor::CameraModel> cameras = hull::test::person_cameras();
  std::map<int, proto::Silhouette> silhouettes;
  PersonScene() {
    for (const hull::HullView& view : hull::test::views_of(hull::test::person_mesh(), cameras)) {
      proto::Silhouette s;
      s.camera_id = view.camera.id;
      s.image_width = view.camera.sensor.width_px;
      s.image_height = view.camera.sensor.height_px;
      std::vector<std::vector<cv::Point>> traced;
      std::vector<cv::Vec4i> hierarchy;
      cv::findContours(view.mask.clone(), traced, hierarchy, cv::RETR_CCOMP,
                       cv::CHAIN_APPROX_SIMPLE);
      for (std::size_t i = 0; i < traced.size(); ++i) {
        std::vector<cv::Point> simplified;
        cv::approxPolyDP(traced[i], simplified, 0.5, true);
        proto::Contour contour;
        contour.hole = hierarchy[i][3] >= 0;
        for (const cv::Point& p : simplified) contour.points.push_back({p.x, p.y});
        s.contours.push_back(contour);
      }
      silhouettes[view.camera.id] = s;
    }
  }
  pipeline::FrameWork work(int64_t frame) const {
    pipeline::FrameWork w;
    w.group.frame_number = frame;
    w.group.trigger = trigger_t{};
    w.group.trigger->frame_number = frame;
    w.ready = std::chrono::steady_clock::now();
    w.group.silhouettes = silhouettes;
    for (auto& [id, s] : w.group.silhouettes) s.frame_number = frame;
    return w;
  }
};

const PersonScene& scene() {
  static const PersonScene s;
  return s;
}

// The person's lowest and highest point [mm].
std::pair<double, double> person_heights() {
  double low = 1e300, high = -1e300;
  const hull::Mesh person = hull::test::person_mesh();
  for (const hull::Mesh::Vertex_index v : person.vertices()) {
    low = std::min(low, person.point(v).z());
    high = std::max(high, person.point(v).z());
  }
  return {low, high};
}

HullStageOptions fast_options() {
  HullStageOptions o;
  o.method = HullMethod::kVoxel;
  o.voxel_resolution = 64;
  o.view_iou = true;
  o.max_wait_ms = 0;  // a loaded test machine must not skip
  return o;
}

TEST(HullStage, APersonGroupGivesAClosedHullThatReprojectsOntoEverySilhouette) {
  HullStage stage(scene().cameras, fast_options());
  pipeline::FrameWork w = scene().work(12);
  stage.process(w);
  ASSERT_TRUE(w.hull.has_value());
  const pipeline::HullSummary& h = *w.hull;
  EXPECT_EQ(h.flags, 0) << h.error;
  EXPECT_EQ(h.cameras, 8);
  EXPECT_GT(h.vertices, 100u);
  EXPECT_GT(h.faces, h.vertices);
  // The person: 1.8 m tall, about 0.5 m wide; its hull's ends within two cells of the grid
  // (about 30 mm at 64 cells) of the person's, where it is round (feet, head).
  const auto [low, high] = person_heights();
  EXPECT_NEAR(h.min_mm.z(), low, 60.0);
  EXPECT_NEAR(h.max_mm.z(), high, 60.0);
  EXPECT_GT(h.max_mm.x() - h.min_mm.x(), 300.0);
  EXPECT_LT(h.max_mm.x() - h.min_mm.x(), 1200.0);
  EXPECT_GT(h.volume_mm3, 0.03e9);  // tens of litres
  EXPECT_LT(h.volume_mm3, 0.2e9);
  ASSERT_EQ(h.view_iou.size(), 8u);
  for (const auto& [camera, iou] : h.view_iou) EXPECT_GT(iou, 0.93) << "camera " << camera;
  EXPECT_GT(h.hull_us, 0.0);
  EXPECT_EQ(stage.stats().hulls, 1);
}

// The default, exact method: the same person, a closed mesh on the cones' planes, every view's
// reprojection within a pixel's outline of its silhouette.
TEST(HullStage, ThePolyhedralHullIsTheDefaultAndReprojectsOntoEverySilhouette) {
  HullStageOptions o = fast_options();
  o.method = HullStageOptions{}.method;
  ASSERT_EQ(o.method, HullMethod::kPolyhedral);
  HullStage stage(scene().cameras, o);
  pipeline::FrameWork w = scene().work(12);
  stage.process(w);
  ASSERT_TRUE(w.hull.has_value());
  const pipeline::HullSummary& h = *w.hull;
  EXPECT_EQ(h.flags, 0) << h.error;
  EXPECT_EQ(h.cameras, 8);
  // Its ends where the person's are, to the silhouettes' pixel (about 6 mm there).
  const auto [low, high] = person_heights();
  EXPECT_NEAR(h.min_mm.z(), low, 10.0);
  EXPECT_NEAR(h.max_mm.z(), high, 10.0);
  for (const auto& [camera, iou] : h.view_iou) EXPECT_GT(iou, 0.96) << "camera " << camera;
  EXPECT_NE(stage.summary().find("host hull: polyhedral"), std::string::npos);
}

// A working volume that cuts the person: the polyhedral method refuses (its hull would be open),
// the voxel hull of the volume stands in, flagged.
TEST(HullStage, WhereThePolyhedralMethodFailsTheVoxelHullStandsInFlagged) {
  HullStageOptions o = fast_options();
  o.method = HullMethod::kPolyhedral;
  o.hull.volume = hull::WorkingVolume{{0, 0, 900}, 400};
  HullStage stage(scene().cameras, o);
  pipeline::FrameWork w = scene().work(9);
  stage.process(w);
  ASSERT_TRUE(w.hull.has_value());
  EXPECT_TRUE(w.hull->flags & hull_frame_t::FLAG_FALLBACK) << w.hull->error;
  EXPECT_FALSE(w.hull->flags & hull_frame_t::FLAG_FAILED) << w.hull->error;
  EXPECT_NE(w.hull->error.find("polyhedral: "), std::string::npos) << w.hull->error;
  EXPECT_GT(w.hull->volume_mm3, 0.0);
  EXPECT_EQ(stage.stats().fallbacks, 1);
}

TEST(HullStage, AMissingOrIncompleteSilhouetteLeavesItsCameraOutAndFlagsTheFrame) {
  HullStage stage(scene().cameras, fast_options());
  pipeline::FrameWork w = scene().work(3);
  w.group.silhouettes.erase(5);
  w.group.incomplete_silhouettes = {2};
  stage.process(w);
  ASSERT_TRUE(w.hull.has_value());
  EXPECT_EQ(w.hull->flags, hull_frame_t::FLAG_CAMERAS_MISSING);
  EXPECT_EQ(w.hull->cameras, 6);
  EXPECT_EQ(w.hull->view_iou.count(5), 0u);
  EXPECT_EQ(w.hull->view_iou.count(2), 0u);
  EXPECT_EQ(stage.stats().cameras_missing, 2);
}

TEST(HullStage, FewCamerasAreFlaggedAndOneIsAFailureThatDoesNotStopTheNextFrame) {
  HullStage stage(scene().cameras, fast_options());
  pipeline::FrameWork two = scene().work(1);
  std::erase_if(two.group.silhouettes, [](const auto& s) { return s.first >= 2; });
  stage.process(two);
  ASSERT_TRUE(two.hull.has_value());
  EXPECT_TRUE(two.hull->flags & hull_frame_t::FLAG_FEW_CAMERAS);
  EXPECT_FALSE(two.hull->flags & hull_frame_t::FLAG_FAILED) << two.hull->error;

  pipeline::FrameWork one = scene().work(2);
  std::erase_if(one.group.silhouettes, [](const auto& s) { return s.first >= 1; });
  stage.process(one);
  ASSERT_TRUE(one.hull.has_value());
  EXPECT_TRUE(one.hull->flags & hull_frame_t::FLAG_FAILED);
  EXPECT_NE(one.hull->error.find("fewer than two"), std::string::npos) << one.hull->error;

  pipeline::FrameWork next = scene().work(3);
  stage.process(next);
  ASSERT_TRUE(next.hull.has_value());
  EXPECT_EQ(next.hull->flags, 0) << next.hull->error;
  EXPECT_EQ(stage.stats().failed, 1);
  EXPECT_NE(stage.summary().find("last failure: frame 2: fewer than two"), std::string::npos)
      << stage.summary();
}

// A camera whose silhouette is shifted 20 px (a bumped camera; the person is about 90 px wide):
// the hull shrinks, and that camera's reprojection disagrees with its silhouette.
TEST(HullStage, ACameraThatDisagreesWithTheOthersIsFlagged) {
  HullStage stage(scene().cameras, fast_options());
  pipeline::FrameWork w = scene().work(7);
  for (proto::Contour& c : w.group.silhouettes.at(4).contours)
    for (proto::ContourPoint& p : c.points) p.x += 20;
  stage.process(w);
  ASSERT_TRUE(w.hull.has_value());
  const pipeline::HullSummary& h = *w.hull;
  ASSERT_FALSE(h.flags & hull_frame_t::FLAG_FAILED) << h.error;
  EXPECT_TRUE(h.flags & hull_frame_t::FLAG_VIEWS_DISAGREE);
  EXPECT_LT(h.view_iou.at(4), 0.9);
  EXPECT_EQ(stage.stats().views_disagree, 1);
}

TEST(HullStage, EveryNthFrameOnlyAndFramesWithoutSilhouettesPassUntouched) {
  HullStageOptions o = fast_options();
  o.every = 2;
  HullStage stage(scene().cameras, o);
  pipeline::FrameWork odd = scene().work(5);
  stage.process(odd);
  EXPECT_FALSE(odd.hull.has_value());
  pipeline::FrameWork empty = scene().work(6);
  empty.group.silhouettes.clear();
  stage.process(empty);
  EXPECT_FALSE(empty.hull.has_value());
  EXPECT_EQ(stage.stats().frames, 0);
}

TEST(HullStage, AGroupThatWaitedTooLongGetsNoHullSoThatLaterFramesAreNotHeldBack) {
  HullStageOptions o = fast_options();
  o.max_wait_ms = 50;
  HullStage stage(scene().cameras, o);
  pipeline::FrameWork late = scene().work(4);
  late.ready -= std::chrono::milliseconds(80);
  stage.process(late);
  EXPECT_FALSE(late.hull.has_value());
  pipeline::FrameWork fresh = scene().work(5);
  stage.process(fresh);
  EXPECT_TRUE(fresh.hull.has_value());
  EXPECT_EQ(stage.stats().skipped_late, 1);
  EXPECT_NE(stage.summary().find("1 skipped (waited over 50 ms)"), std::string::npos)
      << stage.summary();
}

TEST(HullStage, TheMessageTheJsonLineAndTheMeshFileCarryTheHull) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("syncap_hull_stage_" + std::to_string(getpid()));
  HullStageOptions o = fast_options();
  o.mesh_dir = dir;
  HullStage stage(scene().cameras, o);
  pipeline::FrameWork w = scene().work(8);
  stage.process(w);
  ASSERT_TRUE(w.hull.has_value());
  const pipeline::HullSummary& h = *w.hull;

  std::vector<hull_frame_t> sent;
  outputs::HullMessageStage message([&](const hull_frame_t& m) { sent.push_back(m); });
  message.process(w);
  ASSERT_EQ(sent.size(), 1u);
  EXPECT_EQ(sent[0].frame_number, 8);
  EXPECT_EQ(sent[0].cameras, 8);
  EXPECT_EQ(sent[0].vertices, static_cast<int32_t>(h.vertices));
  EXPECT_DOUBLE_EQ(sent[0].volume_mm3, h.volume_mm3);
  EXPECT_FLOAT_EQ(sent[0].max_mm[2], static_cast<float>(h.max_mm.z()));
  EXPECT_GE(sent[0].host_us, sent[0].hull_us);

  const io::FrameRecord back = io::parse_frame_line(io::frame_line(w, false), "line");
  ASSERT_TRUE(back.hull.has_value());
  EXPECT_EQ(back.hull->flags, h.flags);
  EXPECT_EQ(back.hull->faces, h.faces);
  EXPECT_NEAR(back.hull->volume_mm3, h.volume_mm3, 1.0);
  EXPECT_NEAR(back.hull->min_mm.z(), h.min_mm.z(), 1e-3);
  ASSERT_EQ(back.hull->view_iou.size(), 8u);
  EXPECT_NEAR(back.hull->view_iou.at(3), h.view_iou.at(3), 1e-5);

  const hull::Mesh mesh = hull::read_mesh(dir / "hull_8.ply");
  EXPECT_EQ(mesh.number_of_vertices(), h.vertices);
  std::filesystem::remove_all(dir);
}

TEST(HullStage, AHullLineWithoutItsVolumeNamesTheField) {
  try {
    io::parse_frame_line(R"({"cameras": {}, "complete": true, "frame": 1, "hull": {"flags": 0}})",
                         "groups.jsonl:4");
    FAIL() << "no error";
  } catch (const io::FrameLineError& e) {
    EXPECT_NE(std::string(e.what()).find("groups.jsonl:4"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("hull"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("volume_mm3"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace syncap::reconstruction
