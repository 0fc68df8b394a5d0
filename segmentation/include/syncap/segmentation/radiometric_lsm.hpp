// Least-squares matching of the current frame against the background model (thesis 5.1.2,
// eqs 5.12-5.20; Gruen 1985): per image window an affine geometric transformation and a linear
// radiometric one (gain and offset, the thesis has the offset only) so that
//
//   B(u, v) = r0 + r1 I(a0 + a1 u + a2 v, b0 + b1 u + b2 v) + e(u, v)
//
// with B the background (lambda), I the frame resampled bilinearly, (u, v) the window's pixels
// relative to its centre. Solved by Gauss-Newton on the linearised observation equations
// (eq 5.15 with the gain column), with robust weights so that a person inside the window is an
// outlier, not a change of light. Used to bring a frame (and the training frames) to the
// background's radiometry before classification, so that lamps warming up or flickering do not
// fill the mask (docs/design/segmentation.md "Changed illumination").
#pragma once

#include <array>
#include <span>
#include <vector>

#include <opencv2/core.hpp>

namespace syncap::segmentation {

struct LsmOptions {
  int max_iterations = 8;
  // Iterations stop when no affine shift moves a window corner more than this, pixels, and the
  // radiometric step is below 1e-3 of the gain.
  double convergence_px = 0.01;
  // Estimate the affine geometry too (a camera nudged by a few tenths of a pixel); off: gain and
  // offset only. Geometry is kept at the identity in a window without texture either way.
  bool estimate_geometry = true;
  // Tukey's biweight constant in units of the residuals' robust scale (1.4826 MAD): residuals
  // beyond it (the person, its shadow) get weight 0.
  double tukey_c = 4.685;
  // Every pixel_step-th row and column of the window observes (from 2 on, neighbouring
  // observations share no pixel of the bilinear resampling, so their errors are independent)...
  int pixel_step = 2;
  // ...and more sparsely in a large window, so that at most about this many observe: the cost
  // is per observation and iteration, and ~1000 pixels fix a gain to ~1e-3.
  int max_observations = 1024;
};

// The estimate of one window, eq 5.20.
struct LsmWindowResult {
  std::array<double, 6> affine{0, 1, 0, 0, 0, 1};  // a0 a1 a2 b0 b1 b2 (window-centred)
  double offset = 0.0;                             // r0, DN
  double gain = 1.0;                               // r1
  double sigma0 = 0.0;                             // a posteriori sigma of unit weight, DN
  std::array<double, 8> sigmas{};  // of a0 a1 a2 b0 b1 b2 r0 r1 (Q = sigma0^2 (A'WA)^-1)
  int iterations = 0;
  int observations = 0;            // pixels with a non-zero weight at the end
  double background_mean = 0.0;    // of the window's observing pixels, DN
  double background_spread = 0.0;  // their standard deviation, DN
  bool geometry_estimated = false;
  bool valid = false;  // converged with enough observations
};

namespace detail {

// One observing pixel of a window: the pixel, its place relative to the window's centre, the
// background's value and the background's gradient there. The frame's gradient would be the
// textbook choice; the background's (a median of many frames) is nearly noise-free, where the
// frame's noise enters both the gradient and the residual and biases the shift (by 15 % in the
// test of 0.3 px). With I(T(u)) = (B(u) - r0) / r1, r1 grad I = grad B.
struct LsmObservation {
  int x, y;  // the pixel in the image
  float u, v;
  float background;
  float gx, gy;
};

// A window's observing pixels and what its background can estimate; depends on the background
// only, so a correction keeps it from frame to frame.
struct LsmWindow {
  cv::Rect window;
  double cx = 0, cy = 0;  // the centre, image pixels
  std::vector<LsmObservation> observations;
  bool textured = false;  // enough gradient in both directions to locate the geometry
  bool varied = false;    // enough spread of grey values to tell gain from offset
  double background_mean = 0;
  double background_spread = 0;
};

LsmWindow observe_window(const cv::Mat& background, cv::Rect window, int step);
LsmWindowResult solve_window(const LsmWindow& observed, const cv::Mat& frame,
                             const cv::Mat& exclude, const LsmOptions& options);

}  // namespace detail

// Matches `frame` (CV_8UC1) to `background` (CV_8UC1 or CV_32FC1, the same size) in `window`.
// Pixels where `exclude` (CV_8UC1, optional) is non-zero do not observe (the last frame's
// foreground). Throws std::invalid_argument on mismatched images or a window outside them.
LsmWindowResult match_window(const cv::Mat& background, const cv::Mat& frame, cv::Rect window,
                             const cv::Mat& exclude = {}, const LsmOptions& options = {});

// Gain and offset only, from at most ~256 pixels a window (two unknowns: the gain to ~2e-3 at
// 2 DN of noise).
inline LsmOptions radiometric_only() {
  LsmOptions options;
  options.estimate_geometry = false;
  options.max_observations = 256;
  return options;
}

// The step between observing rows and columns match_window takes in `window`.
int pixel_step_for(cv::Rect window, const LsmOptions& options);

struct RadiometricOptions {
  int grid_columns = 4;  // windows across the frame (each the centre part of one grid cell)
  int grid_rows = 3;
  // Gain and offset only: the correction does not apply a shift (a capture room's cameras are
  // fixed), and the six geometric parameters cost ~4x the time per frame (more unknowns, more
  // iterations). Set lsm.estimate_geometry to have the windows' shifts reported in the summary.
  LsmOptions lsm = radiometric_only();
  // A window observed by fewer than this share of its pixels (the rest excluded or outliers)
  // takes its gain and offset from the valid windows (their median).
  double min_observed_share = 0.3;
  // A window whose correction moves its grey values (mean +- one standard deviation) by more
  // than this from what the median window's correction would, DN, is taken for one the foreground
  // fills (a person standing over the whole window matches the background with a wrong gain) and
  // gets the median's.
  double max_disagreement_dn = 8.0;
};

// What the last correction did, for the log and for telling an implausible result.
struct RadiometricSummary {
  int windows = 0;
  int valid_windows = 0;
  int disagreeing_windows = 0;  // converged, but rejected by max_disagreement_dn
  double median_gain = 1.0;
  double median_offset = 0.0;
  double max_shift_px = 0.0;  // largest a0 / b0 of a valid window
  double median_sigma0 = 0.0;
};

// Brings frames to the radiometry of a background: a grid of windows matched by match_window,
// gain and offset interpolated bilinearly between the windows' centres, I' = r0 + r1 I per pixel.
class RadiometricCorrection {
 public:
  // `background` CV_8UC1 (lambda rounded).
  RadiometricCorrection(cv::Mat background, RadiometricOptions options = {});

