// The host's JSON lines (syncap-host --out, syncap markers): one object per frame group with what
// arrived from each camera and the frame's 3D markers (docs/design/reconstruction.md shows the
// markers' part). Written and read here only: hil/compare reads the lines through read_frame_lines.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "pipeline/frame_work.hpp"
#include "syncap/proto/contour_codec.hpp"

namespace syncap::io {

// One frame group as its line, without the newline: {"body"?, "cameras": {"3": {"blobs": [{"area",
// "x", "y"}], "processing_us", "silhouette"?}}, "complete", "frame", "hull"?,
// "incomplete_silhouettes"?, "markers"?: [...], "missing_cameras", "rigid_sets"?: [...],
// "trigger_monotonic_ns"?}, keys in this (sorted) order ("markers" only once a reconstruction stage
// ran, "rigid_sets" with the rigid set stage, "hull" when the hull stage worked on the group). A
// marker: {"cameras" [ids], "id", "predicted"?, "residual_px", "sigma" [sx, sy, sz] (mm),
// "two_cameras"?, "x", "y", "z" (mm)}. A rigid set: {"collinear"?, "found", "name", and when found:
// "marker_ids" [the set's markers' trajectory ids], "rms_mm", "rotation" [9, row-major: world = R *
// set + t], "translation" [x, y, z] (mm)}. The hull: {"area_mm2", "cameras", "error"? (why none was
// built), "faces", "flags" (hull_frame_t's), "hull_us", "max", "min" [x, y, z] (mm, its box),
// "vertices", "view_iou"? {"<camera id>": reprojection IoU}, "volume_mm3"}. The body (when the
// body fit stage worked on the group): {"fit_us", "flags" (body_frame_t's), "joints"? {"<H-Anim
// name>": [x, y, z] (mm)}, "parameters"? [the pose, fitting::PoseVector], "points",
// "points_kept", "rms_mm"}. A number that is not
// finite is written as null. Appends to `out`, so that a writer reuses one buffer for every line.
void append_frame_line(std::string& out, const pipeline::FrameWork& work, bool with_markers);
std::string frame_line(const pipeline::FrameWork& work, bool with_markers);

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
  std::optional<pipeline::HullSummary> hull;
  std::optional<pipeline::BodyFitSummary> body;
};

// One line. Required: what identifies a frame and its measurements ("frame", "complete",
// "cameras", a camera's "blobs" or "silhouette", a blob's "x" and "y", a contour's "points", a
// marker's "x", "y", "z" and "cameras", a rigid set's "name" and "found", the hull's "flags" and
// "volume_mm3", the body's "flags"); any other field, when
// absent, takes its default, so hand-written lines in tests stay short. A number written as null
// (not finite when written) reads as NaN. Throws FrameLineError
// naming `where` and the field ("cameras.2.blobs[0].y is not a number").
FrameRecord parse_frame_line(std::string_view line, const std::string& where);

// Every non-blank line of `path`, in file order; a frame may appear only once (the host writes
// each group once). Throws FrameLineError naming "<path>:<line>", or "<path>: cannot read".
std::vector<FrameRecord> read_frame_lines(const std::filesystem::path& path);

}  // namespace syncap::io
