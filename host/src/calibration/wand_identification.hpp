// Which spots of an image are the wand's targets, and which target each one is (thesis section
// 4.1.3.3: the wand's targets are the object points, the known distances between them the
// scale). Per camera and frame, on the image alone:
//
// - LED mode: exactly one spot is the point; none is "missing", more than one "ambiguous".
// - A wand of 3 collinear targets at end A (0), a middle one at `middle_ratio` x length from A,
//   and end B (length): every triple of spots is tried; it is the wand when the middle spot lies
//   within `collinearity_px` (+ `collinearity_fraction` x the image length) of the line through
//   the outer two, and divides them in the known ratio within `ratio_tolerance` (perspective
//   changes the image ratio by the depth difference of the ends: a 1 m wand tilted 45 deg at
//   4 m moves 0.4 to ~0.35-0.45). The end nearer the middle target is A. Spots that are not
//   targets (reflections, other lights) fail this test; when more than one triple passes the
//   frame is ambiguous. A symmetric wand (ratio 0.5) identifies its ends as a 2-target wand.
// - A wand of 2 targets (or a symmetric 3): the ends by size (end A is the larger spot, by more
//   than `size_margin`) or by continuity (each end nearest to where it was in the camera's
//   previous frame, within `continuity_gate` x the image length; a track's first frame takes the
//   upper spot, smaller y, as A: hold end A up when starting, as docs/design/calibration.md says).
//   With more spots than targets, continuity picks the ones nearest the previous positions.
//
// A target whose spot touches the image border (blob_t::FLAG_AT_BORDER) is identified but not
// used (its centroid is biased). Spots already carrying a target index (CSV with a point column,
// MultiCamSelfCal) are taken as they are.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "calibration/observations.hpp"

namespace syncap::calibration {

enum class EndIdentity { kSize, kContinuity };

struct WandSpec {
  bool led = false;           // one point per frame, no scale
  double length_mm = 0.0;     // between the end targets
  int targets = 3;            // 2 or 3
  double middle_ratio = 0.4;  // of the middle target, from end A, as a fraction of the length
  EndIdentity ends = EndIdentity::kContinuity;  // for 2 targets or a symmetric 3

  // The targets' offsets from end A [mm].
  std::vector<double> offsets_mm() const;
  int point_count() const { return led ? 1 : targets; }
};

struct IdentificationOptions {
  double collinearity_px = 2.0;
  double collinearity_fraction = 0.02;
  double ratio_tolerance = 0.08;
  double min_length_px = 8.0;  // a shorter image of the wand is too foreshortened to use
  int max_spots = 16;          // more spots in one image: ambiguous (a triple search is O(n^3))
  double size_margin = 0.15;   // relative area difference that tells the ends apart
  double continuity_gate = 0.35;
};

struct CameraIdentificationStats {
  long frames = 0;      // frames in which the camera reported
  long identified = 0;  // all targets found
  long missing = 0;     // fewer spots than targets, or no spots fitting the wand
  long ambiguous = 0;   // more than one way to see the wand
  long at_border = 0;   // targets identified but not used: their spot touches the border (or
                        // lies outside the image: a corrupt record)
};

// The image positions of the targets: per frame, per camera, one entry per target (nullopt: not
// used).
using TargetPositions = std::vector<std::optional<Eigen::Vector2d>>;

struct Identification {
  std::map<int64_t, std::map<int, TargetPositions>> frames;  // identified images only
  std::map<int, CameraIdentificationStats> cameras;
  long rejected_frames() const;  // ambiguous over all cameras
};

Identification identify_targets(const Observations& observations, const WandSpec& wand,
                                const IdentificationOptions& options = {});

// One line a camera: "camera 0: 480 frames, 470 identified, 6 missing, 4 ambiguous, 2 at border".
std::string format_identification(const Identification& identification);

}  // namespace syncap::calibration
