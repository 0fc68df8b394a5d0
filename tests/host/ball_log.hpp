// A recorded session of a ball seen by calibrated cameras, as the offline commands read it
// (syncap markers --hull, syncap fit): the tests' log of silhouettes.
#pragma once

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "hull/hull_scenes.hpp"
#include "hull/mesh.hpp"
#include "io/lcm_log_reader.hpp"
#include "malformed_messages.hpp"
#include "sensor/camera_model.hpp"
#include "syncap/proto/channels.hpp"
#include "syncap/proto/contour_codec.hpp"

namespace syncap::tools::test_logs {

// The contours of a mask as an edge sends them: through the boundary pixels' centres.
inline std::vector<proto::Contour> contours_of(const cv::Mat& mask) {
  std::vector<std::vector<cv::Point>> traced;
  std::vector<cv::Vec4i> hierarchy;
  cv::findContours(mask, traced, hierarchy, cv::RETR_CCOMP, cv::CHAIN_APPROX_SIMPLE);
  std::vector<proto::Contour> contours;
  for (std::size_t i = 0; i < traced.size(); ++i) {
    proto::Contour c;
    c.hole = hierarchy[i][3] >= 0;
    for (const cv::Point& p : traced[i]) c.points.push_back({p.x, p.y});
    contours.push_back(std::move(c));
  }
  return contours;
}

// A recorded session of `frames` frames: every camera's (empty) blob frame and the silhouette of
// a ball of radius 300 mm at (0, 0, 950) mm.
inline void write_ball_log(const std::filesystem::path& file,
                           const std::vector<sensor::CameraModel>& cameras, int frames) {
  const hull::Mesh ball = hull::test::sphere_mesh(300.0, {0, 0, 950});
  std::vector<std::uint8_t> log;
  std::int64_t event = 0;
  const auto add = [&](const std::string& channel, const std::vector<std::uint8_t>& data) {
    const auto record = io::encode_log_record(event++, 0, channel, data);
    log.insert(log.end(), record.begin(), record.end());
  };
  for (const sensor::CameraModel& camera : cameras) {
    const auto contours = contours_of(hull::render_mask(ball, camera));
    for (int64_t frame = 0; frame < frames; ++frame) {
      blob_frame_t blobs{};
      blobs.camera_id = static_cast<int16_t>(camera.id);
      blobs.frame_number = frame;
      blobs.image_width = static_cast<int16_t>(camera.sensor.width_px);
      blobs.image_height = static_cast<int16_t>(camera.sensor.height_px);
      blobs.part_count = 1;
      add(proto::blob_channel(camera.id), test::encoded(blobs));
      for (const silhouette_part_t& part : proto::encode_silhouette(
               camera.id, frame, camera.sensor.width_px, camera.sensor.height_px, contours))
        add(proto::silhouette_channel(camera.id), test::encoded(part));
    }
  }
  std::ofstream(file, std::ios::binary)
      .write(reinterpret_cast<const char*>(log.data()), static_cast<std::streamsize>(log.size()));
}

}  // namespace syncap::tools::test_logs
