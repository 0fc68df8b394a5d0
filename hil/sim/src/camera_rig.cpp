#include "camera_rig.hpp"

#include <Eigen/Geometry>
#include <cmath>

#include "sensor/rotation.hpp"

namespace syncap::sim {
namespace {

// Sensor axes as columns (x' right, y' up, z' backwards: the camera looks along -z').
Eigen::Matrix3d looking_at(const Eigen::Vector3d& from, const Eigen::Vector3d& target) {
  const Eigen::Vector3d forward = (target - from).normalized();
  Eigen::Vector3d right = forward.cross(Eigen::Vector3d::UnitZ());
  if (right.norm() < 1e-9) right = Eigen::Vector3d::UnitX();  // looking straight down or up
  right.normalize();
  Eigen::Matrix3d axes;
  axes.col(0) = right;
  axes.col(1) = right.cross(forward);
  axes.col(2) = -forward;
  return axes;
}

sensor::ExteriorOrientation exterior_at(const Eigen::Vector3d& centre,
                                        const Eigen::Matrix3d& axes) {
  const sensor::RotationAngles a = sensor::angles_from_rotation(axes);
  return {centre.x(), centre.y(), centre.z(), a.omega, a.phi, a.kappa};
}

// Ring: evenly around 360 deg, camera 0 on the -Y side. Half circle: evenly over arc_deg,
// centred on the -Y side.
Eigen::Vector3d layout_position(const CameraSpec& spec, int i) {
  const double n = spec.count;
  double angle_deg = -90.0 + 360.0 * i / n;
  if (spec.layout == "half_circle") {
    angle_deg = -90.0 + (n > 1 ? spec.arc_deg * (i / (n - 1) - 0.5) : 0.0);
  }
  const double a = angle_deg * M_PI / 180.0;
  return {spec.look_at_mm.x() + spec.radius_mm * std::cos(a),
          spec.look_at_mm.y() + spec.radius_mm * std::sin(a), spec.height_mm};
}

}  // namespace

std::vector<sensor::CameraModel> build_rig(const Scenario& scenario) {
  const CameraSpec& spec = scenario.cameras;
  std::vector<sensor::CameraModel> rig;
  for (int i = 0; i < spec.count; ++i) {
    sensor::CameraModel cam;
    cam.id = i;
    cam.sensor = {spec.width_px, spec.height_px, spec.pixel_size_mm, spec.pixel_size_mm};
    cam.interior = {spec.c_mm, spec.xp_mm, spec.yp_mm, spec.k1, spec.k2,
                    spec.k3,   spec.p1,    spec.p2,    spec.sc, spec.sh};
    if (spec.layout == "explicit") {
      const CameraPoseSpec& p = spec.poses[static_cast<std::size_t>(i)];
      cam.exterior = {
          p.position_mm.x(), p.position_mm.y(), p.position_mm.z(), p.omega, p.phi, p.kappa};
    } else {
      const Eigen::Vector3d centre = layout_position(spec, i);
      cam.exterior = exterior_at(centre, looking_at(centre, spec.look_at_mm));
    }
    rig.push_back(cam);
  }
  return rig;
}

View make_view(const sensor::CameraModel& camera, const Scenario& scenario) {
  View view;
  view.camera = camera.id;
  view.width = camera.sensor.width_px;
  view.height = camera.sensor.height_px;
  view.centre_mm = camera.projection_centre();
  view.axis = -camera.rotation().col(2);
  view.focal_px = camera.interior.c / camera.sensor.pixel_width_mm;
  view.project = [camera](const Eigen::Vector3d& p) -> std::optional<Eigen::Vector2d> {
    const sensor::Projection pr = camera.project(p);
    if (!pr.ok()) return std::nullopt;
    return pr.pixel;
  };
  build_view_tables(view, scenario, [&camera](double x, double y) {
    return camera.back_project({x, y}).direction;
  });
  return view;
}

}  // namespace syncap::sim
