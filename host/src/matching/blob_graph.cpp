#include "matching/blob_graph.hpp"

#include <cmath>

#include "geometry/epipolar.hpp"

namespace syncap::matching {
namespace {

// The parameters (along each ray) of the closest points of two rays; false for parallel rays.
bool closest_approach(const sensor::Ray& a, const sensor::Ray& b, double& ta, double& tb) {
  const Eigen::Vector3d w = a.origin - b.origin;
  const double ab = a.direction.dot(b.direction);
  const double denominator = 1.0 - ab * ab;
  if (!(denominator > 1e-12)) return false;
  const double aw = a.direction.dot(w);
  const double bw = b.direction.dot(w);
  ta = (ab * bw - aw) / denominator;
  tb = (bw - ab * aw) / denominator;
  return true;
}

bool in_front(const geometry::ViewRay& a, const geometry::ViewRay& b, double min_depth_mm,
              Eigen::Vector3d* midpoint) {
  double ta = 0, tb = 0;
  if (!closest_approach(a.ray, b.ray, ta, tb) || ta < min_depth_mm || tb < min_depth_mm)
    return false;
  if (midpoint != nullptr) {
    *midpoint = 0.5 * (a.ray.origin + ta * a.ray.direction + b.ray.origin + tb * b.ray.direction);
  }
  return true;
}

}  // namespace

bool rays_meet(const geometry::ViewRay& a, const geometry::ViewRay& b, double tolerance_px,
               double min_depth_mm, Eigen::Vector3d* midpoint) {
  const double angle = geometry::epipolar_angle(a.ray, b.ray);
  return angle * b.pixels_per_rad <= tolerance_px && in_front(a, b, min_depth_mm, midpoint);
}

BlobGraph BlobGraph::build(const std::vector<sensor::CameraModel>& cameras,
                           const std::vector<std::vector<Eigen::Vector2d>>& pixels,
                           const MatchOptions& options) {
  BlobGraph g;
  std::vector<int> first(cameras.size() + 1, 0);  // first node of each camera
  for (std::size_t c = 0; c < cameras.size(); ++c) {
    first[c] = g.size();
    if (c >= pixels.size()) continue;
    for (std::size_t k = 0; k < pixels[c].size(); ++k) {
      g.blobs.push_back({static_cast<int>(c), static_cast<int>(k)});
      // The matcher needs the rays alone; the marker stage measures the spots' scale.
      g.rays.push_back(geometry::view_ray(cameras[c], pixels[c][k], geometry::SpotScale::kSkipped));
    }
  }
  first[cameras.size()] = g.size();
  g.neighbours.assign(static_cast<std::size_t>(g.size()), NodeSet(g.size()));
  for (std::size_t c1 = 0; c1 < cameras.size(); ++c1) {
    for (std::size_t c2 = c1 + 1; c2 < cameras.size(); ++c2) {
      if (first[c2] == first[c2 + 1]) continue;
      const Eigen::Vector3d other_centre = g.rays[static_cast<std::size_t>(first[c2])].ray.origin;
      const double pixels_per_rad = g.rays[static_cast<std::size_t>(first[c2])].pixels_per_rad;
      for (int a = first[c1]; a < first[c1 + 1]; ++a) {
        const geometry::ViewRay& ra = g.rays[static_cast<std::size_t>(a)];
        // One plane per blob and camera: then one dot product per blob of that camera.
        const Eigen::Vector3d normal = geometry::epipolar_normal(ra.ray, other_centre);
        if (normal.isZero()) continue;
        for (int b = first[c2]; b < first[c2 + 1]; ++b) {
          const geometry::ViewRay& rb = g.rays[static_cast<std::size_t>(b)];
          if (std::abs(normal.dot(rb.ray.direction)) * pixels_per_rad > options.tolerance_px)
            continue;
          if (!in_front(ra, rb, options.min_depth_mm, nullptr)) continue;
          g.neighbours[static_cast<std::size_t>(a)].insert(b);
          g.neighbours[static_cast<std::size_t>(b)].insert(a);
          g.edges.emplace_back(a, b);
        }
      }
    }
  }
  return g;
}

}  // namespace syncap::matching
