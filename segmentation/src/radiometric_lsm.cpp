#include "syncap/segmentation/radiometric_lsm.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

#include "syncap/segmentation/medi_picture.hpp"

namespace syncap::segmentation {
namespace {

constexpr int kParameters = 8;  // a0 a1 a2 b0 b1 b2 r0 r1
constexpr int kGain = 7;
constexpr int kOffset = 6;
// Below this mean squared gradient (DN^2 per pixel^2, Sobel / 8) in both directions a window has
// too little texture to locate; below this grey-value variance (DN^2) gain and offset cannot be
// told apart and the offset alone is estimated.
constexpr double kMinStructure = 1.0;
constexpr double kMinVariance = 16.0;
constexpr double kMinScaleDn = 0.5;  // floor of the robust scale (noise-free synthetic images)

using Observation = detail::LsmObservation;

double median_of(std::vector<double>& values) {
  if (values.empty()) return 0.0;
  const auto mid = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), mid, values.end());
  return *mid;
}

float bilinear(const cv::Mat& image, double x, double y) {
  const int x0 = static_cast<int>(std::floor(x));
  const int y0 = static_cast<int>(std::floor(y));
  const double fx = x - x0, fy = y - y0;
  const uchar* r0 = image.ptr<uchar>(y0) + x0;
  const uchar* r1 = image.ptr<uchar>(y0 + 1) + x0;
  return static_cast<float>((1 - fy) * ((1 - fx) * r0[0] + fx * r0[1]) +
                            fy * ((1 - fx) * r1[0] + fx * r1[1]));
}

void check_inputs(const cv::Mat& background, const cv::Mat& frame, cv::Rect window,
                  const cv::Mat& exclude) {
  if (frame.type() != CV_8UC1 || (background.type() != CV_8UC1 && background.type() != CV_32FC1))
    throw std::invalid_argument("match_window: frame CV_8UC1, background CV_8UC1 or CV_32FC1");
  if (background.size() != frame.size() || (!exclude.empty() && exclude.size() != frame.size()))
    throw std::invalid_argument("match_window: background, frame and exclude differ in size");
  if (exclude.type() != CV_8UC1 && !exclude.empty())
    throw std::invalid_argument("match_window: exclude must be CV_8UC1");
  const cv::Rect inner(2, 2, frame.cols - 4, frame.rows - 4);
  if (window.area() <= 0 || (window & inner) != window)
    throw std::invalid_argument("match_window: window " + std::to_string(window.width) + "x" +
                                std::to_string(window.height) + "+" + std::to_string(window.x) +
                                "+" + std::to_string(window.y) +
                                " is empty or within 2 px of the image border");
}

// Position of an observation in the frame under the affine parameters.
cv::Point2d transformed(const std::array<double, kParameters>& p, const Observation& o, double cx,
                        double cy) {
  return {cx + p[0] + p[1] * o.u + p[2] * o.v, cy + p[3] + p[4] * o.u + p[5] * o.v};
}

// The row of the design matrix (eq 5.15 with the gain column) for one observation.
std::array<double, kParameters> design_row(const Observation& o, double resampled) {
  const double gx = o.gx, gy = o.gy;
  return {gx, gx * o.u, gx * o.v, gy, gy * o.u, gy * o.v, 1.0, resampled};
}

using Matrix8 = cv::Matx<double, kParameters, kParameters>;

struct Iteration {
  Matrix8 normal = Matrix8::zeros();  // A'WA
  Matrix8 meat = Matrix8::zeros();    // sum of (w v)^2 a a' over the rows a: the sandwich's meat
  cv::Vec<double, kParameters> rhs = cv::Vec<double, kParameters>::all(0);
  double scale = 0.0;  // robust scale of the residuals, 1.4826 MAD
  int observations = 0;
};

// Scratch of one window's solution, kept between iterations so they allocate nothing.
struct Workspace {
  std::vector<double> residuals, resampled, absolute;
};

