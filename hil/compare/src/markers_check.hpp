// The host's 3D markers against the simulator's true targets (docs/design/reconstruction.md,
// "Measured on the replay bench"): for every reported frame, each true target that two or more
// cameras see (projections.csv) is found when a marker lies within the match radius of it (one
// marker per target, nearest first); a marker near no target is a ghost. A found target whose
// marker has another trajectory id than when it was last found is an id switch (the id meant
// another target) or a track break (a new id).
//
// The 3D RMS is judged against a reference computed from the truth: the best estimator on the
// same whole views. For every found target, the cameras where its spot is whole (visible, the disc
// wholly inside the image, no other target's disc within r1 + r2 + 1 px) give the blobs the
// image comparison paired with it; their rays through the TRUE cameras are triangulated as the
// host triangulates (geometry::triangulate) and the point's error is the reference's
// (hil/compare/README.md, "The markers' reference").
#pragma once

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "calibration_check.hpp"
#include "groups.hpp"
#include "truth.hpp"

namespace syncap::compare {

// The best estimator on the same whole views: over the found targets with two or more whole views
// (an oracle that knows which spots are whole, with the real blobs' noise and the true cameras).
struct WholeViewReference {
  long targets = 0;  // found targets with a reference: two or more whole views
  // found targets without: fewer than two whole views (or rays that fix no point)
  long without = 0;
  long views = 0;                        // whole-view blobs triangulated
  double squared_error_sum = 0;          // the reference's 3D errors, mm^2
  double host_squared_error_sum = 0;     // the host's on the same targets, mm^2
  double view_squared_error_sum = 0;     // the whole-view blobs' 2D errors (blob - truth), px^2
  std::optional<double> rms_mm() const;  // the reference's 3D RMS
  std::optional<double> host_rms_mm() const;  // the host's 3D RMS on the same targets
  std::optional<double> ratio() const;        // host_rms_mm / rms_mm
  std::optional<double> view_rms_px() const;  // of the whole-view blobs used
};

struct MarkersCheck {
  long frames = 0;           // groups with markers
  long visible_targets = 0;  // seen by two or more cameras in those frames
  long found = 0;
  long markers = 0;
  long ghosts = 0;
  long two_camera_markers = 0;
  double squared_error_sum = 0;  // of the found, mm^2
  // A target found with another trajectory id than when it was last found (ids from the
  // tracker; markers without one are not counted): a switch when that id last meant another
  // target (two trajectories exchanged markers), a break when it did not (a new trajectory for
  // the target, e.g. after it was hidden longer than the tracker bridges).
  long id_switches = 0;
  long track_breaks = 0;
  double id_switches_per_1000() const;
  double track_breaks_per_1000() const;
  double per_1000_found(long count) const;  // count per 1000 targets found (0 when none)
  double found_share() const;
  double ghost_share() const;
  double rms_mm() const;
  WholeViewReference reference;
};

// The true targets of every frame, from truth/targets.csv [mm], by frame then target.
using TruePositions = std::map<long, std::map<int, std::array<double, 3>>>;
TruePositions read_true_positions(const std::filesystem::path& targets_csv);

// Every group's markers moved by `motion` (from a calibration's frame into the truth's).
void move_markers(std::vector<Group>& groups, const Similarity& motion);

// `blob_radius_px`: the image comparison's match radius (Thresholds::match_radius_px), which pairs
// the blobs with the targets for the reference; cameras missing from truth.cameras give it no
// views.
MarkersCheck check_markers(const Truth& truth, const TruePositions& positions,
                           const std::vector<Group>& groups, double match_radius_mm,
                           double blob_radius_px = 3);

// A camera's view of `target` (an index into `targets`, one camera's projections of a frame) is
// whole: visible, the disc wholly inside `image`, and no other target's disc (in front of the
// camera) within the sum of both radii plus 1 px.
bool whole_view(const std::vector<Projection>& targets, std::size_t target, const ImageSize& image);

// "markers: 2970 of 2980 visible targets found (99.66 %), 3 ghosts of 2973 markers (0.10 %),
// 3D RMS 0.21 mm, best estimator on the same whole views 0.19 mm (the host 0.20 mm on those
// 2960 targets, ratio 1.05; 10 with fewer than 2 whole views; their 9120 blobs' 2D RMS 0.070 px),
// 12 seen by two cameras only, 2 id switches (0.67 per 1000 found), 5 track breaks (1.68 per
// 1000 found)".
std::string format_markers_check(const MarkersCheck& check);

// Every figure of the check, for --json (a figure without data is null).
nlohmann::ordered_json markers_json(const MarkersCheck& check);

}  // namespace syncap::compare
