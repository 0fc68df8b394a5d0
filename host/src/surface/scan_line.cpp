#include "surface/scan_line.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace syncap::surface {
namespace {

// The plane's direction of pixel `p`'s ray, scaled so that centre + t * result lies on the
// plane through centre + t * direction: t's factor is the same for every pixel.
std::optional<Eigen::Vector3d> plane_ray(const sensor::CameraModel& camera,
                                         const Eigen::Vector2d& p, const Eigen::Vector3d& normal,
                                         double normal_along_centre_ray) {
  const Eigen::Vector3d d = camera.back_project(p).direction;
  const double along = normal.dot(d);
  if (std::abs(along) < 1e-6) return std::nullopt;
  return d * (normal_along_centre_ray / along);
}

}  // namespace

bool on_object(const MatchingView& view, const Eigen::Vector2d& pixel) {
  if (view.mask.empty()) return true;
  const int u = static_cast<int>(std::lround(pixel.x())),
            v = static_cast<int>(std::lround(pixel.y()));
  return u >= 0 && v >= 0 && u < view.mask.cols && v < view.mask.rows &&
         view.mask.at<uint8_t>(v, u) != 0;
}

float weight_at(const MatchingView& view, const Eigen::Vector2d& pixel) {
  if (view.weight.empty()) return 1.0f;
  const int u = static_cast<int>(std::lround(pixel.x())),
            v = static_cast<int>(std::lround(pixel.y()));
  if (u < 0 || v < 0 || u >= view.weight.cols || v >= view.weight.rows) return 0.0f;
  return view.weight.at<float>(v, u);
}