  // The frame in the background's radiometry (CV_8UC1, saturated). `exclude` as in match_window.
  // With a non-empty `region` only its pixels are corrected (the rest of the returned image is
  // left from before); the windows are matched all the same. The returned image is reused by the
  // next call.
  const cv::Mat& correct(const cv::Mat& frame, const cv::Mat& exclude = {}, cv::Rect region = {});

  // To be called when the background's pixels changed (the slow update of the model): the
  // windows' observations are kept between frames.
  void background_changed();

  const RadiometricSummary& summary() const { return summary_; }
  // The windows' estimates of the last call, row by row.
  const std::vector<LsmWindowResult>& windows() const { return windows_; }

 private:
  cv::Rect window_of(int row, int column) const;
  void summarise_valid_windows();
  void correct_row(const cv::Mat& frame, int y, double cell, int x0, int x1, cv::Mat& buffer);

  cv::Mat background_;
  RadiometricOptions options_;
  std::vector<detail::LsmWindow> observed_;  // per window, row by row
  std::vector<LsmWindowResult> windows_;
  RadiometricSummary summary_;
  cv::Mat gain_grid_, offset_grid_;  // CV_32FC1 grid_rows x grid_columns
  cv::Mat gain_rows_, offset_rows_;  // CV_32FC1 grid_rows x frame width: the grid along x
  cv::Mat rows_;  // CV_32FC1, per stripe of rows one corrected row before rounding
  cv::Mat corrected_;
};

// The training frames brought to one radiometry (that of their per-pixel median), so that a lamp
// flickering during training does not widen the model's intervals. Frames as train_medi_picture.
std::vector<cv::Mat> normalise_training_frames(std::span<const cv::Mat> frames,
                                               const RadiometricOptions& options = {});

}  // namespace syncap::segmentation
