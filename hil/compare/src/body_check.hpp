// The host's fitted body (syncap-host --body, syncap fit) against the simulator's true joints
// (truth/body.jsonl: every node's centre per frame; docs/design/body-fit.md, "Measured on the
// replay bench"). Per frame with a fit: the distances of the fitted joints' centres to the true
// ones (their RMS over the frame's joints); over the run: the joint-centre RMS, and per limb the
// error of the angle a joint makes between its two bones (hip: trunk and thigh, knee: thigh and
// shank, shoulder: trunk and upper arm, elbow: upper arm and forearm), computed the same way from
// the fitted and the true centres, so that it needs no convention for joint axes.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "calibration_check.hpp"

namespace syncap::compare {

struct BodyCheck {
  long frames = 0;                   // frames with a true body and a body record
  long fitted = 0;                   // of those, with a fitted pose
  long starts = 0;                   // records flagged STARTED (the first start included)
  long lost = 0;                     // records flagged LOST
  long no_start = 0;                 // records flagged NO_START
  long no_hull = 0;                  // records flagged NO_HULL
  std::vector<double> frame_rms_mm;  // per fitted frame
  std::vector<std::pair<long, double>> starts_rms_mm;           // frame and joint RMS of each start
  std::map<std::string, std::vector<double>> joint_errors_mm;   // per joint, per fitted frame
  std::map<std::string, std::vector<double>> angle_errors_deg;  // "l_knee", ...: |fit - truth|
  // The fit's own precision against the truth (frames whose record carries joint sigmas): per
  // joint and frame, the error over its predicted 3D sigma (sqrt(3) x the joint's sigma), whose
  // RMS is 1 where the sigmas are honest; the predicted sigmas; each frame's sigma0.
  std::vector<double> normalized_errors;
  std::vector<double> joint_sigmas_mm;
  std::vector<double> sigma0;
  double rms_mm() const;                // over every joint of every fitted frame
  double mean_angle_error_deg() const;  // over the hips, knees, shoulders and elbows
  // RMS of normalized_errors (1: the sigmas are honest); 0 without sigmas.
  double sigma_ratio() const;
};

// `to_truth`: for a body measured through a calibration, the motion of that calibration's frame
// onto the truth's (fit_to_truth), applied to every joint. Throws InputError naming the file (and
// line) that cannot be read, or a fitted joint the truth does not name.
BodyCheck check_body(const std::filesystem::path& truth_dir,
                     const std::filesystem::path& groups_file,
                     const std::optional<Similarity>& to_truth = std::nullopt);

// "body: N frames, M fitted (starts, lost), joint RMS ..., angle errors ...\n", a line of the
// joints, worst first, one of the fit's precision against the errors (when the records carry
// it), and one of the automatic starts (joint RMS within 50 mm).
std::string format_body_check(const BodyCheck& check);

}  // namespace syncap::compare