// Accumulates the weighted normal equations at the current parameters, over the active
// parameters only (their rows and columns; the rest stay zero); the sandwich's meat when asked.
Iteration accumulate(const std::vector<Observation>& obs, const cv::Mat& frame,
                     const std::array<double, kParameters>& p, double cx, double cy, double tukey_c,
                     const std::array<bool, kParameters>& active, bool with_meat, Workspace& ws) {
  ws.residuals.assign(obs.size(), std::nan(""));
  ws.resampled.assign(obs.size(), 0.0);
  ws.absolute.clear();
  const bool geometry = active[0];
  for (std::size_t i = 0; i < obs.size(); ++i) {
    if (!geometry) {  // the identity: the observation's own pixel, no resampling
      ws.resampled[i] = frame.at<uchar>(obs[i].y, obs[i].x);
    } else {
      const cv::Point2d at = transformed(p, obs[i], cx, cy);
      if (at.x < 0 || at.y < 0 || at.x >= frame.cols - 1 || at.y >= frame.rows - 1) continue;
      ws.resampled[i] = bilinear(frame, at.x, at.y);
    }
    ws.residuals[i] = obs[i].background - (p[kOffset] + p[kGain] * ws.resampled[i]);
    ws.absolute.push_back(std::abs(ws.residuals[i]));
  }
  const double scale = std::max(kMinScaleDn, 1.4826 * median_of(ws.absolute));
  const double limit = tukey_c * scale;
  std::array<int, kParameters> index{};
  int count = 0;
  for (int a = 0; a < kParameters; ++a)
    if (active[a]) index[count++] = a;
  Iteration it;
  for (std::size_t i = 0; i < obs.size(); ++i) {
    const double v = ws.residuals[i];
    if (!(std::abs(v) < limit)) continue;  // NaN (outside) or an outlier
    const double t = v / limit;
    const double w = (1 - t * t) * (1 - t * t);
    const auto row = design_row(obs[i], ws.resampled[i]);
    const double wv2 = (w * v) * (w * v);
    for (int ia = 0; ia < count; ++ia) {
      const int a = index[ia];
      it.rhs[a] += w * row[a] * v;
      for (int ib = ia; ib < count; ++ib) {
        const int b = index[ib];
        it.normal(a, b) += w * row[a] * row[b];
        if (with_meat) it.meat(a, b) += wv2 * row[a] * row[b];
      }
    }
    ++it.observations;
  }
  for (int a = 0; a < kParameters; ++a) {
    for (int b = 0; b < a; ++b) {
      it.normal(a, b) = it.normal(b, a);
      it.meat(a, b) = it.meat(b, a);
    }
  }
  it.scale = scale;
  return it;
}

// Solves for the active parameters only (the others fixed): their rows and columns of the normal
// matrix, the rest replaced by identity rows with a zero right-hand side.
bool solve_active(Iteration& it, const std::array<bool, kParameters>& active,
                  cv::Vec<double, kParameters>& step, Matrix8& inverse) {
  for (int a = 0; a < kParameters; ++a) {
    if (active[a]) continue;
    for (int b = 0; b < kParameters; ++b) it.normal(a, b) = it.normal(b, a) = 0.0;
    it.normal(a, a) = 1.0;
    it.rhs[a] = 0.0;
  }
  if (!cv::invert(it.normal, inverse, cv::DECOMP_CHOLESKY)) return false;
  step = inverse * it.rhs;
  return true;
}

double initial_offset(const std::vector<Observation>& obs, const cv::Mat& frame) {
  std::vector<double> differences;
  differences.reserve(obs.size());
  for (const Observation& o : obs) differences.push_back(o.background - frame.at<uchar>(o.y, o.x));
  return median_of(differences);
}

}  // namespace

namespace detail {

LsmWindow observe_window(const cv::Mat& background, cv::Rect window, int step) {
  cv::Mat bg;
  background(window).convertTo(bg, CV_32F);
  cv::Mat gx, gy;
  const cv::Rect grown(window.x - 1, window.y - 1, window.width + 2, window.height + 2);
  cv::Sobel(background(grown), gx, CV_32F, 1, 0, 3, 1.0 / 8);
  cv::Sobel(background(grown), gy, CV_32F, 0, 1, 3, 1.0 / 8);
  LsmWindow out;
  out.window = window;
  out.cx = window.x + (window.width - 1) / 2.0;
  out.cy = window.y + (window.height - 1) / 2.0;
  double sxx = 0, syy = 0, sum = 0, sum2 = 0;
  for (int r = 0; r < window.height; r += step) {
    for (int c = 0; c < window.width; c += step) {
      const Observation o{window.x + c,
                          window.y + r,
                          static_cast<float>(window.x + c - out.cx),
                          static_cast<float>(window.y + r - out.cy),
                          bg.at<float>(r, c),
                          gx.at<float>(r + 1, c + 1),
                          gy.at<float>(r + 1, c + 1)};
      sxx += o.gx * o.gx;
      syy += o.gy * o.gy;
      sum += o.background;
      sum2 += o.background * o.background;
      out.observations.push_back(o);
    }
  }
  const double n = std::max<double>(1, static_cast<double>(out.observations.size()));
  out.textured = std::min(sxx, syy) / n >= kMinStructure;
  out.varied = sum2 / n - (sum / n) * (sum / n) >= kMinVariance;
  out.background_mean = sum / n;
  out.background_spread =
      std::sqrt(std::max(0.0, sum2 / n - out.background_mean * out.background_mean));
  return out;
}

}  // namespace detail

