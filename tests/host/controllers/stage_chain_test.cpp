// The stage chain composed once (controllers/stage_chain.hpp): which stages each set of options
// and sinks gives, in their one order; the hull built for the stages that need it, with what
// they need; bad combinations named.
#include "controllers/stage_chain.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>
#include <sstream>

#include "hull_scenes.hpp"

namespace syncap::controllers {
namespace {

std::vector<std::string> names(const StageChain& chain) {
  std::vector<std::string> out;
  for (const auto& stage : chain.stages) out.emplace_back(stage->name());
  return out;
}

std::vector<sensor::CameraModel> cameras() { return hull::test::person_cameras(4); }

// Every sink a live host has.
Sinks every_sink(std::ostream& lines) {
  Sinks s;
  s.publish_markers = [](const marker_frame_t&) {};
  s.publish_hull = [](const hull_frame_t&) {};
  s.publish_body = [](const body_frame_t&) {};
  s.send_search_region = [](clip_polygon_t&) {};
  s.frame_lines = &lines;
  s.frame_line_cameras = 4;
  s.json_lines = &lines;
  return s;
}

TEST(StageChain, EveryStageInItsOneOrder) {
  PipelineOptions o;
  tracking::RigidSet set;
  set.name = "plate";
  set.markers = {{"a", {0, 0, 0}}, {"b", {100, 0, 0}}, {"c", {0, 150, 0}}};
  o.markers.rigid_sets.push_back(set);
  o.hull.enabled = true;
  o.body.enabled = true;
  o.search_regions.enabled = true;
  o.surface.enabled = true;
  std::ostringstream lines;
  outputs::PoseRecord poses;
  Sinks sinks = every_sink(lines);
  sinks.poses = &poses;
  const StageChain chain = make_stages(cameras(), o, sinks);
  EXPECT_EQ(names(chain),
            (std::vector<std::string>{"markers", "tracking", "rigid sets", "marker message", "hull",
                                      "hull message", "body fit", "body message", "pose record",
                                      "search regions", "surface", "frame line", "json lines"}));
  EXPECT_NE(chain.markers, nullptr);
  EXPECT_NE(chain.tracking, nullptr);
  EXPECT_NE(chain.rigid_sets, nullptr);
  EXPECT_NE(chain.marker_message, nullptr);
  EXPECT_NE(chain.hull, nullptr);
  EXPECT_NE(chain.body, nullptr);
  EXPECT_NE(chain.surface, nullptr);
}

TEST(StageChain, WithoutCamerasOnlyTheLinesRunAndA3dStageIsRefusedByName) {
  std::ostringstream lines;
  const StageChain chain = make_stages({}, PipelineOptions{}, every_sink(lines));
  EXPECT_EQ(names(chain), (std::vector<std::string>{"frame line", "json lines"}));
  EXPECT_EQ(chain.markers, nullptr);
  for (const char* what : {"hull", "body", "surface"}) {
    PipelineOptions o;
    o.hull.enabled = std::string(what) == "hull";
    o.body.enabled = std::string(what) == "body";
    o.surface.enabled = std::string(what) == "surface";
    try {
      make_stages({}, o, every_sink(lines));
      ADD_FAILURE() << what << " without cameras was accepted";
    } catch (const StageChainError& e) {
      EXPECT_EQ(std::string(e.what()), std::string(what) + ": needs the cameras (a calibration)");
    }
  }
}

TEST(StageChain, TheBodyBringsItsHullAndNoSinkNoOutputStage) {
  PipelineOptions o;
  o.markers.enabled = false;
  o.body.enabled = true;  // the hull not asked for
  const StageChain chain = make_stages(cameras(), o, Sinks{});
  EXPECT_EQ(names(chain), (std::vector<std::string>{"hull", "body fit"}));
}

TEST(StageChain, SearchRegionsNeedTheBodyAndASender) {
  PipelineOptions o;
  o.search_regions.enabled = true;
  std::ostringstream lines;
  EXPECT_THROW(make_stages(cameras(), o, every_sink(lines)), StageChainError);
  o.body.enabled = true;
  EXPECT_THROW(make_stages(cameras(), o, Sinks{}), StageChainError);
  EXPECT_NO_THROW(make_stages(cameras(), o, every_sink(lines)));
}

TEST(StageChain, EachConsumerStatesWhatItNeedsOfTheHull) {
  PipelineOptions o;
  EXPECT_EQ(o.hull_products().surface_samples, 0u);
  EXPECT_FALSE(o.hull_products().triangles);
  o.body.enabled = true;
  o.body.stage.hull_points = 700;
  EXPECT_EQ(o.hull_products().surface_samples, 700u);
  EXPECT_FALSE(o.hull_products().triangles);
  o.surface.enabled = true;
  EXPECT_EQ(o.hull_products().surface_samples, 700u);
  EXPECT_TRUE(o.hull_products().triangles);
  o.body.enabled = false;
  EXPECT_EQ(o.hull_products().surface_samples, 0u);
  EXPECT_TRUE(o.hull_products().triangles);
}

// The person's silhouettes in a frame group, as the edges send them (contours through the
// boundary pixels' centres).
pipeline::FrameWork person_frame(const std::vector<sensor::CameraModel>& cams) {
  pipeline::FrameWork w;
  w.group.frame_number = 1;
  w.ready = std::chrono::steady_clock::now();
  for (const hull::HullView& view : hull::test::views_of(hull::test::person_mesh(), cams)) {
    proto::Silhouette s;
    s.camera_id = view.camera.id;
    s.frame_number = 1;
    s.image_width = view.camera.sensor.width_px;
    s.image_height = view.camera.sensor.height_px;
    std::vector<std::vector<cv::Point>> traced;
    std::vector<cv::Vec4i> hierarchy;
    cv::findContours(view.mask.clone(), traced, hierarchy, cv::RETR_CCOMP, cv::CHAIN_APPROX_SIMPLE);
    for (std::size_t i = 0; i < traced.size(); ++i) {
      proto::Contour contour;
      contour.hole = hierarchy[i][3] >= 0;
      for (const cv::Point& p : traced[i]) contour.points.push_back({p.x, p.y});
      s.contours.push_back(contour);
    }
    w.group.silhouettes[view.camera.id] = s;
  }
  return w;
}

TEST(StageChain, TheHullCarriesWhatItsConsumersAskedFor) {
  const std::vector<sensor::CameraModel> cams = cameras();
  PipelineOptions o;
  o.markers.enabled = false;
  o.hull.stage.method = reconstruction::HullMethod::kVoxel;
  o.hull.stage.voxel_resolution = 48;
  o.hull.stage.max_wait_ms = 0;
  o.body.enabled = true;
  o.body.stage.hull_points = 300;
  StageChain chain = make_stages(cams, o, Sinks{});
  pipeline::FrameWork work = person_frame(cams);
  chain.stages.front()->process(work);  // the hull stage only
  ASSERT_TRUE(work.hull.has_value());
  ASSERT_EQ(work.hull->error, "");
  EXPECT_EQ(work.hull->surface_mm.size(), 300u);
  EXPECT_EQ(work.hull->triangles, nullptr);

  o.body.enabled = false;
  o.surface.enabled = true;
  chain = make_stages(cams, o, Sinks{});
  work = person_frame(cams);
  chain.stages.front()->process(work);
  ASSERT_TRUE(work.hull.has_value());
  EXPECT_TRUE(work.hull->surface_mm.empty());
  ASSERT_NE(work.hull->triangles, nullptr);
  EXPECT_EQ(work.hull->triangles->size(), work.hull->faces);
}

}  // namespace
}  // namespace syncap::controllers
