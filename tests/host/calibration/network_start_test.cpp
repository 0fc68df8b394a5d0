// Start values of simulated 3- and 6-camera networks observing a wand (two targets 500 mm apart
// per frame): the cameras have real lenses, the start knows only approximate interiors (c 1 %
// off, no distortion) and 0.2 px noise is on the measurements. After a similarity transform onto
// the truth, every camera is within a few degrees and a few % of the network size, and the scale
// from the wand within a few %.
#include "calibration/network_start.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <cmath>
#include <iostream>
#include <map>
#include <random>
#include <string>

#include "../sensor/test_cameras.hpp"
#include "estimators/bundle_adjustment.hpp"
#include "sensor/camera_model.hpp"
#include "sensor/rotation.hpp"

namespace syncap::calibration {
namespace {

constexpr double kDegree = M_PI / 180.0;
constexpr double kWandLength = 500.0;

struct SimulatedNetwork {
  scene::Network network;
  std::vector<sensor::CameraModel> truth;
};

// `cameras` on a ring of 4.5 m around a 2 m volume, looking at its centre; `frames` wand
// positions inside it.
SimulatedNetwork simulate(int cameras, int frames, unsigned seed, double blunder_fraction = 0.0) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::uniform_real_distribution<double> cube(-900.0, 900.0);
  std::normal_distribution<double> noise(0.0, 0.2), gauss(0.0, 1.0);
  SimulatedNetwork sim;
  for (int i = 0; i < cameras; ++i) {
    const double angle = 2.0 * M_PI * i / cameras + 0.1;
    sensor::CameraModel camera;
    camera.id = i;
    camera.sensor = sensor::test::basler_sensor();
    camera.interior = sensor::test::basler_interior();
    camera.exterior = sensor::test::looking_at(
        {4500 * std::cos(angle), 4500 * std::sin(angle), 1800.0 + 300.0 * (i % 2)},
        {0, 0, 1000.0 + 100.0 * (i % 3)}, 0.05 * (i % 2 ? 1 : -1));
    sim.truth.push_back(camera);

    scene::CameraModel model;
    model.name = "basler" + std::to_string(i);
    model.sensor = camera.sensor;
    model.interior.c = camera.interior.c * 1.01;  // approximate: nominal c, no distortion
    sim.network.models.push_back(model);
    scene::Station station;
    station.name = "cam" + std::to_string(i);
    station.camera_id = i;
    station.model = model.name;
    sim.network.stations.push_back(station);
  }
  const double camera_width = sim.truth[0].sensor.width_px;
  const double camera_height = sim.truth[0].sensor.height_px;
  for (int f = 0; f < frames; ++f) {
    const Eigen::Vector3d middle(cube(rng), cube(rng), 1000.0 + cube(rng));
    const Eigen::Vector3d axis = Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng)).normalized();
    const std::string a = "f" + std::to_string(f) + "a", b = "f" + std::to_string(f) + "b";
    const Eigen::Vector3d ends[2] = {middle - 0.5 * kWandLength * axis,
                                     middle + 0.5 * kWandLength * axis};
    for (int end = 0; end < 2; ++end) {
      const std::string& name = end == 0 ? a : b;
      const Eigen::Vector3d& x = ends[end];
      for (int i = 0; i < cameras; ++i) {
        const sensor::Projection p = sim.truth[i].project(x);
        if (!p.ok() || !sim.truth[i].contains(p.pixel)) continue;
        scene::ImageMeasurement m;
        m.station = "cam" + std::to_string(i);
        m.point = name;
        m.u = p.pixel.x() + noise(rng);
        m.v = p.pixel.y() + noise(rng);
        if (unit(rng) < blunder_fraction) {  // a wrong blob: somewhere else in the image
          m.u = unit(rng) * (camera_width - 1);
          m.v = unit(rng) * (camera_height - 1);
        }
        m.sigma_px = 0.2;
        m.frame_number = f;
        sim.network.measurements.push_back(m);
      }
    }
    scene::DistanceConstraint wand;
    wand.point_a = a;
    wand.point_b = b;
    wand.distance = kWandLength;
    sim.network.distances.push_back(wand);
  }
  return sim;
}

struct Errors {
  double max_rotation_deg = 0.0;
  double max_position_percent = 0.0;  // of the mean camera distance from the centroid
  double scale = 1.0;                 // similarity scale start -> truth
};

std::vector<sensor::ExteriorOrientation> exteriors(const NetworkStart& start) {
  std::vector<sensor::ExteriorOrientation> result;
  for (const scene::Station& station : start.network.stations) result.push_back(station.exterior);
  return result;
}

