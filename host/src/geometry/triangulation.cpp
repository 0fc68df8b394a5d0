#include "geometry/triangulation.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace syncap::geometry {
namespace {

// Below this smallest eigenvalue of the unweighted normal matrix (sum of I - d d^T over unit
// directions) the rays are too close to parallel to fix a point: 1e-6 is an angle of ~0.06 deg.
constexpr double kMinNormalEigenvalue = 1e-6;

bool well_conditioned(std::span<const ViewRay> rays) {
  NearestPoint unweighted;
  for (const ViewRay& r : rays) unweighted.add(r.ray);
  // The closed-form 3x3 solver: the iterative one cost more than the rest of a triangulation.
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
  eigen.computeDirect(unweighted.normal, Eigen::EigenvaluesOnly);
  return eigen.eigenvalues().minCoeff() > kMinNormalEigenvalue;
}

}  // namespace

Eigen::Vector3d NearestPoint::solve() const { return normal.ldlt().solve(right); }

double pixels_per_rad(const sensor::CameraModel& camera) {
  return camera.interior.c / camera.sensor.pixel_width_mm;
}

double spot_pixels_per_rad(const sensor::CameraModel& camera, const Ray& ray) {
  // Two small turns of the ray about axes across it; the area their pixels span, by the
  // determinant of the 2x2 Jacobian.
  constexpr double kTurn = 1e-3;        // rad
  constexpr double kDistance = 1000.0;  // mm: any distance; the scale is angular
  const Eigen::Vector3d d = ray.direction.normalized();
  const Eigen::Vector3d a = d.unitOrthogonal(), b = d.cross(a);
  const sensor::Projection centre = camera.project(ray.origin + kDistance * d);
  const sensor::Projection pa = camera.project(ray.origin + kDistance * (d + kTurn * a));
  const sensor::Projection pb = camera.project(ray.origin + kDistance * (d + kTurn * b));
  if (!centre.ok() || !pa.ok() || !pb.ok()) return pixels_per_rad(camera);
  Eigen::Matrix2d j;
  j.col(0) = (pa.pixel - centre.pixel) / kTurn;
  j.col(1) = (pb.pixel - centre.pixel) / kTurn;
  return std::sqrt(std::abs(j.determinant()));
}

ViewRay view_ray(const sensor::CameraModel& camera, const Eigen::Vector2d& pixel,
                 SpotScale spot_scale) {
  const Ray ray = camera.back_project(pixel);
  const double scale = pixels_per_rad(camera);
  return {ray, scale,
          spot_scale == SpotScale::kMeasured ? spot_pixels_per_rad(camera, ray) : scale};
}

double angle_to(const Ray& ray, const Eigen::Vector3d& point) {
  const Eigen::Vector3d to_point = point - ray.origin;
  return std::atan2(ray.direction.cross(to_point).norm(), ray.direction.dot(to_point));
}

double RayPoint::rms_px() const {
  if (errors_px.empty()) return 0;
  double sum = 0;
  for (const double e : errors_px) sum += e * e;
  return std::sqrt(sum / static_cast<double>(errors_px.size()));
}

namespace {

// triangulate() with ray i's image sigma sigma_of(i).
template <typename SigmaOf>
RayPoint triangulate_with(std::span<const ViewRay> rays, const SigmaOf& sigma_of,
                          bool weigh_by_distance) {
  RayPoint result;
  if (rays.size() < 2 || !well_conditioned(rays)) return result;
  NearestPoint first;
  for (const ViewRay& r : rays) first.add(r.ray);
  const Eigen::Vector3d start = first.solve();
  // Each ray weighted by its precision across itself at the point: 1 / (r sigma_rad)^2 (a ray
  // with the point behind it weighs as if at 1 um: its error below names it).
  NearestPoint weighted;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const ViewRay& r = rays[i];
    const double along =
        weigh_by_distance ? std::max(r.ray.direction.dot(start - r.ray.origin), 1e-3) : 1.0;
    const double sigma_mm = along * sigma_of(i) / r.pixels_per_rad;
    weighted.add(r.ray, 1.0 / (sigma_mm * sigma_mm));
  }
  result.position = weighted.solve();
  result.covariance = weighted.normal.inverse();
  result.errors_px.reserve(rays.size());
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const ViewRay& r = rays[i];
    // The sine of the ray's angle to the point: the angle itself for the small ones that matter
    // (1e-5 relative at 10 mrad), without atan2's cost. A point behind the ray: kBehindPx.
    const Eigen::Vector3d to_point = result.position - r.ray.origin;
    const bool in_front = r.ray.direction.dot(to_point) > 0;
    result.errors_px.push_back(in_front ? r.ray.direction.cross(to_point).norm() / to_point.norm() *
                                              r.pixels_per_rad
                                        : kBehindPx);
    const double normalised = result.errors_px.back() / sigma_of(i);
    result.chi_square += normalised * normalised;
  }
  result.ok = result.position.allFinite();
  return result;
}

}  // namespace

RayPoint triangulate(std::span<const ViewRay> rays, double sigma_px, bool weigh_by_distance) {
  return triangulate_with(
      rays, [sigma_px](std::size_t) { return sigma_px; }, weigh_by_distance);
}

RayPoint triangulate(std::span<const ViewRay> rays, std::span<const double> sigmas_px,
                     bool weigh_by_distance) {
  if (sigmas_px.size() != rays.size()) return {};
  return triangulate_with(
      rays, [sigmas_px](std::size_t i) { return sigmas_px[i]; }, weigh_by_distance);
}

RayPoint triangulate_dropping_outliers(std::span<const ViewRay> rays, double sigma_px,
                                       double max_error_px, std::vector<bool>* kept,
                                       bool weigh_by_distance) {
  std::vector<ViewRay> used(rays.begin(), rays.end());
  std::vector<std::size_t> index(rays.size());
  for (std::size_t i = 0; i < index.size(); ++i) index[i] = i;
  RayPoint point;
  while (used.size() >= 2) {
    point = triangulate(used, sigma_px, weigh_by_distance);
    if (!point.ok) break;
    const auto worst = std::max_element(point.errors_px.begin(), point.errors_px.end());
    if (*worst <= max_error_px) break;
    const auto at = worst - point.errors_px.begin();
    used.erase(used.begin() + at);
    index.erase(index.begin() + at);
    point.ok = false;
  }
  if (kept != nullptr) {
    kept->assign(rays.size(), false);
    if (point.ok)
      for (const std::size_t i : index) (*kept)[i] = true;
  }
  return point;
}

std::optional<Eigen::Vector3d> refine_by_reprojection(
    std::span<const sensor::CameraModel* const> cameras, std::span<const Eigen::Vector2d> pixels,
    const Eigen::Vector3d& start, int iterations) {
  Eigen::Vector3d point = start;
  for (int iteration = 0; iteration < iterations; ++iteration) {
    Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
    Eigen::Vector3d gradient = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < cameras.size(); ++i) {
      const sensor::ProjectionJacobians j = cameras[i]->project_with_jacobians(point);
      if (!j.projection.ok()) return std::nullopt;
      const Eigen::Vector2d residual = pixels[i] - j.projection.pixel;
      normal += j.d_point.transpose() * j.d_point;
      gradient += j.d_point.transpose() * residual;
    }
    const Eigen::Vector3d step = normal.ldlt().solve(gradient);
    point += step;
    if (step.norm() < 1e-6) break;
  }
  if (!point.allFinite()) return std::nullopt;
  return point;
}

}  // namespace syncap::geometry