MatchingView make_matching_view(const sensor::CameraModel& camera, const cv::Mat& image,
                                const cv::Mat& mask, int margin_px) {
  MatchingView view{camera, MatchImage(image), {}, {}};
  if (mask.empty()) return view;
  if (mask.type() != CV_8UC1 || mask.size() != image.size())
    throw std::invalid_argument("matching view: the mask is not 8-bit of the image's size");
  if (margin_px <= 0) {
    view.mask = mask.clone();
  } else {
    cv::erode(mask, view.mask,
              cv::getStructuringElement(cv::MORPH_RECT, {2 * margin_px + 1, 2 * margin_px + 1}));
  }
  // The distance from the outline: to the nearest pixel off the (unshrunk) mask.
  cv::Mat inside = mask != 0, distance;
  cv::distanceTransform(inside, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  distance.convertTo(view.weight, CV_32F, 1.0 / kOutlineRampPx);
  cv::min(view.weight, 1.0, view.weight);
  return view;
}

std::optional<ScanWindow> make_scan_window(const MatchingView& reference,
                                           const Eigen::Vector2i& pixel, int half,
                                           const Eigen::Vector3d& normal) {
  const MatchImage& image = reference.image;
  if (pixel.x() - half < 0 || pixel.y() - half < 0 || pixel.x() + half >= image.width() ||
      pixel.y() + half >= image.height())
    return std::nullopt;
  ScanWindow w;
  w.pixel = pixel;
  w.half = half;
  w.normal = normal.normalized();
  const sensor::Ray ray = reference.camera.back_project(pixel.cast<double>());
  w.centre = ray.origin;
  w.direction = ray.direction;
  const double facing = w.normal.dot(w.direction);
  if (std::abs(facing) < 0.09) return std::nullopt;  // within ~5 degrees of edge-on
  const Eigen::Vector2d p = pixel.cast<double>();
  const auto right = plane_ray(reference.camera, p + Eigen::Vector2d(1, 0), w.normal, facing);
  const auto left = plane_ray(reference.camera, p - Eigen::Vector2d(1, 0), w.normal, facing);
  const auto down = plane_ray(reference.camera, p + Eigen::Vector2d(0, 1), w.normal, facing);
  const auto up = plane_ray(reference.camera, p - Eigen::Vector2d(0, 1), w.normal, facing);
  if (!right || !left || !down || !up) return std::nullopt;
  w.along_u = (*right - *left) / 2.0;
  w.along_v = (*down - *up) / 2.0;
  double sum = 0.0, sum2 = 0.0;
  for (int dv = -half; dv <= half; ++dv) {
    for (int du = -half; du <= half; ++du) {
      if (!reference.mask.empty() &&
          reference.mask.at<uint8_t>(pixel.y() + dv, pixel.x() + du) == 0)
        continue;
      w.offsets.emplace_back(du, dv);
      const float g = image.at(pixel.x() + du, pixel.y() + dv);
      w.grey.push_back(g);
      w.weight.push_back(reference.weight.empty()
                             ? 1.0f
                             : reference.weight.at<float>(pixel.y() + dv, pixel.x() + du));
      sum += g, sum2 += static_cast<double>(g) * g;
    }
  }
  if (w.grey.empty()) return std::nullopt;
  const double n = static_cast<double>(w.grey.size());
  w.object_share = n / ((2.0 * half + 1) * (2.0 * half + 1));
  w.grey_sd = std::sqrt(std::max(0.0, sum2 / n - (sum / n) * (sum / n)));
  return w;
}

std::optional<WarpedWindow> warp_window(const ScanWindow& window, const MatchingView& search,
                                        double t) {
  const auto j = search.camera.project_with_jacobians(window.point(t));
  if (!j.projection.ok()) return std::nullopt;
  WarpedWindow w;
  w.centre = j.projection.pixel;
  w.affine.col(0) = t * (j.d_point * window.along_u);
  w.affine.col(1) = t * (j.d_point * window.along_v);
  w.per_mm = j.d_point * window.direction;
  return w;
}

std::optional<double> window_ncc(const ScanWindow& window, const MatchingView& view,
                                 const WarpedWindow& warp) {
  const MatchImage& image = view.image;
  const double reach = window.half * (warp.affine.cwiseAbs().rowwise().sum().maxCoeff());
  if (!image.inside(warp.centre.x() - reach, warp.centre.y() - reach) ||
      !image.inside(warp.centre.x() + reach, warp.centre.y() + reach))
    return std::nullopt;
  double sw = 0, sww = 0, sg = 0, sgg = 0, sgw = 0;
  std::size_t used = 0;
  for (std::size_t k = 0; k < window.offsets.size(); ++k) {
    const Eigen::Vector2d q = warp.centre + warp.affine * window.offsets[k];
    if (!on_object(view, q)) continue;
    ++used;
    const double w = image.value(q.x(), q.y());
    const double g = window.grey[k];
    sw += w, sww += w * w, sg += g, sgg += g * g, sgw += g * w;
  }
  if (static_cast<double>(used) < kMinShareOnObject * static_cast<double>(window.offsets.size()))
    return std::nullopt;
  const double n = static_cast<double>(used);
  const double cov = sgw - sg * sw / n;
  const double var_g = sgg - sg * sg / n, var_w = sww - sw * sw / n;
  if (var_g <= 1e-9 || var_w <= 1e-9) return std::nullopt;
  return cov / std::sqrt(var_g * var_w);
}

ScanProfile scan_sncc(const ScanWindow& window, const std::vector<const MatchingView*>& search,
                      double t_from, double t_to, double step_px, double min_peak) {
  ScanProfile profile;
  // The step: the fastest-moving search window moves step_px per step (measured mid-line).
  double fastest = 0.0;
  for (const MatchingView* view : search) {
    if (const auto w = warp_window(window, *view, 0.5 * (t_from + t_to)))
      fastest = std::max(fastest, w->per_mm.norm());
  }
  if (fastest <= 0.0 || t_to <= t_from) return profile;
  const double step = step_px / fastest;
  const int steps = static_cast<int>(std::ceil((t_to - t_from) / step));
  for (int i = 0; i <= steps; ++i) {
    const double t = t_from + i * step;
    double sum = 0.0;
    bool complete = true;
    for (const MatchingView* view : search) {
      const auto warp = warp_window(window, *view, t);
      const auto ncc = warp ? window_ncc(window, *view, *warp) : std::nullopt;
      if (!ncc) {
        complete = false;
        break;
      }
      sum += *ncc;
    }
    profile.t.push_back(t);
    profile.sncc.push_back(complete ? sum / static_cast<double>(search.size())
                                    : std::numeric_limits<double>::quiet_NaN());
  }
  const auto& s = profile.sncc;
  for (std::size_t i = 0; i < s.size(); ++i) {
    // Only maxima inside the line: one at its end may belong to a surface beyond it.
    if (i == 0 || i + 1 == s.size() || std::isnan(s[i]) || s[i] < min_peak) continue;
    if (std::isnan(s[i - 1]) || std::isnan(s[i + 1]) || s[i - 1] >= s[i] || s[i + 1] > s[i])
      continue;
    SnccPeak peak{profile.t[i], s[i]};
    const double curvature = s[i - 1] - 2 * s[i] + s[i + 1];
    if (curvature < 0) peak.t += step * 0.5 * (s[i - 1] - s[i + 1]) / curvature;
    profile.peaks.push_back(peak);
  }
  std::sort(profile.peaks.begin(), profile.peaks.end(),
            [](const SnccPeak& a, const SnccPeak& b) { return a.sncc > b.sncc; });
  return profile;
}

}  // namespace syncap::surface
