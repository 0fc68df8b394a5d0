#include "surface_check.hpp"

#include <algorithm>
#include <cmath>

#include "csv_reader.hpp"

namespace syncap::compare {

std::vector<SurfacePoint> read_surface_points(const std::filesystem::path& file) {
  static const std::vector<std::string> columns{"x",
                                                "y",
                                                "z",
                                                "sigma_ray_mm",
                                                "sigma_normal_mm",
                                                "sncc",
                                                "sigma0",
                                                "iterations",
                                                "reference_camera",
                                                "u",
                                                "v",
                                                "origin_x",
                                                "origin_y",
                                                "origin_z",
                                                "dir_x",
                                                "dir_y",
                                                "dir_z",
                                                "nx",
                                                "ny",
                                                "nz",
                                                "sweep_t_mm",
                                                "search_cameras"};
  std::vector<SurfacePoint> points;
  read_csv(file, columns, [&](const CsvRow& row) {
    SurfacePoint p;
    p.point = {row.number(0), row.number(1), row.number(2)};
    p.sigma_ray_mm = row.number(3);
    p.origin = {row.number(11), row.number(12), row.number(13)};
    p.direction = Eigen::Vector3d(row.number(14), row.number(15), row.number(16)).normalized();
    p.sweep_t_mm = row.number(20);
    points.push_back(p);
  });
  return points;
}

std::optional<TrueHit> first_true_hit(const TrueBody& body, const Eigen::Vector3d& origin,
                                      const Eigen::Vector3d& direction) {
  std::optional<TrueHit> best;
  for (const TrueEllipsoid& e : body.ellipsoids) {
    // In the frame where the ellipsoid is the unit sphere: |o + t d|^2 = 1.
    const Eigen::Vector3d o = (e.axes.transpose() * (origin - e.centre)).cwiseQuotient(e.radii);
    const Eigen::Vector3d d = (e.axes.transpose() * direction).cwiseQuotient(e.radii);
    const double a = d.squaredNorm(), b = o.dot(d), c = o.squaredNorm() - 1.0;
    const double disc = b * b - a * c;
    if (disc < 0) continue;
    const double t = (-b - std::sqrt(disc)) / a;
    if (t <= 0 || (best && t >= best->t)) continue;
    const Eigen::Vector3d local = o + t * d;  // on the unit sphere
    best = TrueHit{t, (e.axes * local.cwiseQuotient(e.radii)).normalized()};
  }
  return best;
}

SurfaceErrors check_surface(const std::vector<SurfacePoint>& points, const TrueBody& body,
                            double blunder_mm, std::vector<PointError>* each) {
  SurfaceErrors out;
  out.points = points.size();
  double sum_normal = 0, sum_normalised = 0, sum_sweep = 0;
  std::size_t kept = 0, within = 0;
  std::vector<double> sigmas;
  std::vector<std::pair<double, double>> kept_sigma_normalised;
  for (const SurfacePoint& p : points) {
    const auto hit = first_true_hit(body, p.origin, p.direction);
    if (!hit) {
      ++out.off_body, ++out.blunders;
      if (each) each->push_back({std::nan(""), std::nan(""), std::nan(""), std::nan("")});
      continue;
    }
    const double cosine = std::abs(p.direction.dot(hit->normal));
    const double t = (p.point - p.origin).dot(p.direction);
    const double error_ray = t - hit->t;
    const double error_normal = error_ray * cosine;
    const double sigma_normal = p.sigma_ray_mm * cosine;
    sigmas.push_back(sigma_normal);
    const double sweep_error = (p.sweep_t_mm - hit->t) * cosine;
    if (each) each->push_back({error_ray, error_normal, sigma_normal, sweep_error});
    const double normalised = p.sigma_ray_mm > 0 ? error_ray / p.sigma_ray_mm : INFINITY;
    if (std::abs(normalised) <= 3.0) ++within;
    if (std::abs(error_normal) > std::max(5.0 * sigma_normal, blunder_mm)) {
      ++out.blunders;
      continue;
    }
    ++kept;
    kept_sigma_normalised.emplace_back(sigma_normal, normalised);
    sum_normal += error_normal * error_normal;
    sum_normalised += normalised * normalised;
    sum_sweep += sweep_error * sweep_error;
  }
  if (kept > 0) {
    out.rms_normal_mm = std::sqrt(sum_normal / kept);
    out.rms_normalised = std::sqrt(sum_normalised / kept);
    out.sweep_rms_normal_mm = std::sqrt(sum_sweep / kept);
  }
  if (!points.empty()) out.within_3_sigma = static_cast<double>(within) / points.size();
  if (kept_sigma_normalised.size() >= 4) {
    std::ranges::sort(kept_sigma_normalised);
    const std::size_t n = kept_sigma_normalised.size();
    for (std::size_t q = 0; q < 4; ++q) {
      double sum = 0;
      const std::size_t from = q * n / 4, to = (q + 1) * n / 4;
      for (std::size_t i = from; i < to; ++i)
        sum += kept_sigma_normalised[i].second * kept_sigma_normalised[i].second;
      out.rms_normalised_by_sigma[q] = std::sqrt(sum / static_cast<double>(to - from));
    }
  }
  if (!sigmas.empty()) {
    std::ranges::sort(sigmas);
    out.median_sigma_normal_mm = sigmas[sigmas.size() / 2];
  }
  return out;
}

}  // namespace syncap::compare
