#include "hull/capture_volume.hpp"

#include <CGAL/Polygon_mesh_processing/bbox.h>
#include <CGAL/Polygon_mesh_processing/clip.h>

#include <exception>
#include <utility>

#include "util/printf_string.hpp"

namespace syncap::hull {

namespace PMP = CGAL::Polygon_mesh_processing;

Mesh clipped_to(Mesh hull, const Eigen::AlignedBox3d& box) {
  const CGAL::Bbox_3 b = PMP::bbox(hull);
  const Eigen::AlignedBox3d extent(Eigen::Vector3d(b.xmin(), b.ymin(), b.zmin()),
                                   Eigen::Vector3d(b.xmax(), b.ymax(), b.zmax()));
  if (box.contains(extent)) return hull;
  const auto describe = [&] {
    return util::printf_string(
        "the hull (x %.0f..%.0f, y %.0f..%.0f, z %.0f..%.0f mm) and the capture volume --volume "
        "%.0f,%.0f,%.0f,%.0f,%.0f,%.0f",
        b.xmin(), b.xmax(), b.ymin(), b.ymax(), b.zmin(), b.zmax(), box.min().x(), box.min().y(),
        box.min().z(), box.max().x(), box.max().y(), box.max().z());
  };
  if (!box.intersects(extent)) throw EmptyHullError(describe() + " do not meet");
  const Kernel::Iso_cuboid_3 cuboid(Point3(box.min().x(), box.min().y(), box.min().z()),
                                    Point3(box.max().x(), box.max().y(), box.max().z()));
  try {
    if (!PMP::clip(hull, cuboid, CGAL::parameters::clip_volume(true)))
      throw HullError(describe() + ": CGAL could not clip the hull (not closed?)");
  } catch (const CGAL::Failure_exception& e) {
    throw HullError(describe() + ": CGAL could not clip the hull: " + e.what());
  }
  hull.collect_garbage();  // clip removes faces in place: indices dense again for every user
  if (hull.number_of_faces() == 0) throw EmptyHullError(describe() + " do not meet");
  return hull;
}

Mesh finished(Mesh hull, const HullOptions& options) {
  if (!options.capture_volume) return hull;
  return clipped_to(std::move(hull), *options.capture_volume);
}

}  // namespace syncap::hull
