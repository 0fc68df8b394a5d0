#include "surface/point_files.hpp"

#include <fstream>
#include <stdexcept>
#include <string>

#include "util/printf_string.hpp"

namespace syncap::surface {

std::vector<int> camera_ids(const std::vector<MatchingView>& views) {
  std::vector<int> ids;
  for (const MatchingView& v : views) ids.push_back(v.camera.id);
  return ids;
}

void write_points_ply(const std::filesystem::path& file, const std::vector<MatchedPoint>& points) {
  std::ofstream out(file);
  out << "ply\nformat ascii 1.0\ncomment syncap match: sigma = standard deviation along the "
         "normal [mm]\nelement vertex "
      << points.size()
      << "\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\n"
         "property float ny\nproperty float nz\nproperty float sigma\nend_header\n";
  for (const auto& p : points) {
    out << util::printf_string("%.4f %.4f %.4f %.5f %.5f %.5f %.5f\n", p.point.x(), p.point.y(),
                               p.point.z(), p.normal.x(), p.normal.y(), p.normal.z(),
                               p.sigma_normal_mm);
  }
  if (!out) throw std::runtime_error("cannot write " + file.string());
}

void write_points_csv(const std::filesystem::path& file, const std::vector<MatchedPoint>& points,
                      const std::vector<int>& camera_ids) {
  std::ofstream out(file);
  out << "x,y,z,sigma_ray_mm,sigma_normal_mm,sncc,sigma0,iterations,reference_camera,u,v,"
         "origin_x,origin_y,origin_z,dir_x,dir_y,dir_z,nx,ny,nz,sweep_t_mm,search_cameras\n";
  const auto id = [&](int view) { return camera_ids.at(static_cast<std::size_t>(view)); };
  for (const auto& p : points) {
    std::string search;
    for (const int j : p.search) search += (search.empty() ? "" : " ") + std::to_string(id(j));
    out << util::printf_string(
        "%.4f,%.4f,%.4f,%.5f,%.5f,%.4f,%.3f,%d,%d,%d,%d,%.4f,%.4f,%.4f,%.8f,%.8f,%.8f,%.5f,%.5f,"
        "%.5f,%.4f,%s\n",
        p.point.x(), p.point.y(), p.point.z(), p.sigma_ray_mm, p.sigma_normal_mm, p.sncc, p.sigma0,
        p.iterations, id(p.reference), p.pixel.x(), p.pixel.y(), p.ray_origin.x(), p.ray_origin.y(),
        p.ray_origin.z(), p.ray_direction.x(), p.ray_direction.y(), p.ray_direction.z(),
        p.normal.x(), p.normal.y(), p.normal.z(), p.sweep_t, search.c_str());
  }
  if (!out) throw std::runtime_error("cannot write " + file.string());
}

}  // namespace syncap::surface
