// The parts of report.html that keep a big rig readable (issue 37: 20 cameras, thousands of rays
// each): one table of every camera with the figures that tell which cameras limit the result
// (rays, RMS, the share of the image its rays cover, c's precision, the centre's), the three
// worst of each column marked; and each image drawn as a grid of cells (the rays' density, the
// mean residual vector of each cell) instead of every ray, so that a systematic error shows as
// a pattern and the page stays small. Internal to report.cpp.
#pragma once

#include <string>
#include <vector>

#include "calibration/report.hpp"

namespace syncap::calibration {

// The image's cells: kGridColumns x kGridRows.
inline constexpr int kGridColumns = 16;
inline constexpr int kGridRows = 10;

struct CameraOverview {
  int id = 0;
  long rays = 0;  // accepted
  double rms_px = 0.0;
  double coverage = 0.0;       // share of the cells holding an accepted ray
  double c_sigma_share = 0.0;  // sigma(c) / c; 0 when c was not estimated
  double centre_sigma = 0.0;   // sqrt(sX0^2 + sY0^2 + sZ0^2) [the network's units]
};

std::vector<CameraOverview> camera_overview(const CalibrationReport& report);

// The table, each column's three worst (of more than three cameras) in bold, and a sentence
// naming the camera that limits most.
std::string html_camera_overview(const CalibrationReport& report);

// Whether the images are drawn as cells: more than 6 cameras, or a camera with over 2000 rays.
bool draws_cells(const CalibrationReport& report);

// The magnification at which the largest cell mean of any camera draws as 0.8 of a cell of an
// image `width` px wide.
double cell_residual_scale(const CalibrationReport& report, double width);

// One camera's image `width` px wide as cells: grey by the number of accepted rays, and when
// `scale` > 0 the cell's mean residual magnified by `scale`.
std::string svg_cells(const ReportCamera& camera, const std::vector<ReportResidual>& residuals,
                      double scale, double width, const std::string& caption);

}  // namespace syncap::calibration
