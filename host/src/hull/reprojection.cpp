#include "hull/reprojection.hpp"

#include <vector>
#include "hull/silhouette.hpp"

namespace syncap::hull {

cv::Mat render_mask(const Mesh& mesh, const sensor::CameraModel& camera) {
  cv::Mat mask = cv::Mat::zeros(camera.sensor.height_px, camera.sensor.width_px, CV_8UC1);
  std::vector<Eigen::Vector2d> pixel(mesh.num_vertices());  // removed ones included
  std::vector<bool> ok(mesh.num_vertices(), false);
  for (Mesh::Vertex_index v : mesh.vertices()) {
    const Point3& p = mesh.point(v);
    const sensor::Projection q = camera.project({p.x(), p.y(), p.z()});
    if (!q.ok() || q.pixel.cwiseAbs().maxCoeff() > 1e6) continue;
    ok[v.idx()] = true;
    pixel[v.idx()] = q.pixel;
  }
  std::vector<std::vector<Eigen::Vector2d>> triangle(1);
  for (Mesh::Face_index f : mesh.faces()) {
    std::vector<Eigen::Vector2d>& corners = triangle[0];
    corners.clear();
    bool usable = true;
    for (Mesh::Vertex_index v : vertices_around_face(mesh.halfedge(f), mesh)) {
      if (corners.size() == 3 || !ok[v.idx()]) {
        usable = false;
        break;
      }
      corners.push_back(pixel[v.idx()]);
    }
    if (usable && corners.size() == 3) fill_pixel_centres(mask, triangle);
  }
  return mask;
}

}  // namespace syncap::hull
