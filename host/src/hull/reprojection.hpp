// A mesh seen by a camera: its triangles projected with the camera model (distortion included)
// and filled, the mask the hull casts; and its agreement with the view's silhouette.
#pragma once

#include <opencv2/core.hpp>

#include "hull/mesh.hpp"
#include "sensor/camera_model.hpp"

namespace syncap::hull {

// 255 where some triangle of the mesh covers the pixel's centre (fill_pixel_centres per
// triangle: the same rule as rasterize(), so that a hull and a mask compare fairly). Triangles with
// a vertex behind the camera or without a pixel are left out. Each triangle's edges are projected
// as straight lines; the mesh's triangles are small enough for the lens' curvature between their
// vertices not to matter.
cv::Mat render_mask(const Mesh& mesh, const sensor::CameraModel& camera);

}  // namespace syncap::hull
