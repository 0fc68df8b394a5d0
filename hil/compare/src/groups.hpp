// The host's frame groups as the comparison scores them: the host's JSON lines (syncap-host
// --out), read by the host's own reader (io::read_frame_lines, host/src/io/frame_json.hpp), less
// what is not scored: a camera whose blob frame was lost, the tracker's predicted markers.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <opencv2/core/types.hpp>

namespace syncap::compare {

struct Blob {
  double x = 0, y = 0;  // sub-pixel centroid, pixel (0, 0) the centre of the top-left pixel
  double area = 0;      // pixels
};

// One contour of a silhouette: the centres of the foreground's boundary pixels, in order.
struct Outline {
  bool hole = false;
  std::vector<cv::Point> points;
};

struct CameraBlobs {
  double processing_us = 0;
  std::vector<Blob> blobs;
  std::optional<std::vector<Outline>> silhouette;  // when the camera sent one for the frame
};

// A 3D marker of the host's reconstruction (syncap-host --calibration).
struct Marker {
  double x = 0, y = 0, z = 0;  // mm
  int cameras = 0;             // how many saw it
  long id = -1;                // the tracker's trajectory id; -1: none
};

struct Group {
  long frame = 0;
  bool complete = false;
  std::vector<int> missing_cameras;
  std::map<int, CameraBlobs> cameras;          // by camera id: the cameras whose message arrived
  std::optional<std::vector<Marker>> markers;  // when the host reconstructed them
};

// One line; `where` ("groups.jsonl:17") starts every InputError message.
Group parse_group(std::string_view line, const std::string& where);

// Every non-empty line of `file`, in file order; a frame may appear only once. Throws
// InputError naming the file and the line.
std::vector<Group> read_groups(const std::filesystem::path& file);

}  // namespace syncap::compare
