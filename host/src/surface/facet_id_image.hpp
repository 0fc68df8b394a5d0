// A triangle mesh rendered into one view as a facet-ID image with its depths: the thesis' tool for
// "which surface point is seen in which image" (Facet-ID image after Fua and Leclerc, thesis lines
// 4990-5010): a point on facet f is visible in a view when the view's nearest facet at the
// point's pixel is f. Rendered in the camera's ideal (distortion-free) pixels, where a facet's
// edges stay straight; each pixel's depth is exact (its ray meets the facet's plane).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <opencv2/core.hpp>
#include <optional>
#include <span>
#include <vector>

#include "sensor/camera_model.hpp"

namespace syncap::surface {

// One triangle of a mesh whose faces are outward oriented (a, b, c counter-clockwise seen from
// outside).
struct Facet {
  Eigen::Vector3d a, b, c;
  Eigen::Vector3d normal() const { return (b - a).cross(c - a).normalized(); }
};

// Facets of triangles given by their corners (hull::triangles_of).
std::vector<Facet> facets_of(std::span<const std::array<Eigen::Vector3d, 3>> triangles);

// The camera without lens distortion, affinity and shear: its pixels are where the pinhole
// puts a point, the space facet-ID images are rendered in.
sensor::CameraModel ideal_camera(const sensor::CameraModel& camera);

class FacetIdImage {
 public:
  static constexpr int kNoFacet = -1;

  // Renders `facets` (indexed by their position) with a z-buffer. Facets with a vertex behind
  // the camera are left out.
  FacetIdImage(const sensor::CameraModel& camera, const std::vector<Facet>& facets);

  const sensor::CameraModel& ideal() const { return ideal_; }
  int width() const { return ids_.cols; }
  int height() const { return ids_.rows; }
  // The nearest facet's index at an ideal pixel, kNoFacet outside the image or where none is.
  int facet_at(int u, int v) const;
  // Its distance from the projection centre along the pixel's ray [mm]; +inf where none.
  float depth_at(int u, int v) const;
  // The unit ray of an ideal pixel.
  Eigen::Vector3d ray(int u, int v) const;
  // The ideal pixel (rounded) of an object point, if it is in the image.
  std::optional<Eigen::Vector2i> pixel_of(const Eigen::Vector3d& point) const;
  // Whether `point`, on facet `facet`, is seen: the nearest facet at its pixel is that facet,
  // or the point is no more than `tolerance_mm` behind the nearest surface there (a facet
  // smaller than a pixel, or the point on a neighbour's edge).
  bool sees(const Eigen::Vector3d& point, int facet, double tolerance_mm) const;

 private:
  sensor::CameraModel ideal_;
  Eigen::Vector3d centre_;
  cv::Mat ids_;     // CV_32S
  cv::Mat depths_;  // CV_32F
};

}  // namespace syncap::surface
