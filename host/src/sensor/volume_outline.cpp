#include "sensor/volume_outline.hpp"

#include <cmath>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

namespace syncap::sensor {
namespace {

// Samples on the six faces of the box (edges included), samples_per_edge per side.
std::vector<Eigen::Vector3d> face_samples(const Eigen::AlignedBox3d& box, int n) {
  std::vector<Eigen::Vector3d> samples;
  const Eigen::Vector3d lo = box.min(), size = box.sizes();
  for (int axis = 0; axis < 3; ++axis) {
    const int a = (axis + 1) % 3, b = (axis + 2) % 3;
    for (double side : {0.0, 1.0}) {
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
          Eigen::Vector3d p = lo;
          p[axis] += side * size[axis];
          p[a] += size[a] * i / (n - 1);
          p[b] += size[b] * j / (n - 1);
          samples.push_back(p);
        }
      }
    }
  }
  return samples;
}

// Grows a convex polygon by `margin` along its vertices' outward bisectors (approximately an
// offset curve; exact on edges, slightly more at sharp corners, which only errs outward).
std::vector<cv::Point2f> grown(const std::vector<cv::Point2f>& hull, double margin) {
  if (margin <= 0 || hull.size() < 3) return hull;
  cv::Point2f centre(0, 0);
  for (const cv::Point2f& p : hull) centre += p;
  centre *= 1.0f / static_cast<float>(hull.size());
  std::vector<cv::Point2f> out;
  for (const cv::Point2f& p : hull) {
    const cv::Point2f d = p - centre;
    const double length = std::hypot(d.x, d.y);
    // Convex: the vertex moves outward; the factor keeps every edge at least `margin` away for
    // vertex angles of 90 degrees or more (boxes seen in perspective).
    const double k = length > 0 ? std::sqrt(2.0) * margin / length : 0.0;
    out.push_back(p + d * static_cast<float>(k));
  }
  return out;
}

// At most max_points vertices, never inside the input: the hull of approxPolyDP's result is
// grown by its tolerance.
std::vector<cv::Point2f> reduced(std::vector<cv::Point2f> polygon, int max_points) {
  for (double epsilon = 0.5; static_cast<int>(polygon.size()) > max_points; epsilon *= 2) {
    std::vector<cv::Point2f> fewer;
    cv::approxPolyDP(polygon, fewer, epsilon, /*closed=*/true);
    cv::convexHull(grown(fewer, epsilon), polygon);
  }
  return polygon;
}

}  // namespace

VolumeOutline volume_outline(const CameraModel& camera, const Eigen::AlignedBox3d& volume,
                             const VolumeOutlineOptions& options) {
  if (volume.isEmpty()) throw std::invalid_argument("volume_outline: the volume is empty");
  if (options.samples_per_edge < 2 || options.max_points < 3) {
    throw std::invalid_argument("volume_outline: samples_per_edge >= 2 and max_points >= 3");
  }
  VolumeOutline outline;
  std::vector<cv::Point2f> pixels;
  // Far outside the image, where the lens model's correction folds, a point has no pixel: it is
  // put far beyond the image border in the direction the distortion-free camera sees it, so the
  // outline reaches the border there (it errs towards clipping less).
  CameraModel pinhole = camera;
  pinhole.interior = {camera.interior.c, camera.interior.xp, camera.interior.yp};
  const Eigen::Vector2d centre = camera.pixel_from_image({camera.interior.xp, camera.interior.yp});
  const double far = 4.0 * std::hypot(camera.sensor.width_px, camera.sensor.height_px);
  for (const Eigen::Vector3d& p : face_samples(volume, options.samples_per_edge)) {
    Projection projection = camera.project(p);
    if (projection.status == ProjectionStatus::kDistortionNotInvertible) {
      const Projection straight = pinhole.project(p);
      if (straight.ok() && (straight.pixel - centre).norm() > 0) {
        projection.status = ProjectionStatus::kOk;
        projection.pixel = centre + far * (straight.pixel - centre).normalized();
      }
    }
    if (!projection.ok()) {
      outline.whole_image = true;
      outline.note = "the volume reaches behind camera " + std::to_string(camera.id) + ": no clip";
      return outline;
    }
    pixels.emplace_back(static_cast<float>(projection.pixel.x()),
                        static_cast<float>(projection.pixel.y()));
  }
  std::vector<cv::Point2f> hull;
  cv::convexHull(pixels, hull);
  const cv::Size size(camera.sensor.width_px, camera.sensor.height_px);
  const std::vector<cv::Point2f> image{{-0.5f, -0.5f},
                                       {size.width - 0.5f, -0.5f},
                                       {size.width - 0.5f, size.height - 0.5f},
                                       {-0.5f, size.height - 0.5f}};
  std::vector<cv::Point2f> inside;
  cv::intersectConvexConvex(grown(hull, options.margin_px), image, inside, /*handleNested=*/true);
  if (inside.size() < 3) {
    outline.outside_image = true;
    outline.note = "the volume lies outside camera " + std::to_string(camera.id) + "'s image";
    return outline;
  }
  for (const cv::Point2f& p : reduced(inside, options.max_points)) {
    // Rounded outward from the centre would be exact; rounding to nearest costs at most half a
    // pixel against a margin of several.
    outline.polygon.emplace_back(
        std::clamp(static_cast<int>(std::lround(p.x)), 0, size.width - 1),
        std::clamp(static_cast<int>(std::lround(p.y)), 0, size.height - 1));
  }
  return outline;
}

}  // namespace syncap::sensor
