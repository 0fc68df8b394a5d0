// The host's 3D markers against the simulator's true targets (docs/design/reconstruction.md,
// "Measured on the replay bench"): for every reported frame, each true target that two or more
// cameras see (projections.csv) is found when a marker lies within the match radius of it (one
// marker per target, nearest first); a marker near no target is a ghost. A found target whose
// marker has another trajectory id than when it was last found is an id switch (the id meant
// another target) or a track break (a new id).
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "calibration_check.hpp"
#include "groups.hpp"
#include "truth.hpp"

namespace syncap::compare {

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
};

// The true targets of every frame, from truth/targets.csv [mm], by frame then target.
using TruePositions = std::map<long, std::map<int, std::array<double, 3>>>;
TruePositions read_true_positions(const std::filesystem::path& targets_csv);

// Every group's markers moved by `motion` (from a calibration's frame into the truth's).
void move_markers(std::vector<Group>& groups, const Similarity& motion);

MarkersCheck check_markers(const Truth& truth, const TruePositions& positions,
                           const std::vector<Group>& groups, double match_radius_mm);

// "markers: 2970 of 2980 visible targets found (99.66 %), 3 ghosts of 2973 markers (0.10 %),
// 3D RMS 0.21 mm, 12 seen by two cameras only, 2 id switches (0.67 per 1000 found), 5 track
// breaks (1.68 per 1000 found)".
std::string format_markers_check(const MarkersCheck& check);

}  // namespace syncap::compare
