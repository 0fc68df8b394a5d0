#include "hull/reprojection.hpp"

#include <opencv2/imgproc.hpp>
#include <vector>

namespace syncap::hull {

namespace {

constexpr int kShift = 4;  // fillConvexPoly's fractional bits

}  // namespace

cv::Mat render_mask(const Mesh& mesh, const sensor::CameraModel& camera) {
  cv::Mat mask = cv::Mat::zeros(camera.sensor.height_px, camera.sensor.width_px, CV_8UC1);
  std::vector<cv::Point> pixel(mesh.num_vertices());  // removed ones included
  std::vector<bool> ok(mesh.num_vertices(), false);
  constexpr double kScale = 1 << kShift;
  for (Mesh::Vertex_index v : mesh.vertices()) {
    const Point3& p = mesh.point(v);
    const sensor::Projection q = camera.project({p.x(), p.y(), p.z()});
    // Far outside the image the fixed-point coordinates would overflow; such a triangle is
    // clipped anyway.
    if (!q.ok() || q.pixel.cwiseAbs().maxCoeff() > 1e6) continue;
    ok[v.idx()] = true;
    pixel[v.idx()] = cv::Point(cvRound(q.pixel.x() * kScale), cvRound(q.pixel.y() * kScale));
  }
  for (Mesh::Face_index f : mesh.faces()) {
    cv::Point corners[3];
    int n = 0;
    bool usable = true;
    for (Mesh::Vertex_index v : vertices_around_face(mesh.halfedge(f), mesh)) {
      if (n == 3 || !ok[v.idx()]) {
        usable = false;
        break;
      }
      corners[n++] = pixel[v.idx()];
    }
    if (usable && n == 3) cv::fillConvexPoly(mask, corners, 3, cv::Scalar(255), cv::LINE_8, kShift);
  }
  return mask;
}

}  // namespace syncap::hull
