#include "outputs/search_region_stage.hpp"

#include "body/hanim_model.hpp"

namespace syncap::outputs {

clip_polygon_t search_region_message(const sensor::CameraModel& camera,
                                     const std::vector<body::Ellipsoid>& ellipsoids, int64_t frame,
                                     const SearchRegionStageOptions& options, bool* whole_image) {
  clip_polygon_t m{};
  m.camera_id = static_cast<int16_t>(camera.id);
  m.region = clip_polygon_t::REGION_SEARCH;
  m.frame_number = frame + options.lead;
  m.valid_frames = static_cast<int16_t>(options.valid_frames);
  m.image_width = static_cast<int16_t>(camera.sensor.width_px);
  m.image_height = static_cast<int16_t>(camera.sensor.height_px);
  const fitting::SearchRegion region = fitting::search_region(camera, ellipsoids, options.region);
  if (whole_image != nullptr) *whole_image = region.whole_image;
  for (const cv::Point& p : region.polygon) {
    m.x.push_back(static_cast<int16_t>(p.x));
    m.y.push_back(static_cast<int16_t>(p.y));
  }
  m.num_points = static_cast<int16_t>(m.x.size());
  return m;
}

SearchRegionStage::SearchRegionStage(std::vector<sensor::CameraModel> cameras,
                                     SearchRegionStageOptions options, Publish publish)
    : cameras_(std::move(cameras)),
      options_(options),
      publish_(std::move(publish)),
      skeleton_(body::hanim_skeleton()),
      parameters_(skeleton_) {}

void SearchRegionStage::process(pipeline::FrameWork& work) {
  if (!work.body ||
      work.body->parameters.size() != static_cast<std::size_t>(fitting::kPoseParameterCount)) {
    return;  // no fit: the regions sent before expire on their own
  }
  const body::BodyFrame body =
      body::body_frame(skeleton_, parameters_.pose(work.body->parameters.data()));
  for (const sensor::CameraModel& camera : cameras_) {
    clip_polygon_t m =
        search_region_message(camera, body.ellipsoids, work.group.frame_number, options_);
    publish_(m);
  }
  ++frames_sent_;
}

}  // namespace syncap::outputs