int pixel_step_for(cv::Rect window, const LsmOptions& options) {
  const double per_observation = window.area() / std::max(1.0, double(options.max_observations));
  return std::max({1, options.pixel_step, static_cast<int>(std::ceil(std::sqrt(per_observation)))});
}

LsmWindowResult match_window(const cv::Mat& background, const cv::Mat& frame, cv::Rect window,
                             const cv::Mat& exclude, const LsmOptions& options) {
  check_inputs(background, frame, window, exclude);
  return detail::solve_window(
      detail::observe_window(background, window, pixel_step_for(window, options)), frame, exclude,
      options);
}

namespace detail {

LsmWindowResult solve_window(const LsmWindow& observed, const cv::Mat& frame,
                             const cv::Mat& exclude, const LsmOptions& options) {
  const cv::Rect window = observed.window;
  const double cx = observed.cx, cy = observed.cy;
  // The last frame's foreground does not observe.
  std::vector<Observation> kept;
  if (!exclude.empty()) {
    kept.reserve(observed.observations.size());
    for (const Observation& o : observed.observations) {
      if (exclude.at<uchar>(o.y, o.x) == 0) kept.push_back(o);
    }
  }
  const std::vector<Observation>& obs = exclude.empty() ? observed.observations : kept;
  LsmWindowResult result;
  result.background_mean = observed.background_mean;
  result.background_spread = observed.background_spread;
  result.geometry_estimated = options.estimate_geometry && observed.textured;
  std::array<bool, kParameters> active{};
  for (int a = 0; a < 6; ++a) active[a] = result.geometry_estimated;
  active[kOffset] = true;
  active[kGain] = observed.varied;
  const int unknowns = static_cast<int>(std::count(active.begin(), active.end(), true));
  if (static_cast<int>(obs.size()) < 2 * unknowns + 8) return result;

  std::array<double, kParameters> p{0, 1, 0, 0, 0, 1, initial_offset(obs, frame), 1};
  const double half_w = window.width / 2.0, half_h = window.height / 2.0;
  bool converged = false;
  Workspace ws;
  Iteration it;
  Matrix8 inverse;
  for (result.iterations = 1; result.iterations <= options.max_iterations; ++result.iterations) {
    it = accumulate(obs, frame, p, cx, cy, options.tukey_c, active, false, ws);
    cv::Vec<double, kParameters> step;
    if (it.observations < 2 * unknowns + 8 || !solve_active(it, active, step, inverse))
      return result;
    for (int a = 0; a < kParameters; ++a) p[a] += step[a];
    const double corner_shift =
        std::max(std::abs(step[0]) + std::abs(step[1]) * half_w + std::abs(step[2]) * half_h,
                 std::abs(step[3]) + std::abs(step[4]) * half_w + std::abs(step[5]) * half_h);
    if (corner_shift < options.convergence_px &&
        std::abs(step[kGain]) < 1e-3 * std::abs(p[kGain]) && std::abs(step[kOffset]) < 0.05) {
      converged = true;
      break;
    }
  }
  result.iterations = std::min(result.iterations, options.max_iterations);
  // Eq 5.20 at the solution, in its robust form: with Tukey's weights Q = sigma0^2 (A'WA)^-1
  // understates the scatter (by ~40 % in the test); the sandwich
  // n / (n - u) (A'WA)^-1 (sum (w v)^2 a a') (A'WA)^-1 matches it. sigma0 is the residuals'
  // robust scale (the weighted sum of squares understates it too).
  it = accumulate(obs, frame, p, cx, cy, options.tukey_c, active, true, ws);
  cv::Vec<double, kParameters> unused;
  if (it.observations <= unknowns || !solve_active(it, active, unused, inverse)) return result;
  result.sigma0 = it.scale;
  const Matrix8 covariance = inverse * it.meat * inverse *
                             (static_cast<double>(it.observations) / (it.observations - unknowns));
  for (int a = 0; a < kParameters; ++a)
    result.sigmas[a] = active[a] ? std::sqrt(covariance(a, a)) : 0.0;
  std::copy(p.begin(), p.begin() + 6, result.affine.begin());
  result.offset = p[kOffset];
  result.gain = p[kGain];
  result.observations = it.observations;
  result.valid = converged && std::isfinite(result.gain) && result.gain > 0;
  return result;
}

}  // namespace detail

