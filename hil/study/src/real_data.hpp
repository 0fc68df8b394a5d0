// Section 3 of the calibration accuracy study: the real recordings of strawlab's MultiCamSelfCal
// test data (flydra, a single moved LED; $SYNCAP_DATA/calibration/strawlab-*), calibrated by the
// code of `syncap calibrate --input mcsc:DIR --led` (calibration/calibrate.hpp). No truth here:
// the figures are the adjustment's own (sigma0, residuals, removed outliers) and its checks
// (the verdict, the held-out frames, the two halves).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace syncap::study {

struct RealDataRun {
  std::string dataset;  // folder name
  bool ok = false;
  std::string failure;
  int cameras = 0;
  long frames = 0;         // with the LED seen by at least one camera
  long observations = 0;   // image measurements accepted
  long outliers = 0;       // removed by data snooping (and undetermined after it)
  double sigma0_px = 0.0;  // a posteriori sigma of an image coordinate
  double rms_px = 0.0;     // of the accepted residuals
  double min_camera_rms_px = 0.0, max_camera_rms_px = 0.0;
  bool converged = false;
  double seconds = 0.0;
  // The calibration's own checks (calibration/verdict.hpp).
  std::string verdict;                  // good, weak, failed
  std::vector<std::string> reasons;     // the verdict's
  std::string focal_px;                 // c / pixel size per camera, "677, 682, ..."
  double check_median_px = 0.0;         // held-out frames' median image distance
  double fit_median_px = 0.0;           // the adjusted measurements' median
  double halves_worst_z = 0.0;          // largest |c_a - c_b| / sigma over the cameras
  double halves_centres_percent = 0.0;  // centres apart after a similarity fit, % of spread
  bool halves_compared = false;
};

// Every strawlab-* folder under `calibration_dir`, in name order; empty when there is none.
std::vector<RealDataRun> calibrate_real_data(const std::filesystem::path& calibration_dir);

// The section's Markdown (without its heading).
std::string format_real_data(const std::vector<RealDataRun>& runs,
                             const std::filesystem::path& calibration_dir);

}  // namespace syncap::study
