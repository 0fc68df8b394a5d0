// The host's JSON lines (syncap-host --out, syncap markers): one object per frame group with what
// arrived from each camera and the frame's 3D markers. The format is documented in
// docs/reconstruction.md ("The host's JSON lines"); hil/compare reads it back.
#pragma once

#include <nlohmann/json.hpp>

#include "pipeline/frame_work.hpp"

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

}  // namespace syncap::io