RadiometricCorrection::RadiometricCorrection(cv::Mat background, RadiometricOptions options)
    : background_(std::move(background)), options_(options) {
  if (background_.type() != CV_8UC1 || background_.empty())
    throw std::invalid_argument("RadiometricCorrection: background must be a CV_8UC1 image");
  if (options_.grid_columns < 1 || options_.grid_rows < 1 ||
      background_.cols / options_.grid_columns < 16 || background_.rows / options_.grid_rows < 16)
    throw std::invalid_argument("RadiometricCorrection: the grid's cells must be >= 16 px");
  gain_grid_.create(options_.grid_rows, options_.grid_columns, CV_32F);
  offset_grid_.create(options_.grid_rows, options_.grid_columns, CV_32F);
  background_changed();
}

void RadiometricCorrection::background_changed() {
  observed_.clear();
  for (int r = 0; r < options_.grid_rows; ++r) {
    for (int c = 0; c < options_.grid_columns; ++c) {
      const cv::Rect window = window_of(r, c);
      observed_.push_back(
          detail::observe_window(background_, window, pixel_step_for(window, options_.lsm)));
    }
  }
}

// Row y of the corrected frame: gain and offset blended between the two nearest grid rows.
void RadiometricCorrection::correct_row(const cv::Mat& frame, int y, double cell, int x0, int x1,
                                        cv::Mat& buffer) {
  const double at = std::clamp((y + 0.5) / cell - 0.5, 0.0, options_.grid_rows - 1.0);
  const int r0 = std::min(static_cast<int>(at), options_.grid_rows - 1);
  const int r1 = std::min(r0 + 1, options_.grid_rows - 1);
  const float t = static_cast<float>(at - r0);
  const float* g0 = gain_rows_.ptr<float>(r0) + x0;
  const float* g1 = gain_rows_.ptr<float>(r1) + x0;
  const float* o0 = offset_rows_.ptr<float>(r0) + x0;
  const float* o1 = offset_rows_.ptr<float>(r1) + x0;
  const uchar* in = frame.ptr<uchar>(y) + x0;
  float* __restrict value = buffer.ptr<float>();
  const int n = x1 - x0;
  for (int x = 0; x < n; ++x) {  // vectorised; OpenCV rounds and saturates below
    const float g = g0[x] + t * (g1[x] - g0[x]);
    const float o = o0[x] + t * (o1[x] - o0[x]);
    value[x] = o + g * static_cast<float>(in[x]);
  }
  buffer.colRange(0, n).convertTo(corrected_.row(y).colRange(x0, x1), CV_8U);
}

// The median gain over the valid windows with the offset of the same window (a consistent line,
// not the gain of one window and the offset of another), and the other figures of the summary.
void RadiometricCorrection::summarise_valid_windows() {
  std::vector<double> gains, sigma0s;
  summary_.valid_windows = 0;
  summary_.max_shift_px = 0.0;
  for (const LsmWindowResult& w : windows_) {
    if (!w.valid) continue;
    gains.push_back(w.gain);
    sigma0s.push_back(w.sigma0);
    summary_.max_shift_px =
        std::max({summary_.max_shift_px, std::abs(w.affine[0]), std::abs(w.affine[3])});
  }
  summary_.valid_windows = static_cast<int>(gains.size());
  summary_.median_gain = 1.0;
  summary_.median_offset = 0.0;
  summary_.median_sigma0 = 0.0;
  if (gains.empty()) return;
  summary_.median_gain = median_of(gains);
  summary_.median_sigma0 = median_of(sigma0s);
  for (const LsmWindowResult& w : windows_) {
    if (w.valid && w.gain == summary_.median_gain) {
      summary_.median_offset = w.offset;
      break;
    }
  }
}

// The middle 60 % of a grid cell, kept 2 px from the border for the resampling.
cv::Rect RadiometricCorrection::window_of(int row, int column) const {
  const int x0 = column * background_.cols / options_.grid_columns;
  const int x1 = (column + 1) * background_.cols / options_.grid_columns;
  const int y0 = row * background_.rows / options_.grid_rows;
  const int y1 = (row + 1) * background_.rows / options_.grid_rows;
  const int mx = (x1 - x0) / 5, my = (y1 - y0) / 5;
  const cv::Rect inner(2, 2, background_.cols - 4, background_.rows - 4);
  return cv::Rect(x0 + mx, y0 + my, x1 - x0 - 2 * mx, y1 - y0 - 2 * my) & inner;
}

