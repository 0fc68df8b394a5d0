// `syncap clip`: the capture volume's outline in every camera's image, sent to the edges as
// their masking's clip polygon (clip_polygon_t on SYNCAP_EDGE_CLIP), so that motion outside the
// volume never becomes silhouette; with --floor the floor's outline (the volume's floor plane
// grown by --floor-extent), within which alone the edge calls pixels shadow.
#pragma once

#include <array>
#include <ostream>
#include <span>
#include <string>
#include <vector>

#include "sensor/camera_model.hpp"
#include "syncap/clip_polygon_t.hpp"

namespace syncap::tools {

struct ClipPolygons {
  // One per camera; none for a camera that cannot see the volume at all; no points (no clip)
  // for a camera the volume reaches behind.
  std::vector<clip_polygon_t> messages;
  std::vector<std::string> notes;  // those two cases, naming the camera
};

// The clip messages of `cameras` for the box [min, max] (mm), or of no points with `remove`.
// With region REGION_FLOOR: the floor's messages, the rectangle of the box's floor (z = zmin)
// grown by `floor_extent_mm` on every side (a shadow falls beyond the volume's footprint).
ClipPolygons clip_polygons(const std::vector<sensor::CameraModel>& cameras,
                           const std::array<double, 6>& volume, double margin_px, bool remove,
                           int8_t region = clip_polygon_t::REGION_CLIP,
                           double floor_extent_mm = 0.0);

// Parses its options with CLI11 (--help lists them all with the exit statuses).
int clip_command(std::span<const std::string> args, std::ostream& out, std::ostream& err);

}  // namespace syncap::tools
