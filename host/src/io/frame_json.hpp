// The host's JSON lines (syncap-host --out, syncap markers): one object per frame group with what
// arrived from each camera and the frame's 3D markers (docs/reconstruction.md shows the markers'
// part). Written and read here only: hil/compare reads the lines through read_frame_lines.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "pipeline/frame_work.hpp"
#include "syncap/proto/contour_codec.hpp"

namespace syncap::io {

// {"frame", "complete", "missing_cameras", "trigger_monotonic_ns"?, "cameras": {"3": {
// "processing_us", "blobs": [{"x", "y", "area"}], "silhouette"?}}, "incomplete_silhouettes"?,
// "markers"?: [...], "rigid_sets"?: [...]} ("markers" only once a reconstruction stage ran,
// "rigid_sets" with the rigid set stage).
nlohmann::json frame_json(const pipeline::FrameWork& work, bool with_markers);

// {"id", "x", "y", "z" (mm), "sigma" [sx, sy, sz] (mm), "residual_px", "cameras" [ids],
// "two_cameras"?, "predicted"?}
nlohmann::json marker_json(const pipeline::Marker3d& marker);

// {"name", "found", and when found: "translation" [x, y, z] (mm), "rotation" [9, row-major: world
// = R * set + t], "rms_mm", "marker_ids" [the set's markers' trajectory ids], "collinear"?}
nlohmann::json rigid_body_json(const pipeline::RigidBody& body);

// --- Reading the lines back ---

// A line without the form above; what() is "<where>: <problem>", where "groups.jsonl:17" names
// the file and the line.
class FrameLineError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct BlobRecord {
  double x = 0, y = 0;  // sub-pixel centroid, pixel (0, 0) the centre of the top-left pixel
  double area = 0;      // pixels
};

// One camera's entry of a line.
struct CameraRecord {
  // The blob frame's blobs; nothing when only the camera's silhouette arrived (its blob frame was
  // lost: the line names the camera missing).
  std::optional<std::vector<BlobRecord>> blobs;
  double processing_us = 0;
  std::optional<proto::Silhouette> silhouette;  // camera_id and frame_number from the line
};

// One line read back: the frame group and what the stages added.
struct FrameRecord {
  std::int64_t frame = 0;
  bool complete = false;
  std::vector<int> missing_cameras;
  std::optional<std::int64_t> trigger_monotonic_ns;
  std::map<int, CameraRecord> cameras;  // by camera id
  std::vector<int> incomplete_silhouettes;
  // When a reconstruction stage ran; covariances diagonal (the line holds the sigmas only).
  std::optional<std::vector<pipeline::Marker3d>> markers;
  std::vector<pipeline::RigidBody> rigid_bodies;
};

// One line. Required: what identifies a frame and its measurements ("frame", "complete",
// "cameras", a camera's "blobs" or "silhouette", a blob's "x" and "y", a contour's "points", a
// marker's "x", "y", "z" and "cameras", a rigid set's "name" and "found"); any other field, when
// absent, takes its default, so hand-written lines in tests stay short. A number written as null
// (not finite when written) reads as NaN. Throws FrameLineError
// naming `where` and the field ("cameras.2.blobs[0].y is not a number").
FrameRecord parse_frame_line(std::string_view line, const std::string& where);

// Every non-blank line of `path`, in file order; a frame may appear only once (the host writes
// each group once). Throws FrameLineError naming "<path>:<line>", or "<path>: cannot read".
std::vector<FrameRecord> read_frame_lines(const std::filesystem::path& path);

}  // namespace syncap::io
