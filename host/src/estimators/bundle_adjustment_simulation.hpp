// A simulated wand calibration network (the SIMULATE design tag of thesis section 4.2.1 and the
// simulated network of section 4.3): cameras on an arc around a volume, a wand with targets at
// known offsets waved through it, image measurements with Gaussian noise and, if asked, blunders,
// and approximate values perturbed from the truth. Tests and benchmarks of the bundle adjustment
// use it; it knows the truth the adjustment must find.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "scene/network.hpp"
#include "sensor/camera_model.hpp"

namespace syncap::estimators {

struct WandSimulation {
  int cameras = 3;
  double arc_deg = 100.0;  // cameras evenly on this arc (360: a full ring)
  double radius_mm = 4200.0;
  double height_mm = 2300.0;
  Eigen::Vector3d look_at_mm{0.0, 0.0, 1000.0};
  Eigen::Vector3d volume_min_mm{-1000.0, -1000.0, 0.0};
  Eigen::Vector3d volume_max_mm{1000.0, 1000.0, 2000.0};
  // The cameras' truth (hil/scenarios/wand-3cam-basler.yaml): Basler A620f, 6 mm lens.
  sensor::SensorGeometry sensor{1280, 1024, 0.0067, 0.0067};
  sensor::InteriorOrientation interior{6.0,    0.02,   -0.03,  5.6e-3, 2.0e-5,
                                       4.0e-6, 3.0e-5, 2.0e-5, 0.0,    0.0};
  // When not empty, these cameras (e.g. a scenario's rig, hil/sim/src/camera_rig.hpp) are the
  // truth instead of the arc above; their ids become the stations' camera ids.
  std::vector<sensor::CameraModel> true_cameras;
  int frames = 200;
  std::vector<double> target_offsets_mm{0.0, 400.0, 1000.0};
  double wand_sigma_mm = 0.1;  // each frame's distance observations scatter by this
  double noise_px = 0.2;
  // This share of the measurements, at most one per point, moved by blunder_min..max px.
  double blunder_fraction = 0.0;
  double blunder_min_px = 5.0;
  double blunder_max_px = 20.0;
  // Approximate values: interior c off by this fraction, xp, yp by this [mm], distortion zero;
  // stations off by these [mm] / [rad]; points without approximation (triangulated).
  double perturb_c = 0.02;
  double perturb_principal_point_mm = 0.05;
  double perturb_position_mm = 50.0;
  double perturb_angle_rad = 0.01;
  uint32_t seed = 4301;
};

struct SimulatedWandNetwork {
  scene::Network network;                    // one model per camera, free interior and exterior
  std::vector<sensor::CameraModel> cameras;  // the truth, per station
  std::vector<Eigen::Vector3d> points;       // the truth, per network point
  std::vector<size_t> blunders;              // indices into network.measurements, in order
};

SimulatedWandNetwork simulate_wand_network(const WandSimulation& simulation);

}  // namespace syncap::estimators
