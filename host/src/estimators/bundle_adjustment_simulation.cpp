#include "estimators/bundle_adjustment_simulation.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <set>
#include <string>

#include "sensor/rotation.hpp"

namespace syncap::estimators {
namespace {

// The orientation of a camera at `centre` looking at `target` with the image's y' axis up.
sensor::ExteriorOrientation looking_at(const Eigen::Vector3d& centre,
                                       const Eigen::Vector3d& target) {
  const Eigen::Vector3d z = (centre - target).normalized();
  const Eigen::Vector3d x = Eigen::Vector3d::UnitZ().cross(z).normalized();
  const Eigen::Vector3d y = z.cross(x);
  Eigen::Matrix3d r;
  r << x, y, z;
  const sensor::RotationAngles a = sensor::angles_from_rotation(r);
  return {centre.x(), centre.y(), centre.z(), a.omega, a.phi, a.kappa};
}

std::vector<sensor::CameraModel> true_cameras(const WandSimulation& sim) {
  if (!sim.true_cameras.empty()) return sim.true_cameras;
  std::vector<sensor::CameraModel> cameras;
  const bool ring = sim.arc_deg >= 360.0;
  for (int i = 0; i < sim.cameras; ++i) {
    const double step = sim.cameras > 1 ? sim.arc_deg / (ring ? sim.cameras : sim.cameras - 1) : 0;
    const double angle = (-0.5 * (ring ? 0.0 : sim.arc_deg) + i * step) * M_PI / 180.0;
    const Eigen::Vector3d centre(sim.radius_mm * std::cos(angle), sim.radius_mm * std::sin(angle),
                                 sim.height_mm);
    sensor::CameraModel camera;
    camera.id = i;
    camera.sensor = sim.sensor;
    camera.interior = sim.interior;
    camera.exterior = looking_at(centre, sim.look_at_mm);
    cameras.push_back(camera);
  }
  return cameras;
}

}  // namespace

SimulatedWandNetwork simulate_wand_network(const WandSimulation& sim) {
  SimulatedWandNetwork out;
  out.cameras = true_cameras(sim);
  std::mt19937 rng(sim.seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  scene::Network& network = out.network;

  for (const auto& camera : out.cameras) {
    const std::string name = "camera" + std::to_string(camera.id);
    scene::CameraModel model;
    model.name = name;
    model.sensor = camera.sensor;
    model.interior = {};
    model.interior.c = camera.interior.c * (1.0 + sim.perturb_c * (2.0 * unit(rng) - 1.0));
    model.interior.xp = sim.perturb_principal_point_mm * (2.0 * unit(rng) - 1.0);
    model.interior.yp = sim.perturb_principal_point_mm * (2.0 * unit(rng) - 1.0);
    network.models.push_back(model);
    scene::Station station;
    station.name = name;
    station.camera_id = camera.id;
    station.model = name;
    station.has_approximation = true;
    station.exterior = camera.exterior;
    station.exterior.X0 += sim.perturb_position_mm * gauss(rng);
    station.exterior.Y0 += sim.perturb_position_mm * gauss(rng);
    station.exterior.Z0 += sim.perturb_position_mm * gauss(rng);
    station.exterior.omega += sim.perturb_angle_rad * gauss(rng);
    station.exterior.phi += sim.perturb_angle_rad * gauss(rng);
    station.exterior.kappa += sim.perturb_angle_rad * gauss(rng);
    network.stations.push_back(station);
  }

  double mean_offset = 0.0;
  for (double o : sim.target_offsets_mm) mean_offset += o / sim.target_offsets_mm.size();
  const double half_length = 0.5 * (sim.target_offsets_mm.back() - sim.target_offsets_mm.front());
  const Eigen::Vector3d margin = Eigen::Vector3d::Constant(half_length * 0.5);
  for (int frame = 0; frame < sim.frames; ++frame) {
    Eigen::Vector3d centre;
    for (int k = 0; k < 3; ++k) {
      const double lo = sim.volume_min_mm[k] + margin[k], hi = sim.volume_max_mm[k] - margin[k];
      centre[k] = lo + (hi - lo) * unit(rng);
    }
    const Eigen::Vector3d direction =
        Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng)).normalized();
    const size_t first = network.points.size();
    for (size_t t = 0; t < sim.target_offsets_mm.size(); ++t) {
      const Eigen::Vector3d truth = centre + (sim.target_offsets_mm[t] - mean_offset) * direction;
      scene::ObjectPoint point;
      point.name = "f" + std::to_string(frame) + "t" + std::to_string(t);
      network.points.push_back(point);
      out.points.push_back(truth);
      for (const auto& camera : out.cameras) {
        const sensor::Projection projection = camera.project(truth);
        if (!projection.ok() || !camera.contains(projection.pixel)) continue;
        scene::ImageMeasurement meas;
        meas.station = "camera" + std::to_string(camera.id);
        meas.point = point.name;
        meas.u = projection.pixel.x() + sim.noise_px * gauss(rng);
        meas.v = projection.pixel.y() + sim.noise_px * gauss(rng);
        meas.sigma_px = sim.noise_px;
        meas.frame_number = frame;
        network.measurements.push_back(meas);
      }
    }
    for (size_t t = 1; t < sim.target_offsets_mm.size(); ++t) {
      scene::DistanceConstraint distance;
      distance.point_a = network.points[first + t - 1].name;
      distance.point_b = network.points[first + t].name;
      distance.distance =
          sim.target_offsets_mm[t] - sim.target_offsets_mm[t - 1] + sim.wand_sigma_mm * gauss(rng);
      distance.sigma = sim.wand_sigma_mm;
      network.distances.push_back(distance);
    }
  }

  // At most one blunder per point: with three rays, two bad ones outvote the good one and no test
  // can tell which is which.
  std::vector<size_t> order(network.measurements.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::shuffle(order.begin(), order.end(), rng);
  const auto blunders = static_cast<size_t>(std::lround(sim.blunder_fraction * order.size()));
  std::set<std::string> spoilt;
  for (size_t m : order) {
    if (out.blunders.size() >= blunders) break;
    if (!spoilt.insert(network.measurements[m].point).second) continue;
    const double size = sim.blunder_min_px + (sim.blunder_max_px - sim.blunder_min_px) * unit(rng);
    const double angle = 2.0 * M_PI * unit(rng);
    network.measurements[m].u += size * std::cos(angle);
    network.measurements[m].v += size * std::sin(angle);
    out.blunders.push_back(m);
  }
  std::sort(out.blunders.begin(), out.blunders.end());
  return out;
}

}  // namespace syncap::estimators
