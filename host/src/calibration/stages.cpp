#include "calibration/stages.hpp"

#include <chrono>
#include <memory>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <set>

#include "calibration/model_selection.hpp"
#include "estimators/bootstrap.hpp"
#include "sensor/rotation.hpp"

#include "util/printf_string.hpp"

namespace syncap::calibration {
namespace {

constexpr double kPi = 3.14159265358979323846;
// A free network from one point a frame converges slowly along the weakly determined camera
// constants; 50 (the design default) is not always enough. The second stage, blunders removed,
// must converge: a few strawlab blunder seeds crawl there for 150-400 iterations. The first, with
// the blunders still in, only gives approximate values: longer, it can wander off along c
// against depth (strawlab blunder seed 8 ends at 1.1 px RMS with 1000).
constexpr int kFirstStageIterations = 200;
constexpr int kMaxIterations = 1000;

// The network without the points the start could not triangulate (their rays did not meet
// within NetworkStartOptions::max_ray_error_px with the start's rough interiors), for the first
// stage; the second stage takes them back, triangulated with the first stage's orientations.
scene::Network triangulated_part(const scene::Network& network) {
  std::set<std::string> triangulated;
  for (const scene::ObjectPoint& p : network.points) {
    if (p.has_approximation) triangulated.insert(p.name);
  }
  return scene::restricted_to_points(network, triangulated);
}

// The room's vertical as the cameras show it. Cameras hang without roll, so their image-right
// axes are horizontal, whatever their pitch: the vertical is the direction most nearly at right
// angles to all of them (the smallest eigenvector of their scatter), turned to agree with the
// mean image-up axis. When the right axes are (nearly) parallel that direction is not defined,
// and the mean image-up axis itself serves (biased by the cameras' common pitch).
Eigen::Vector3d vertical_of(const std::vector<scene::Station>& stations) {
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  Eigen::Vector3d mean_up = Eigen::Vector3d::Zero();
  for (const scene::Station& s : stations) {
    const Eigen::Matrix3d r =
        sensor::rotation_matrix(s.exterior.omega, s.exterior.phi, s.exterior.kappa);
    scatter += r.col(0) * r.col(0).transpose();
    mean_up += r.col(1);
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(scatter);
  const Eigen::Vector3d values = solver.eigenvalues();  // increasing
  if (values[1] < 0.05 * values[2]) return mean_up;     // right axes all alike
  Eigen::Vector3d vertical = solver.eigenvectors().col(0);
  return vertical.dot(mean_up) < 0 ? Eigen::Vector3d(-vertical) : vertical;
}

}  // namespace

// Start interior: centred principal point, no distortion, c from the typical field of view.
std::vector<int64_t> evenly_spread(std::vector<int64_t> frames, int count) {
  if (count <= 0 || static_cast<int>(frames.size()) <= count) return frames;
  std::vector<int64_t> spread;
  const double step = static_cast<double>(frames.size()) / count;
  for (int i = 0; i < count; ++i)
    spread.push_back(frames[static_cast<size_t>(std::floor(i * step))]);
  return spread;
}

sensor::InteriorOrientation start_interior(const sensor::SensorGeometry& sensor,
                                           double field_of_view_deg) {
  sensor::InteriorOrientation interior;
  const double half_width_mm = 0.5 * sensor.width_px * sensor.pixel_width_mm;
  interior.c = half_width_mm / std::tan(0.5 * field_of_view_deg * kPi / 180.0);
  return interior;
}

// Moves the network (stations and points, rigidly) into the levelled frame documented in
// calibrate.hpp: origin at the centroid of the points, Z along the cameras' mean image-up axis,
// Y horizontal from the first camera towards the origin. The last adjustment then stays in this
// frame: its free-network datum holds the first station where it is put here.
void level_network(scene::Network& network) {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  int points = 0;
  for (const scene::ObjectPoint& p : network.points) {
    if (!p.has_approximation) continue;
    origin += Eigen::Vector3d(p.xyz[0], p.xyz[1], p.xyz[2]);
    ++points;
  }
  if (points == 0 || network.stations.empty()) return;
  origin /= points;
  const Eigen::Vector3d up = vertical_of(network.stations);
  const auto& first = network.stations.front().exterior;
  const Eigen::Vector3d towards = origin - Eigen::Vector3d(first.X0, first.Y0, first.Z0);
  if (up.norm() < 1e-9) return;  // cameras all around a sphere: no common up
  const Eigen::Vector3d z = up.normalized();
  Eigen::Vector3d y = towards - towards.dot(z) * z;
  if (y.norm() < 1e-9) return;  // the first camera right above the points
  y.normalize();
  Eigen::Matrix3d axes;  // the new axes in the old frame, as columns
  axes << y.cross(z), y, z;
  for (scene::Station& s : network.stations) {
    auto& e = s.exterior;
    const Eigen::Vector3d centre = axes.transpose() * (Eigen::Vector3d(e.X0, e.Y0, e.Z0) - origin);
    const sensor::RotationAngles a = sensor::angles_from_rotation(
        axes.transpose() * sensor::rotation_matrix(e.omega, e.phi, e.kappa));
    e = {centre.x(), centre.y(), centre.z(), a.omega, a.phi, a.kappa};
  }
  for (scene::ObjectPoint& p : network.points) {
    if (!p.has_approximation) continue;
    const Eigen::Vector3d q =
        axes.transpose() * (Eigen::Vector3d(p.xyz[0], p.xyz[1], p.xyz[2]) - origin);
    p.xyz = {q.x(), q.y(), q.z()};
  }
}

// The stage's free and held values, design and tests on `network`.
void prepare_stage(scene::Network& network, const CalibrationOptions& options, Stage stage) {
  const std::vector<int> requested = requested_interior(options);
  const std::set<int> free(requested.begin(), requested.end());
  for (scene::CameraModel& model : network.models) {
    for (int i = 0; i < sensor::InteriorBlock::kSize; ++i) {
      const bool is_free =
          free.count(i) > 0 && (stage.distortion_free || i <= sensor::InteriorBlock::kYp);
      model.priors[static_cast<size_t>(i)] =
          is_free ? scene::ParameterPrior::free() : scene::ParameterPrior::fixed();
    }
    const auto observed = [&](int i, double sigma) {
      if (free.count(i) > 0)
        model.priors[static_cast<size_t>(i)] = scene::ParameterPrior::observed(sigma);
    };
    // The principal point is observed at the image centre (lenses sit centred on their sensor
    // to a few per cent of its size): where the data determine it (a wand seen all over the
    // images) the prior hardly counts; where they do not (one LED in a small volume: a shift of
    // the principal point and a turn of the camera look alike) it holds the point where lenses
    // are. Observed at the approximation, so the approximation is the centre.
    if (principal_point_sigma(options) > 0) {
      const double sigma =
          principal_point_sigma(options) * model.sensor.width_px * model.sensor.pixel_width_mm;
      for (int i : {sensor::InteriorBlock::kXp, sensor::InteriorBlock::kYp}) {
        if (free.count(i) == 0) continue;
        observed(i, sigma);
        (i == sensor::InteriorBlock::kXp ? model.interior.xp : model.interior.yp) = 0.0;
      }
    }
    // One point a frame and no scale leave c weakly determined (thesis Table 4.8): held loosely
    // at its approximation (within half its value) so that blunders cannot walk it off to a
    // degenerate camera (c -> 0) during data snooping. The first stage, with the blunders still
    // in, holds c within a tenth: else it can wander along the flat valley of c against depth
    // (one seed of the strawlab blunder test ended with c 3 to 7 times too long).
    if (options.wand.led) {
      observed(sensor::InteriorBlock::kC,
               (stage.snoop || stage.clean ? 0.5 : 0.1) * model.interior.c);
    }
  }
  network.design.max_iterations = stage.snoop ? kMaxIterations : kFirstStageIterations;
  network.design.calculate_covariance = stage.snoop || stage.clean;
  network.design.statistical_tests = stage.snoop || stage.clean;
  network.design.covariance_stretches = options.covariance_stretches;
  network.design.covariance_cells = options.covariance_cells;
  network.residual_test.iterative_rejection = stage.snoop;
  network.residual_test.reject_per_point = true;
  network.residual_test.critical_snooping = options.critical_snooping;
  network.residual_test.snoop_with_a_posteriori_sigma0 = options.snoop_with_a_posteriori_sigma0;
}

estimators::BundleOptions adjustment_options(const CalibrationOptions& options,
                                             const std::string& what) {
  estimators::BundleOptions bundle;
  if (!options.progress) return bundle;
  using Clock = std::chrono::steady_clock;
  struct Told {
    Clock::time_point start = Clock::now(), last = start;
  };
  auto told = std::make_shared<Told>();
  bundle.progress = [told, what, say = options.progress](const estimators::AdjustmentProgress& p) {
    const Clock::time_point now = Clock::now();
    if (now - told->start < std::chrono::seconds(1) || now - told->last < std::chrono::seconds(1))
      return;
    told->last = now;
    say(util::printf_string("%s: solve %d, iteration %d, cost %.6g, %ld measurements, %.0f s",
                            what.c_str(), p.solve, p.iteration, p.cost, p.measurements_kept,
                            std::chrono::duration<double>(now - told->start).count()));
  };
  return bundle;
}

estimators::BundleAdjustmentResult adjust_stage(scene::Network& network,
                                                const CalibrationOptions& options, Stage stage) {
  prepare_stage(network, options, stage);
  return estimators::adjust(network,
                            adjustment_options(options, stage.snoop   ? "adjustment (data snooping)"
                                                        : stage.clean ? "adjustment (clean)"
                                                                      : "adjustment"));
}

SecondStageStart second_stage_start(scene::Network network, const CalibrationOptions& options) {
  NetworkStart start = start_network(network, options.start);
  SecondStageStart out{std::move(start.network), std::move(start.report), {}};
  scene::Network first_network = triangulated_part(out.network);
  out.first = adjust_stage(first_network, options, {false, false});
  out.network = estimators::with_adjusted_values(std::move(out.network), out.first);
  level_network(out.network);
  return out;
}

}  // namespace syncap::calibration
