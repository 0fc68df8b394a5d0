#include "groups.hpp"

#include "input_error.hpp"
#include "io/frame_json.hpp"

namespace syncap::compare {
namespace {

std::vector<Outline> outlines(const proto::Silhouette& silhouette) {
  std::vector<Outline> result;
  for (const proto::Contour& c : silhouette.contours) {
    Outline& o = result.emplace_back(Outline{c.hole, {}});
    for (const proto::ContourPoint& p : c.points) o.points.emplace_back(p.x, p.y);
  }
  return result;
}

CameraBlobs camera_blobs(const io::CameraRecord& record) {
  CameraBlobs camera;
  camera.processing_us = record.processing_us;
  for (const io::BlobRecord& b : *record.blobs) camera.blobs.push_back({b.x, b.y, b.area});
  if (record.silhouette) camera.silhouette = outlines(*record.silhouette);
  return camera;
}

std::vector<Marker> measured_markers(const std::vector<pipeline::Marker3d>& markers) {
  std::vector<Marker> result;
  for (const pipeline::Marker3d& m : markers) {
    // The tracker's predictions of hidden markers are not measurements: not scored.
    if (m.predicted) continue;
    result.push_back({m.position.x(), m.position.y(), m.position.z(),
                      static_cast<int>(m.camera_ids.size()), m.id});
  }
  return result;
}

Group group(const io::FrameRecord& record) {
  Group g;
  g.frame = record.frame;
  g.complete = record.complete;
  g.missing_cameras = record.missing_cameras;
  for (const auto& [id, camera] : record.cameras) {
    // Only a silhouette: its blob frame was lost (the group names the camera missing), so the
    // camera did not report this frame; its orphan silhouette is left out of the scores.
    if (camera.blobs) g.cameras[id] = camera_blobs(camera);
  }
  if (record.markers) g.markers = measured_markers(*record.markers);
  return g;
}

}  // namespace

Group parse_group(std::string_view line, const std::string& where) {
  try {
    return group(io::parse_frame_line(line, where));
  } catch (const io::FrameLineError& e) {
    throw InputError(e.what());
  }
}

std::vector<Group> read_groups(const std::filesystem::path& file) {
  std::vector<io::FrameRecord> records;
  try {
    records = io::read_frame_lines(file);
  } catch (const io::FrameLineError& e) {
    throw InputError(e.what());
  }
  std::vector<Group> groups;
  for (const io::FrameRecord& r : records) groups.push_back(group(r));
  return groups;
}

}  // namespace syncap::compare