// Aligns the start's projection centres onto the truth (Umeyama similarity) and compares.
Errors compare(const std::vector<sensor::ExteriorOrientation>& exteriors,
               const std::vector<sensor::CameraModel>& truth) {
  const int n = static_cast<int>(truth.size());
  Eigen::Matrix3Xd estimated(3, n), real(3, n);
  for (int i = 0; i < n; ++i) {
    const sensor::ExteriorOrientation& e = exteriors[i];
    estimated.col(i) = Eigen::Vector3d(e.X0, e.Y0, e.Z0);
    real.col(i) = truth[i].projection_centre();
  }
  const Eigen::Matrix4d similarity = Eigen::umeyama(estimated, real, true);
  const Eigen::Matrix3d sr = similarity.topLeftCorner<3, 3>();
  Errors errors;
  errors.scale = std::cbrt(sr.determinant());
  const Eigen::Matrix3d rotation = sr / errors.scale;
  const Eigen::Vector3d centroid = real.rowwise().mean();
  double size = 0.0;
  for (int i = 0; i < n; ++i) size += (real.col(i) - centroid).norm() / n;
  for (int i = 0; i < n; ++i) {
    const sensor::ExteriorOrientation& e = exteriors[i];
    const Eigen::Matrix3d r = rotation * sensor::rotation_matrix(e.omega, e.phi, e.kappa);
    const double angle = Eigen::AngleAxisd(r.transpose() * truth[i].rotation()).angle() / kDegree;
    const Eigen::Vector3d centre = sr * estimated.col(i) + similarity.topRightCorner<3, 1>();
    errors.max_rotation_deg = std::max(errors.max_rotation_deg, angle);
    errors.max_position_percent =
        std::max(errors.max_position_percent, 100.0 * (centre - real.col(i)).norm() / size);
  }
  return errors;
}

void expect_good_start(int cameras, unsigned seed, double blunder_fraction = 0.0) {
  const SimulatedNetwork sim = simulate(cameras, 150, seed, blunder_fraction);
  const NetworkStart start = start_network(sim.network);
  for (const scene::Station& station : start.network.stations) {
    EXPECT_TRUE(station.has_approximation) << station.name;
  }
  EXPECT_GT(start.report.triangulated_points, 250);
  EXPECT_TRUE(start.report.scale_from_distances);
  EXPECT_GT(start.report.distances_used, 120);
  int with_approximation = 0;
  for (const scene::ObjectPoint& point : start.network.points)
    with_approximation += point.has_approximation;
  EXPECT_EQ(with_approximation, start.report.triangulated_points);

  const Errors errors = compare(exteriors(start), sim.truth);
  std::cout << cameras << " cameras, " << 100 * blunder_fraction << " % blunders: root "
            << start.report.root << ", " << start.report.edges.size() << " tree edges, "
            << start.report.resected.size() << " resected, " << start.report.triangulated_points
            << " points; max rotation error " << errors.max_rotation_deg
            << " deg, max position error " << errors.max_position_percent
            << " % of the network radius, scale error " << 100.0 * (errors.scale - 1.0) << " %\n";
  EXPECT_LT(errors.max_rotation_deg, 3.0);
  EXPECT_LT(errors.max_position_percent, 5.0);
  EXPECT_NEAR(errors.scale, 1.0, 0.03);
}

TEST(NetworkStart, ThreeCameraWandNetwork) { expect_good_start(3, 11); }

TEST(NetworkStart, SixCameraWandNetwork) { expect_good_start(6, 12); }

TEST(NetworkStart, SixCameraWandNetworkWith5PercentBlunders) { expect_good_start(6, 17, 0.05); }

// A camera seeing hardly anything the others see is named, with the numbers.
TEST(NetworkStart, BadlyConnectedCameraIsNamed) {
  SimulatedNetwork sim = simulate(4, 60, 13);
  std::vector<scene::ImageMeasurement> kept;
  int camera3 = 0;
  for (const scene::ImageMeasurement& m : sim.network.measurements) {
    if (m.station == "cam3" && camera3++ >= 4) continue;
    kept.push_back(m);
  }
  sim.network.measurements = kept;
  try {
    start_network(sim.network);
    FAIL() << "expected NetworkStartError";
  } catch (const NetworkStartError& e) {
    EXPECT_EQ(std::string(e.what()),
              "network start: camera 3 (station \"cam3\") shares only 4 observations with the "
              "others; need >= 12");
  }
}

