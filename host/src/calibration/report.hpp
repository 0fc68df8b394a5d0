// The calibration report a person reads: `report.txt` and a self-contained `report.html` (inline
// SVG, no scripts, no external files) with the parameters and their standard deviations, the
// per-camera correlations of the interior parameters (as thesis Table 4.6), the residual
// histogram, each camera's residual vectors over the image, the coverage of each image, a plan
// and an elevation of the network with the wand positions, and the outcome of every test. A
// table of every camera says which limit the result; a big rig's images are drawn as cells
// (report_overview.hpp).
//
// The report is filled from whatever produced the calibration (the bundle adjustment's result and
// the observations); it computes nothing but layout and summary figures.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "sensor/camera_model.hpp"

namespace syncap::calibration {

struct ReportParameter {
  std::string name;  // "c", "xp", ..., "X0", ..., "kappa"
  double value = 0;
  double sigma = 0;            // a posteriori standard deviation; 0 when not estimated
  std::string unit;            // "mm", "rad", "mm^-2", "1"
  std::string mode;            // "free", "fixed", "observed"
  double bootstrap_sigma = 0;  // from the parametric bootstrap; 0 when not computed
};

struct ReportCamera {
  sensor::CameraModel camera;
  std::vector<ReportParameter> parameters;     // interior, then exterior
  std::vector<std::string> correlation_names;  // the interior parameters that were estimated
  Eigen::MatrixXd correlation;                 // their correlation matrix (square, or empty)
  double rms_px = 0;
  long observations = 0;
  long rejected = 0;
};

// One image measurement after the adjustment.
struct ReportResidual {
  int camera = 0;
  int64_t frame = -1;
  double u = 0, v = 0;    // measured pixel
  double vu = 0, vv = 0;  // residual (adjusted minus measured) [px]
  double w = 0;           // standardised residual (data snooping), 0 when not computed
  bool rejected = false;  // removed as a blunder
};

struct ReportTest {
  std::string name;  // "variance factor (chi-square, two-tailed)"
  double statistic = 0;
  double lower = 0;  // acceptance interval of the statistic
  double upper = 0;
  bool passed = false;
  std::string detail;  // one sentence
};

struct CalibrationReport {
  std::string title = "syncap calibration";
  std::string input;  // what was calibrated ("lcmlog:run.lcmlog", ...)
  std::vector<ReportCamera> cameras;
  std::vector<ReportResidual> residuals;
  std::vector<ReportTest> tests;
  std::vector<Eigen::Vector3d> points;  // adjusted object points [mm] (wand targets)
  std::vector<double> wand_lengths_mm;  // per frame, from the adjusted end points
  double wand_length_mm = 0;            // nominal; 0 in LED mode
  double sigma0 = 0;                    // a posteriori, of unit weight
  long observations = 0;
  long unknowns = 0;
  long redundancy = 0;
  int iterations = 0;
  bool converged = false;
  long outliers_removed = 0;
  int bootstrap_samples = 0;          // re-adjustments behind ReportParameter::bootstrap_sigma
  std::vector<std::string> messages;  // notes from the run (rejected frames, warnings)
  // The calibration's verdict ("good", "weak", "failed"; empty: not judged) and its reasons,
  // each "weak: ..." or "failed: ...": the report's first lines.
  std::string verdict;
  std::vector<std::string> verdict_reasons;
  // How the start was found and how the held-out frames were predicted (one line each).
  std::vector<std::string> start_search;
  std::string check_points;
  std::string halves;                        // the two halves' agreement
  std::vector<std::string> model_selection;  // the model estimated, then one line a group tested
};

std::string format_report_text(const CalibrationReport& report);
std::string format_report_html(const CalibrationReport& report);

// The report's data as tables for other tools (`syncap view --calibration DIR`, spreadsheets):
// residuals.csv, one image measurement a line ("camera,frame,u_px,v_px,vu_px,vv_px,w,rejected");
// points.csv, one adjusted object point a line ("x_mm,y_mm,z_mm"). Each with its header line.
std::string format_residuals_csv(const CalibrationReport& report);
std::string format_points_csv(const CalibrationReport& report);

}  // namespace syncap::calibration
