// The parameters of one camera in the thesis' model (thesis eqs 4.1-4.13,
// docs/reference/camera-model.md): the sensor (known in advance), the interior orientation with the
// additional parameters, the exterior orientation, and the layout of the parameter blocks a
// least-squares solver (Ceres) works on.
#pragma once

#include <array>

namespace syncap::sensor {

// The sensor: known in advance, never estimated (thesis: "four parameters defining the sensor
// characteristics ... have to be known in advance").
struct SensorGeometry {
  int width_px = 0;              // nx: image width [pixel]
  int height_px = 0;             // ny: image height [pixel]
  double pixel_width_mm = 0.0;   // mu_x: pixel pitch in x [mm]
  double pixel_height_mm = 0.0;  // mu_y: pixel pitch in y [mm]
};

// Interior orientation and additional parameters. Units make every term of eqs 4.9-4.11 come
// out in mm: r is in mm, so k1 is in mm^-2, k2 in mm^-4, k3 in mm^-6, p1 and p2 in mm^-1; sc and
// sh are dimensionless.
struct InteriorOrientation {
  double c = 0.0;   // camera constant [mm], > 0
  double xp = 0.0;  // principal point x' in the focal plane, from the sensor centre [mm]
  double yp = 0.0;  // principal point y' in the focal plane, from the sensor centre [mm]
  double k1 = 0.0;  // symmetric radial distortion [mm^-2]
  double k2 = 0.0;  // [mm^-4]
  double k3 = 0.0;  // [mm^-6]
  double p1 = 0.0;  // decentring distortion [mm^-1]
  double p2 = 0.0;  // [mm^-1]
  double sc = 0.0;  // differential scale (affinity) in x [1]
  double sh = 0.0;  // shear [1]
};

// Exterior orientation: where the projection centre is and how the camera is turned.
// R = R_kappa * R_phi * R_omega (eq 4.2, see rotation.hpp).
struct ExteriorOrientation {
  double X0 = 0.0;  // projection centre in object space [mm]
  double Y0 = 0.0;
  double Z0 = 0.0;
  double omega = 0.0;  // rotation about x [rad]
  double phi = 0.0;    // rotation about y [rad]
  double kappa = 0.0;  // rotation about z [rad]
};

// Parameter block layouts, the order of the values in the double (or ceres::Jet) arrays the
// templated projection (projection.hpp) and the Jacobians (camera_model.hpp) use.
struct InteriorBlock {
  static constexpr int kC = 0;
  static constexpr int kXp = 1;
  static constexpr int kYp = 2;
  static constexpr int kK1 = 3;
  static constexpr int kK2 = 4;
  static constexpr int kK3 = 5;
  static constexpr int kP1 = 6;
  static constexpr int kP2 = 7;
  static constexpr int kSc = 8;
  static constexpr int kSh = 9;
  static constexpr int kSize = 10;
  // The values' names in reports, scene files and options, in block order.
  static constexpr const char* kNames[kSize] = {"c",  "xp", "yp", "k1", "k2",
                                                "k3", "p1", "p2", "sc", "sh"};
};

struct ExteriorBlock {
  static constexpr int kX0 = 0;
  static constexpr int kY0 = 1;
  static constexpr int kZ0 = 2;
  static constexpr int kOmega = 3;
  static constexpr int kPhi = 4;
  static constexpr int kKappa = 5;
  static constexpr int kSize = 6;
  static constexpr const char* kNames[kSize] = {"X0", "Y0", "Z0", "omega", "phi", "kappa"};
};

// Whether the thesis' lens correction (eq 4.10's k1, k2, k3, p1, p2) is anything but zero.
inline bool has_lens_correction(const InteriorOrientation& i) {
  return i.k1 != 0.0 || i.k2 != 0.0 || i.k3 != 0.0 || i.p1 != 0.0 || i.p2 != 0.0;
}

inline std::array<double, InteriorBlock::kSize> interior_block(const InteriorOrientation& i) {
  return {i.c, i.xp, i.yp, i.k1, i.k2, i.k3, i.p1, i.p2, i.sc, i.sh};
}

inline InteriorOrientation interior_from_block(const double* b) {
  return {b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7], b[8], b[9]};
}

inline std::array<double, ExteriorBlock::kSize> exterior_block(const ExteriorOrientation& e) {
  return {e.X0, e.Y0, e.Z0, e.omega, e.phi, e.kappa};
}

inline ExteriorOrientation exterior_from_block(const double* b) {
  return {b[0], b[1], b[2], b[3], b[4], b[5]};
}

}  // namespace syncap::sensor
