#include "hull/hull_view.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <random>

#include "util/printf_string.hpp"

namespace syncap::hull {
namespace {

Eigen::Vector3d viewing_axis(const sensor::CameraModel& camera) {
  return -camera.rotation().col(2);  // the sensor's z' axis points back, away from the scene
}

Eigen::Vector2d vertex_centroid(const Silhouette& s) {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (const Contour& c : s.contours) {
    for (const Eigen::Vector2d& p : c.points) sum += p;
  }
  return sum / static_cast<double>(std::max<std::size_t>(1, s.vertex_count()));
}

double distance_to_ray(const sensor::Ray& ray, const Eigen::Vector3d& point) {
  const Eigen::Vector3d v = point - ray.origin;
  return (v - v.dot(ray.direction) * ray.direction).norm();
}

// The point with the least summed squared distance to the rays.
std::optional<Eigen::Vector3d> closest_to_rays(const std::vector<sensor::Ray>& rays) {
  Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (const sensor::Ray& ray : rays) {
    const Eigen::Matrix3d m =
        Eigen::Matrix3d::Identity() - ray.direction * ray.direction.transpose();
    a += m;
    b += m * ray.origin;
  }
  const Eigen::FullPivLU<Eigen::Matrix3d> lu(a);
  if (rays.size() < 2 || lu.rank() < 3) return std::nullopt;
  return lu.solve(b);
}

void check_silhouette(const HullView& view) {
  if (view.silhouette.empty())
    throw HullError(view.name + ": empty silhouette (no foreground in the mask)");
  const sensor::SensorGeometry& s = view.camera.sensor;
  if (!view.mask.empty() && (view.mask.cols != s.width_px || view.mask.rows != s.height_px)) {
    throw HullError(util::printf_string("%s: mask is %dx%d, the camera's image %dx%d",
                                        view.name.c_str(), view.mask.cols, view.mask.rows,
                                        s.width_px, s.height_px));
  }
}

void check_sees(const HullView& view, const WorkingVolume& volume) {
  const sensor::Projection p = view.camera.project(volume.centre);
  if (!p.ok() || !view.camera.contains(p.pixel)) {
    throw HullError(util::printf_string(
        "%s: the camera sees nothing of the working volume (its centre %.4g, %.4g, %.4g is %s)",
        view.name.c_str(), volume.centre.x(), volume.centre.y(), volume.centre.z(),
        p.ok() ? "outside its image" : "behind it"));
  }
}

}  // namespace

WorkingVolume estimate_working_volume(const std::vector<HullView>& views, double margin) {
  std::vector<sensor::Ray> rays;
  for (const HullView& view : views) {
    check_silhouette(view);
    rays.push_back(view.camera.back_project(vertex_centroid(view.silhouette)));
  }
  const std::optional<Eigen::Vector3d> centre = closest_to_rays(rays);
  if (!centre) {
    throw HullError(util::printf_string(
        "%zu view(s) with parallel or too few viewing rays: no common working volume",
        views.size()));
  }
  WorkingVolume volume{*centre, 0.0};
  for (const HullView& view : views) {
    check_sees(view, volume);
    for (const Contour& c : view.silhouette.contours) {
      for (const Eigen::Vector2d& p : c.points) {
        volume.radius =
            std::max(volume.radius, distance_to_ray(view.camera.back_project(p), *centre));
      }
    }
  }
  volume.radius *= margin;
  return volume;
}

void check_views(const std::vector<HullView>& views, const WorkingVolume& volume) {
  if (views.empty()) throw HullError("no views");
  for (const HullView& view : views) {
    check_silhouette(view);
    check_sees(view, volume);
  }
}

WorkingVolume checked_working_volume(const std::vector<HullView>& views,
                                     const HullOptions& options) {
  if (views.empty()) throw HullError("no views");
  const WorkingVolume volume =
      options.volume ? *options.volume : estimate_working_volume(views, options.volume_margin);
  check_views(views, volume);
  return volume;
}

ConeDepths cone_depths(const sensor::CameraModel& camera, const WorkingVolume& volume) {
  const double d = viewing_axis(camera).dot(volume.centre - camera.projection_centre());
  return {std::max(d - volume.radius, 0.02 * d), d + volume.radius};
}

Silhouette perturbed(const Silhouette& silhouette, unsigned attempt, std::size_t view_index) {
  std::mt19937 rng(static_cast<unsigned>(1000 * attempt + view_index));
  std::uniform_real_distribution<double> shift(-kPerturbationPx, kPerturbationPx);
  Silhouette out = silhouette;
  for (Contour& c : out.contours) {
    for (Eigen::Vector2d& p : c.points) {
      const double dx = shift(rng);
      const double dy = shift(rng);  // after dx: two statements, a sequenced order
      p += Eigen::Vector2d(dx, dy);
    }
  }
  return out;
}

}  // namespace syncap::hull