const cv::Mat& RadiometricCorrection::correct(const cv::Mat& frame, const cv::Mat& exclude,
                                              cv::Rect region) {
  if (frame.size() != background_.size() || frame.type() != CV_8UC1)
    throw std::invalid_argument(
        "RadiometricCorrection::correct: frame not CV_8UC1 of the background's size");
  if (!exclude.empty() && (exclude.size() != frame.size() || exclude.type() != CV_8UC1))
    throw std::invalid_argument(
        "RadiometricCorrection::correct: exclude not CV_8UC1 of the frame's size");
  windows_.clear();
  summary_ = RadiometricSummary{};
  for (const detail::LsmWindow& observed : observed_) {  // the background's, kept between frames
    LsmWindowResult w = detail::solve_window(observed, frame, exclude, options_.lsm);
    const double possible = static_cast<double>(observed.observations.size());
    w.valid = w.valid && w.observations >= options_.min_observed_share * possible;
    windows_.push_back(w);
  }
  summary_.windows = static_cast<int>(windows_.size());
  summarise_valid_windows();
  // A window the foreground fills converges to a wrong line; it disagrees with the others. The
  // lines are compared over the window's grey values (mean +- one standard deviation): at the
  // mean alone a flat line (a uniform object over a textured floor: gain ~0) would agree.
  for (LsmWindowResult& w : windows_) {
    if (!w.valid) continue;
    double disagreement = 0;
    for (const double level :
         {w.background_mean - w.background_spread, w.background_mean + w.background_spread}) {
      const double corrected = w.offset + w.gain * level;
      const double expected = summary_.median_offset + summary_.median_gain * level;
      disagreement = std::max(disagreement, std::abs(corrected - expected));
    }
    if (disagreement > options_.max_disagreement_dn) {
      w.valid = false;
      ++summary_.disagreeing_windows;
    }
  }
  if (summary_.disagreeing_windows > 0) summarise_valid_windows();
  for (int r = 0, i = 0; r < options_.grid_rows; ++r) {
    for (int c = 0; c < options_.grid_columns; ++c, ++i) {
      const LsmWindowResult& w = windows_[static_cast<std::size_t>(i)];
      gain_grid_.at<float>(r, c) = static_cast<float>(w.valid ? w.gain : summary_.median_gain);
      offset_grid_.at<float>(r, c) =
          static_cast<float>(w.valid ? w.offset : summary_.median_offset);
    }
  }
  // Bilinear between the cells' centres (clamped at the border), as cv::resize of the grid would
  // give, without frame-sized maps: the grid is first spread along x (one row per grid row),
  // then each image row blends the two nearest.
  cv::resize(gain_grid_, gain_rows_, cv::Size(frame.cols, options_.grid_rows), 0, 0,
             cv::INTER_LINEAR);
  cv::resize(offset_grid_, offset_rows_, cv::Size(frame.cols, options_.grid_rows), 0, 0,
             cv::INTER_LINEAR);
  corrected_.create(frame.size(), CV_8UC1);
  const cv::Rect area = region.empty() ? cv::Rect(cv::Point(), frame.size())
                                       : region & cv::Rect(cv::Point(), frame.size());
  // Rows split over OpenCV's threads like the classification pass; each stripe its own buffer.
  const int stripes = std::clamp(4 * cv::getNumThreads(), 1, frame.rows);
  rows_.create(stripes, frame.cols, CV_32F);
  const double cell = double(frame.rows) / options_.grid_rows;
  cv::parallel_for_(cv::Range(0, stripes), [&](const cv::Range& range) {
    for (int s = range.start; s < range.end; ++s) {
      cv::Mat buffer = rows_.row(s);
      for (int y = frame.rows * s / stripes; y < frame.rows * (s + 1) / stripes; ++y) {
        if (y >= area.y && y < area.y + area.height)
          correct_row(frame, y, cell, area.x, area.x + area.width, buffer);
      }
    }
  });
  return corrected_;
}

std::vector<cv::Mat> normalise_training_frames(std::span<const cv::Mat> frames,
                                               const RadiometricOptions& options) {
  const MediPictureModel raw = train_medi_picture(frames);
  cv::Mat reference;
  raw.median.convertTo(reference, CV_8U);
  RadiometricCorrection correction(reference, options);
  std::vector<cv::Mat> out;
  out.reserve(frames.size());
  for (const cv::Mat& f : frames) out.push_back(correction.correct(f).clone());
  return out;
}

}  // namespace syncap::segmentation