// A camera that shares points with the others, but fewer than a tree edge needs with any single
// one, is placed by spatial resection on the triangulated points.
TEST(NetworkStart, WeaklyLinkedCameraIsResected) {
  SimulatedNetwork sim = simulate(4, 100, 16);
  // cam3 keeps 15 of its points; each of those is seen by only two of cam0..cam2 (a different
  // pair each time), so cam3 shares 10 points with each of them: too few for an edge.
  std::map<std::string, int> kept_point;  // point -> the camera that loses it
  for (const scene::ImageMeasurement& m : sim.network.measurements) {
    if (m.station == "cam3" && kept_point.size() < 15 && !kept_point.count(m.point)) {
      kept_point[m.point] = static_cast<int>(kept_point.size()) % 3;
    }
  }
  std::vector<scene::ImageMeasurement> kept;
  for (const scene::ImageMeasurement& m : sim.network.measurements) {
    const auto point = kept_point.find(m.point);
    if (m.station == "cam3" && point == kept_point.end()) continue;
    if (point != kept_point.end() && m.station == "cam" + std::to_string(point->second)) continue;
    kept.push_back(m);
  }
  sim.network.measurements = kept;
  const NetworkStart start = start_network(sim.network);
  ASSERT_EQ(start.report.resected, std::vector<std::string>{"cam3"});
  EXPECT_EQ(start.report.edges.size(), 2u);
  const Errors errors = compare(exteriors(start), sim.truth);
  std::cout << "resected cam3: max rotation error " << errors.max_rotation_deg
            << " deg, max position error " << errors.max_position_percent << " %\n";
  EXPECT_LT(errors.max_rotation_deg, 3.0);
  EXPECT_LT(errors.max_position_percent, 5.0);
}

// The start values are what the bundle adjustment needs: it converges from them, with sigma0 at
// the simulated noise, the centres and the scale at the truth.
TEST(NetworkStart, BundleAdjustmentConvergesFromTheStart) {
  const SimulatedNetwork sim = simulate(3, 100, 18);
  const NetworkStart start = start_network(sim.network);
  const estimators::BundleAdjustmentResult adjusted = estimators::adjust(start.network, {});
  ASSERT_TRUE(adjusted.converged) << adjusted.termination;
  EXPECT_NEAR(adjusted.sigma0, 1.0, 0.15);  // measurements have sigma_px = 0.2 = the noise
  std::vector<sensor::ExteriorOrientation> result;
  for (const estimators::StationResult& station : adjusted.stations) {
    result.push_back(station.exterior);
  }
  const Errors errors = compare(result, sim.truth);
  std::cout << "after the bundle adjustment: max rotation error " << errors.max_rotation_deg
            << " deg, max position error " << errors.max_position_percent << " %, scale error "
            << 100.0 * (errors.scale - 1.0) << " %\n";
  // The angles stay correlated with the free principal point in a 3-camera ring (0.5 deg is
  // 0.05 mm of xp): the centres and the scale are the sharp check.
  EXPECT_LT(errors.max_rotation_deg, 1.0);
  EXPECT_LT(errors.max_position_percent, 0.3);
  EXPECT_NEAR(errors.scale, 1.0, 0.005);
}

TEST(NetworkStart, UnknownStationInAMeasurementIsNamed) {
  SimulatedNetwork sim = simulate(3, 20, 14);
  sim.network.measurements[5].station = "cam9";
  try {
    start_network(sim.network);
    FAIL() << "expected NetworkStartError";
  } catch (const NetworkStartError& e) {
    EXPECT_NE(std::string(e.what()).find("measurement 5 (point \""), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("names unknown station \"cam9\""), std::string::npos)
        << e.what();
  }
}

// Without distance constraints the first base has the default length.
TEST(NetworkStart, WithoutDistancesTheFirstBaseSetsTheScale) {
  SimulatedNetwork sim = simulate(3, 80, 15);
  sim.network.distances.clear();
  const NetworkStart start = start_network(sim.network);
  EXPECT_FALSE(start.report.scale_from_distances);
  const auto& edge = start.report.edges.front();
  const auto centre = [&](const std::string& name) {
    for (const scene::Station& s : start.network.stations) {
      if (s.name == name) return Eigen::Vector3d(s.exterior.X0, s.exterior.Y0, s.exterior.Z0);
    }
    return Eigen::Vector3d(Eigen::Vector3d::Constant(NAN));
  };
  EXPECT_NEAR((centre(edge.child) - centre(edge.parent)).norm(), 1000.0, 1e-6);
  EXPECT_NEAR(centre(start.report.root).norm(), 0.0, 1e-9);
}

}  // namespace
}  // namespace syncap::calibration
