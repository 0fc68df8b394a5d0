// `syncap clip`: the capture volume's outline in every camera's image, sent to the edges as
// their masking's clip polygon (clip_polygon_t on SYNCAP_EDGE_CLIP), so that motion outside the
// volume never becomes silhouette.
#pragma once

#include <array>
#include <ostream>
#include <span>
#include <string>
#include <vector>

#include "sensor/camera_model.hpp"
#include "syncap/clip_polygon_t.hpp"

namespace syncap::tools {

inline constexpr const char* kClipUsage =
    "usage: syncap clip --cameras FILE --volume XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX [options]\n"
    "       syncap clip --cameras FILE --remove [options]\n"
    "Projects the capture volume (mm, the cameras' object frame) into every camera of FILE\n"
    "(cameras.json) and prints each camera's clip polygon as a JSON line; with --publish sends\n"
    "it to the camera's edge process, whose masking then treats pixels outside it as background.\n"
    "  --margin PX     grow each outline by PX pixels (default 8)\n"
    "  --camera ID     only this camera (repeatable)\n"
    "  --remove        clip nothing: polygons of no points\n"
    "  --publish       send clip_polygon_t on SYNCAP_EDGE_CLIP, signed with --key\n"
    "  --key FILE      the installation's command key (syncap keygen; needed by --publish:\n"
    "                  an edge applies only signed polygons, docs/security.md)\n"
    "  --lcm-url URL   LCM provider for --publish (default udpm://239.255.76.67:7667?ttl=0)\n"
    "Exit status: 0 done, 1 a camera could not be clipped (named; the others are sent),\n"
    "2 usage error or unreadable FILE.\n";

struct ClipPolygons {
  // One per camera; none for a camera that cannot see the volume at all; no points (no clip)
  // for a camera the volume reaches behind.
  std::vector<clip_polygon_t> messages;
  std::vector<std::string> notes;  // those two cases, naming the camera
};

// The clip messages of `cameras` for the box [min, max] (mm), or of no points with `remove`.
ClipPolygons clip_polygons(const std::vector<sensor::CameraModel>& cameras,
                           const std::array<double, 6>& volume, double margin_px, bool remove);

int clip_command(std::span<const std::string> args, std::ostream& out, std::ostream& err);

}  // namespace syncap::tools
