// Cameras and points for the sensor tests: a Basler A620f like the thesis' (Table 4.2: 1280 x
// 1024, 6.7 um pixels, c ~ 6 mm) with a realistic lens, and random cameras around a 2 m volume.
#pragma once

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <sstream>
#include <string>

#include "sensor/camera_model.hpp"
#include "sensor/rotation.hpp"

namespace syncap::sensor::test {

// Distortion of the size a 6 mm lens on a 1/2" sensor has: about 30 px radial at the corners.
inline InteriorOrientation basler_interior() {
  InteriorOrientation in;
  in.c = 6.1;
  in.xp = 0.021;
  in.yp = -0.034;
  in.k1 = 2.1e-3;
  in.k2 = -3.0e-5;
  in.k3 = 1.0e-7;
  in.p1 = 2.0e-5;
  in.p2 = -1.5e-5;
  in.sc = 1.2e-4;
  in.sh = -6.0e-5;
  return in;
}

inline SensorGeometry basler_sensor() { return {1280, 1024, 0.0067, 0.0067}; }

// The orientation of a camera at `centre` looking at `target` with the image's y' axis up
// (world z): its -z' axis points at the target.
inline ExteriorOrientation looking_at(const Eigen::Vector3d& centre, const Eigen::Vector3d& target,
                                      double roll = 0.0) {
  const Eigen::Vector3d z = (centre - target).normalized();
  const Eigen::Vector3d x = Eigen::Vector3d::UnitZ().cross(z).normalized();
  const Eigen::Vector3d y = z.cross(x);
  Eigen::Matrix3d r;
  r << x, y, z;
  r = r * Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const RotationAngles a = angles_from_rotation(r);
  return {centre.x(), centre.y(), centre.z(), a.omega, a.phi, a.kappa};
}

inline CameraModel basler_camera() {
  CameraModel camera;
  camera.id = 3;
  camera.sensor = basler_sensor();
  camera.interior = basler_interior();
  camera.exterior = looking_at({4200, -800, 2300}, {0, 0, 1000}, 0.05);
  return camera;
}

// A camera on a ring around a 2 x 2 x 2 m volume, looking at a point inside it, with random
// interior orientation and, if asked, distortion up to about 1.5 times the Basler's.
inline CameraModel random_camera(std::mt19937& rng, bool with_distortion) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const double azimuth = 3.14159265358979 * unit(rng);
  const Eigen::Vector3d centre(3500 * std::cos(azimuth), 3500 * std::sin(azimuth),
                               1500 + 800 * unit(rng));
  const Eigen::Vector3d target(300 * unit(rng), 300 * unit(rng), 1000 + 300 * unit(rng));
  CameraModel camera;
  camera.sensor = unit(rng) > 0 ? basler_sensor() : SensorGeometry{640, 480, 0.0056, 0.0058};
  camera.exterior = looking_at(centre, target, 0.5 * unit(rng));
  InteriorOrientation& in = camera.interior;
  in.c = camera.sensor.width_px * camera.sensor.pixel_width_mm * (0.6 + 0.2 * unit(rng));
  in.xp = 0.05 * unit(rng);
  in.yp = 0.05 * unit(rng);
  if (with_distortion) {
    // Scaled to the sensor: the radial term stays below ~8 % at the corner.
    const double half_diagonal =
        0.5 * std::hypot(camera.sensor.width_px * camera.sensor.pixel_width_mm,
                         camera.sensor.height_px * camera.sensor.pixel_height_mm);
    const double r2 = half_diagonal * half_diagonal;
    in.k1 = 0.05 * unit(rng) / r2;
    in.k2 = 0.01 * unit(rng) / (r2 * r2);
    in.k3 = 0.005 * unit(rng) / (r2 * r2 * r2);
    in.p1 = 5e-4 * unit(rng) / half_diagonal;
    in.p2 = 5e-4 * unit(rng) / half_diagonal;
    in.sc = 5e-4 * unit(rng);
    in.sh = 2e-4 * unit(rng);
  }
  return camera;
}

// A point the camera sees inside its image, at 1.5 to 5 m, built without the model under test:
// points of the volume around the look-at point, kept if they project into the image.
inline Eigen::Vector3d random_point_near_axis(const CameraModel& camera, std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const Eigen::Matrix3d r = camera.rotation();
  const Eigen::Vector3d forward = -r.col(2);
  const double depth = 3250 + 1750 * unit(rng);
  // Up to 0.8 of the half image width/height, as seen through the pinhole.
  const double half_w = 0.5 * camera.sensor.width_px * camera.sensor.pixel_width_mm;
  const double half_h = 0.5 * camera.sensor.height_px * camera.sensor.pixel_height_mm;
  const double x = 0.8 * half_w * unit(rng) / camera.interior.c * depth;
  const double y = 0.8 * half_h * unit(rng) / camera.interior.c * depth;
  return camera.projection_centre() + depth * forward + x * r.col(0) + y * r.col(1);
}

// A measured number for RecordProperty, with three significant digits in any magnitude.
inline std::string number_text(double value) {
  std::ostringstream out;
  out.precision(3);
  out << value;
  return out.str();
}

}  // namespace syncap::sensor::test
