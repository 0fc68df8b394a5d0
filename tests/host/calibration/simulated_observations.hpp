// Simulated networks (estimators::simulate_wand_network) turned into what `syncap calibrate`
// reads: each measurement a spot, unlabelled unless asked, with reflections that are not targets
// and targets lost. The calibration tests share it.
#pragma once

#include <cmath>
#include <map>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "calibration/observations.hpp"
#include "estimators/bundle_adjustment_simulation.hpp"
#include "sensor/camera_model.hpp"

namespace syncap::calibration {

struct Simulated {
  Observations observations;
  std::vector<sensor::CameraModel> truth;
  std::set<std::pair<int64_t, int>> blunders;  // (frame, camera)
  estimators::SimulatedWandNetwork network;    // the simulation's network and true points
};

// The simulation's measurements as spots, unlabelled unless `labelled`; every image gets a
// reflection (anywhere on its sensor) with probability `reflections`, and loses a target with
// probability `losses`.
inline Simulated observe(const estimators::WandSimulation& sim, bool labelled, double reflections,
                         double losses) {
  Simulated out;
  out.network = estimators::simulate_wand_network(sim);
  const auto& net = out.network;
  out.truth = net.cameras;
  std::map<std::string, int> camera_of;
  std::map<int, sensor::SensorGeometry> sensor_of;
  for (const auto& c : net.cameras) {
    camera_of["camera" + std::to_string(c.id)] = c.id;
    sensor_of[c.id] = c.sensor;
    out.observations.image_sizes[c.id] = {c.sensor.width_px, c.sensor.height_px};
  }
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (size_t m = 0; m < net.network.measurements.size(); ++m) {
    const auto& meas = net.network.measurements[m];
    if (unit(rng) < losses) continue;
    Spot s;
    s.x = meas.u;
    s.y = meas.v;
    s.area = 30;
    if (labelled) s.target = std::stoi(meas.point.substr(meas.point.find('t') + 1));
    out.observations.frames[meas.frame_number][camera_of.at(meas.station)].push_back(s);
  }
  for (auto& [frame, cameras] : out.observations.frames) {
    for (auto& [camera, spots] : cameras) {
      if (unit(rng) >= reflections) continue;
      Spot s;
      s.x = sensor_of[camera].width_px * unit(rng);
      s.y = sensor_of[camera].height_px * unit(rng);
      s.area = 12;
      spots.push_back(s);
    }
  }
  for (size_t m : net.blunders) {
    const auto& meas = net.network.measurements[m];
    out.blunders.insert({meas.frame_number, camera_of.at(meas.station)});
  }
  out.observations.source = "simulation";
  return out;
}

// A replica of a weak real LED network (issue 14: the strawlab-like recordings of 659x494
// cameras with strong barrel distortion, a few hundred points in a small volume): four cameras
// of focal 390-422 px on a 120 degree arc at 1 m, one LED a frame in a 0.8 x 0.3 x 0.3 m
// volume (it fills the middle half of the images), 0.15 px noise and 1 % blunders of 5-20 px.
inline constexpr double kWeakPixelMm = 0.0074;

inline estimators::WandSimulation weak_led_network(int frames, uint32_t seed) {
  estimators::WandSimulation sim;
  sim.cameras = 4;
  sim.arc_deg = 120.0;
  sim.radius_mm = 1000.0;
  sim.height_mm = 450.0;
  sim.look_at_mm = {0.0, 0.0, 0.0};
  sim.volume_min_mm = {-400.0, -150.0, -150.0};
  sim.volume_max_mm = {400.0, 150.0, 150.0};
  sim.sensor = {659, 494, kWeakPixelMm, kWeakPixelMm};
  sim.frames = frames;
  sim.target_offsets_mm = {0.0};
  sim.noise_px = 0.15;
  sim.blunder_fraction = 0.01;
  sim.seed = seed;
  // The cameras' own interiors: focal 390-422 px, principal points a few pixels off, barrel
  // distortion of k1 0.28 on coordinates normalised by the focal length (the correction model:
  // positive k1 moves a measured point outwards).
  const double focal_px[] = {390.0, 405.0, 414.0, 422.0};
  const double offset_px[][2] = {{4.0, -3.0}, {-6.0, 2.0}, {2.0, 5.0}, {-3.0, -4.0}};
  std::vector<sensor::CameraModel> truth = estimators::simulate_wand_network(sim).cameras;
  for (size_t i = 0; i < truth.size(); ++i) {
    auto& io = truth[i].interior;
    io = {};
    io.c = focal_px[i] * kWeakPixelMm;
    io.xp = offset_px[i][0] * kWeakPixelMm;
    io.yp = offset_px[i][1] * kWeakPixelMm;
    io.k1 = 0.28 / (io.c * io.c);
    io.k2 = 0.05 / std::pow(io.c, 4);
  }
  sim.true_cameras = truth;
  return sim;
}

}  // namespace syncap::calibration
