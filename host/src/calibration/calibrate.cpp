#include "calibration/calibrate.hpp"
#include "estimators/bootstrap.hpp"
#include "sensor/rotation.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

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
// The thesis finds the interior orientation stable from about 40 wand positions on (Table 4.3).
constexpr size_t kStableFrames = 40;

std::string camera_name(int id) {
  std::ostringstream name;
  name << "camera" << (id < 10 ? "0" : "") << id;
  return name.str();
}

std::string point_name(int64_t frame, int target, bool led) {
  return "f" + std::to_string(frame) + (led ? "" : "t" + std::to_string(target));
}

void say(const CalibrationOptions& options, const std::string& line) {
  if (options.progress) options.progress(line);
}

// The frames used: those where at least two cameras identified the wand, evenly thinned to
// max_frames.
std::vector<int64_t> frames_to_use(const Identification& identification, int max_frames) {
  std::vector<int64_t> frames;
  for (const auto& [frame, cameras] : identification.frames) {
    if (cameras.size() >= 2) frames.push_back(frame);
  }
  if (max_frames <= 0 || static_cast<int>(frames.size()) <= max_frames) return frames;
  std::vector<int64_t> thinned;
  const double step = static_cast<double>(frames.size()) / max_frames;
  for (int i = 0; i < max_frames; ++i) {
    thinned.push_back(frames[static_cast<size_t>(std::floor(i * step))]);
  }
  return thinned;
}

// Start interior: centred principal point, no distortion, c from the typical field of view.
sensor::InteriorOrientation start_interior(const sensor::SensorGeometry& sensor,
                                           double field_of_view_deg) {
  sensor::InteriorOrientation interior;
  const double half_width_mm = 0.5 * sensor.width_px * sensor.pixel_width_mm;
  interior.c = half_width_mm / std::tan(0.5 * field_of_view_deg * kPi / 180.0);
  return interior;
}

const char* kInteriorNames[] = {"c", "xp", "yp", "k1", "k2", "k3", "p1", "p2", "sc", "sh"};
const char* kInteriorUnits[] = {"mm",    "mm",    "mm",    "mm^-2", "mm^-4",
                                "mm^-6", "mm^-1", "mm^-1", "1",     "1"};
const char* kExteriorNames[] = {"X0", "Y0", "Z0", "omega", "phi", "kappa"};
const char* kExteriorUnits[] = {"mm", "mm", "mm", "rad", "rad", "rad"};

const char* mode_name(scene::ParameterMode mode) {
  switch (mode) {
    case scene::ParameterMode::kFixed:
      return "fixed";
    case scene::ParameterMode::kObserved:
      return "observed";
    case scene::ParameterMode::kFree:
      break;
  }
  return "free";
}

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

struct Stage {
  bool distortion_free = false;
  bool snoop = false;
};

// The stage's free and held values, design and tests on `network`.
void prepare_stage(scene::Network& network, const CalibrationOptions& options, Stage stage) {
  std::set<int> free(options.free_interior.begin(), options.free_interior.end());
  if (free.empty()) {
    free = options.wand.led ? std::set<int>{0, 1, 2, 3, 4, 6, 7}
                            : std::set<int>{0, 1, 2, 3, 4, 5, 6, 7};
  }
  for (scene::CameraModel& model : network.models) {
    for (int i = 0; i < sensor::InteriorBlock::kSize; ++i) {
      const bool is_free =
          stage.distortion_free ? free.count(i) > 0 : i <= sensor::InteriorBlock::kYp;
      model.priors[static_cast<size_t>(i)] =
          is_free ? scene::ParameterPrior::free() : scene::ParameterPrior::fixed();
    }
    // One point a frame and no scale leave c and the principal point weakly determined (thesis
    // Table 4.8): held loosely at their approximations (c within half its value, the principal
    // point within a tenth of the sensor) so that blunders cannot walk them off to a degenerate
    // camera (c -> 0) during data snooping. The first stage, with the blunders still in, holds c
    // within a tenth: else it can wander along the flat valley of c against depth (one seed of
    // the strawlab blunder test ended with c 3 to 7 times too long).
    if (options.wand.led) {
      const double width_mm = model.sensor.width_px * model.sensor.pixel_width_mm;
      model.priors[sensor::InteriorBlock::kC] =
          scene::ParameterPrior::observed((stage.snoop ? 0.5 : 0.1) * model.interior.c);
      model.priors[sensor::InteriorBlock::kXp] = scene::ParameterPrior::observed(0.1 * width_mm);
      model.priors[sensor::InteriorBlock::kYp] = scene::ParameterPrior::observed(0.1 * width_mm);
    }
  }
  network.design.max_iterations = stage.snoop ? kMaxIterations : kFirstStageIterations;
  network.design.calculate_covariance = stage.snoop;
  network.design.statistical_tests = stage.snoop;
  network.residual_test.iterative_rejection = stage.snoop;
  network.residual_test.critical_snooping = options.critical_snooping;
  network.residual_test.snoop_with_a_posteriori_sigma0 = options.snoop_with_a_posteriori_sigma0;
}

estimators::BundleAdjustmentResult adjust_stage(scene::Network& network,
                                                const CalibrationOptions& options, Stage stage) {
  prepare_stage(network, options, stage);
  return estimators::adjust(network, {});
}

ReportCamera report_camera(const sensor::CameraModel& camera, const scene::CameraModel& model,
                           const estimators::ModelResult& m, const estimators::StationResult& s) {
  ReportCamera c;
  c.camera = camera;
  const auto interior = sensor::interior_block(m.interior);
  for (int i = 0; i < sensor::InteriorBlock::kSize; ++i) {
    c.parameters.push_back({kInteriorNames[i], interior[static_cast<size_t>(i)],
                            m.interior_sigma[static_cast<size_t>(i)], kInteriorUnits[i],
                            mode_name(model.priors[static_cast<size_t>(i)].mode)});
  }
  const auto exterior = sensor::exterior_block(s.exterior);
  for (int i = 0; i < sensor::ExteriorBlock::kSize; ++i) {
    c.parameters.push_back({kExteriorNames[i], exterior[static_cast<size_t>(i)],
                            s.exterior_sigma[static_cast<size_t>(i)], kExteriorUnits[i], "free"});
  }
  for (int i : m.estimated_interior) c.correlation_names.push_back(kInteriorNames[i]);
  c.correlation = m.interior_correlation;
  c.rms_px = s.rms_px;
  c.observations = s.measurements;
  c.rejected = s.rejected;
  return c;
}

// The adjusted wand lengths, one per frame with both end points adjusted.
std::vector<double> adjusted_wand_lengths(const scene::Network& network,
                                          const estimators::BundleAdjustmentResult& r,
                                          const std::vector<int64_t>& frames,
                                          const WandSpec& wand) {
  std::map<std::string, size_t> index;
  for (size_t p = 0; p < network.points.size(); ++p) index[network.points[p].name] = p;
  std::vector<double> lengths;
  if (wand.led) return lengths;
  for (int64_t frame : frames) {
    const auto a = index.find(point_name(frame, 0, false));
    const auto b = index.find(point_name(frame, wand.targets - 1, false));
    if (a == index.end() || b == index.end()) continue;
    const auto& pa = r.points[a->second];
    const auto& pb = r.points[b->second];
    if (!pa.adjusted || !pb.adjusted) continue;
    lengths.push_back(
        std::hypot(pa.xyz[0] - pb.xyz[0], pa.xyz[1] - pb.xyz[1], pa.xyz[2] - pb.xyz[2]));
  }
  return lengths;
}

// The second stage's approximate values from a network's observations alone: the start
// (relative orientations, resection, scale), the first stage (c, xp, yp and the exterior, on the
// points the start triangulated), and the levelled frame.
struct SecondStageStart {
  scene::Network network;
  NetworkStartReport start;
  estimators::BundleAdjustmentResult first;
};

SecondStageStart second_stage_start(scene::Network network, const CalibrationOptions& options) {
  NetworkStart start = start_network(network, options.start);
  SecondStageStart out{std::move(start.network), std::move(start.report), {}};
  scene::Network first_network = triangulated_part(out.network);
  out.first = adjust_stage(first_network, options, {false, false});
  out.network = estimators::with_adjusted_values(std::move(out.network), out.first);
  level_network(out.network);
  return out;
}

// The parametric bootstrap's interior sigmas beside the linearised ones in the report.
// `nominal`: the camera models the calibration started from.
void add_bootstrap(CalibrationResult& out, const CalibrationOptions& options,
                   const std::vector<scene::CameraModel>& nominal) {
  say(options, "bootstrap: " + std::to_string(options.bootstrap_samples) + " re-adjustments ...");
  estimators::BootstrapOptions bootstrap;
  bootstrap.samples = options.bootstrap_samples;
  // Each sample goes the calibration's whole way from its own observations to the second stage.
  bootstrap.restart = [&options, &nominal](scene::Network sample) {
    for (size_t m = 0; m < sample.models.size() && m < nominal.size(); ++m) {
      sample.models[m].interior = nominal[m].interior;
    }
    scene::Network second = second_stage_start(std::move(sample), options).network;
    prepare_stage(second, options, {true, true});
    return second;
  };
  const estimators::BootstrapResult b =
      estimators::bootstrap_precision(out.network, out.adjustment, bootstrap);
  out.report.bootstrap_samples = b.samples;
  for (size_t s = 0; s < out.report.cameras.size() && s < b.interior_sigma.size(); ++s) {
    auto& parameters = out.report.cameras[s].parameters;
    for (int i = 0; i < sensor::InteriorBlock::kSize && i < static_cast<int>(parameters.size());
         ++i) {
      parameters[static_cast<size_t>(i)].bootstrap_sigma =
          b.interior_sigma[s][static_cast<size_t>(i)];
    }
  }
  say(options, "bootstrap: " + std::to_string(b.samples) + " converged, " +
                   std::to_string(b.failed) + " did not");
}

void fill_report(CalibrationResult& out, const Observations& observations,
                 const CalibrationOptions& options, const std::vector<int64_t>& frames) {
  const auto& r = out.adjustment;
  const scene::Network& network = out.network;
  CalibrationReport& report = out.report;
  report.input = observations.source;
  std::map<std::string, int> camera_of_station;
  for (size_t s = 0; s < network.stations.size(); ++s) {
    camera_of_station[network.stations[s].name] = network.stations[s].camera_id;
    report.cameras.push_back(
        report_camera(out.cameras[s], network.models[s], r.models[s], r.stations[s]));
  }
  for (size_t m = 0; m < network.measurements.size(); ++m) {
    const auto& meas = network.measurements[m];
    const auto& res = r.measurements[m];
    const double w = std::abs(res.w_u) > std::abs(res.w_v) ? res.w_u : res.w_v;
    report.residuals.push_back({camera_of_station[meas.station], meas.frame_number, meas.u, meas.v,
                                res.residual_u, res.residual_v, w,
                                res.status != estimators::MeasurementStatus::kAccepted});
  }
  for (const auto& p : r.points) {
    if (p.adjusted) report.points.emplace_back(p.xyz[0], p.xyz[1], p.xyz[2]);
  }
  report.wand_lengths_mm = adjusted_wand_lengths(network, r, frames, options.wand);
  report.wand_length_mm = options.wand.led ? 0.0 : options.wand.length_mm;
  report.sigma0 = r.sigma0;
  report.observations = r.observations;
  report.unknowns = r.unknowns;
  report.redundancy = r.redundancy;
  report.iterations = r.iterations;
  report.converged = r.converged;
  report.outliers_removed = static_cast<long>(r.rejected.size());
  if (r.tests_computed) {
    const auto& v = r.variance_test;
    report.tests.push_back(
        {"variance factor (chi-square, two-tailed)", v.variance_factor, v.lower, v.upper, v.passed,
         "sigma0^2 against its interval for redundancy " + std::to_string(v.redundancy)});
    const auto& g = r.goodness_of_fit;
    std::ostringstream detail;
    detail << g.samples << " standardised residuals in " << g.bins
           << " classes; Kolmogorov-Smirnov distance " << g.ks_distance << ", p " << g.ks_p_value;
    report.tests.push_back({"goodness of fit (chi-square of the standardised residuals)",
                            g.statistic, 0.0, g.critical, g.passed, detail.str()});
  }
  std::istringstream identification(format_identification(out.identification));
  for (std::string line; std::getline(identification, line);) report.messages.push_back(line);
  if (observations.incomplete_groups > 0) {
    report.messages.push_back(std::to_string(observations.incomplete_groups) +
                              " frame groups lacked a camera");
  }
  for (const std::string& m : r.messages) report.messages.push_back(m);
  if (options.bootstrap_samples < 2 && (options.wand.led || frames.size() < kStableFrames)) {
    report.messages.push_back(
        "weak network (" +
        (options.wand.led ? std::string("one LED a frame")
                          : std::to_string(frames.size()) + " wand positions") +
        "): its minima are several and its linearised sigmas can understate the errors several "
        "times; --bootstrap 30 gives sigmas that cover them (docs/calibration.md)");
  }
}

sensor::CalibrationQuality quality_of(const CalibrationResult& out, const CalibrationOptions& o) {
  const auto& r = out.adjustment;
  sensor::CalibrationQuality q;
  q.sigma0_px = r.sigma0 * o.sigma_px;
  double square_sum = 0;
  long accepted = 0;
  for (const auto& m : r.measurements) {
    if (m.status != estimators::MeasurementStatus::kAccepted) continue;
    square_sum += m.residual_u * m.residual_u + m.residual_v * m.residual_v;
    ++accepted;
  }
  q.rms_px = accepted ? std::sqrt(square_sum / (2.0 * accepted)) : 0.0;
  for (const auto& s : r.stations) q.per_camera_rms_px[s.camera_id] = s.rms_px;
  q.observations = accepted;
  q.outliers_removed = static_cast<long>(r.rejected.size());
  const auto& lengths = out.report.wand_lengths_mm;
  if (!o.wand.led && !lengths.empty()) {
    double sum = 0, sum2 = 0;
    for (double l : lengths) sum += l;
    const double mean = sum / static_cast<double>(lengths.size());
    for (double l : lengths) sum2 += (l - mean) * (l - mean);
    q.wand_length_mean_mm = mean;
    q.wand_length_sd_mm =
        lengths.size() > 1 ? std::sqrt(sum2 / static_cast<double>(lengths.size() - 1)) : 0.0;
  }
  return q;
}

void check_options(const CalibrationOptions& options) {
  const WandSpec& wand = options.wand;
  if (!wand.led) {
    if (!(wand.length_mm > 0)) throw CalibrationError("calibrate: the wand length must be > 0 mm");
    if (wand.targets != 2 && wand.targets != 3) {
      throw CalibrationError("calibrate: a wand has 2 or 3 targets, not " +
                             std::to_string(wand.targets));
    }
    if (wand.targets == 3 && !(wand.middle_ratio > 0.05 && wand.middle_ratio < 0.95)) {
      throw CalibrationError("calibrate: the middle target's ratio must lie in (0.05, 0.95)");
    }
  }
  if (!(options.field_of_view_deg > 5 && options.field_of_view_deg < 170)) {
    throw CalibrationError("calibrate: the field of view must lie in (5, 170) degrees");
  }
  if (options.bootstrap_samples < 0 || options.bootstrap_samples == 1) {
    throw CalibrationError("calibrate: --bootstrap needs at least 2 re-adjustments, not " +
                           std::to_string(options.bootstrap_samples));
  }
  if (!(options.sigma_px > 0)) throw CalibrationError("calibrate: sigma_px must be > 0");
}

}  // namespace

scene::Network build_network(const Observations& observations, const Identification& identification,
                             const CalibrationOptions& options) {
  check_options(options);
  const WandSpec& wand = options.wand;
  scene::Network network;
  std::map<int, std::string> station_of;
  for (int id : observations.cameras()) {
    const auto size = observations.image_sizes.find(id);
    if (size == observations.image_sizes.end() || size->second.width <= 0) {
      throw CalibrationError("calibrate: camera " + std::to_string(id) + " of " +
                             observations.source + " has no image size");
    }
    const auto pixel = options.pixel_size_mm_by_camera.find(id);
    const double mu =
        pixel == options.pixel_size_mm_by_camera.end() ? options.pixel_size_mm : pixel->second;
    scene::CameraModel model;
    model.name = camera_name(id);
    model.sensor = {size->second.width, size->second.height, mu, mu};
    model.interior = start_interior(model.sensor, options.field_of_view_deg);
    network.models.push_back(model);
    scene::Station station;
    station.name = camera_name(id);
    station.camera_id = id;
    station.model = model.name;
    network.stations.push_back(station);
    station_of[id] = station.name;
  }
  if (network.stations.size() < 2) {
    throw CalibrationError("calibrate: " + observations.source + " has " +
                           std::to_string(network.stations.size()) +
                           " camera(s); a calibration needs at least 2");
  }
  const std::vector<double> offsets = wand.offsets_mm();
  const int targets = wand.point_count();
  for (int64_t frame : frames_to_use(identification, options.max_frames)) {
    const auto& cameras = identification.frames.at(frame);
    std::vector<bool> has_point(static_cast<size_t>(targets), false);
    for (int t = 0; t < targets; ++t) {
      int rays = 0;
      for (const auto& [camera, positions] : cameras) {
        if (static_cast<int>(positions.size()) > t && positions[static_cast<size_t>(t)]) ++rays;
      }
      if (rays < 2) continue;
      has_point[static_cast<size_t>(t)] = true;
      scene::ObjectPoint point;
      point.name = point_name(frame, t, wand.led);
      network.points.push_back(point);
      for (const auto& [camera, positions] : cameras) {
        if (static_cast<int>(positions.size()) <= t || !positions[static_cast<size_t>(t)]) continue;
        const Eigen::Vector2d& p = *positions[static_cast<size_t>(t)];
        network.measurements.push_back(
            {station_of.at(camera), point.name, p.x(), p.y(), options.sigma_px, frame});
      }
    }
    for (int t = 1; t < targets; ++t) {
      if (!has_point[static_cast<size_t>(t - 1)] || !has_point[static_cast<size_t>(t)]) continue;
      network.distances.push_back(
          {point_name(frame, t - 1, false), point_name(frame, t, false),
           offsets[static_cast<size_t>(t)] - offsets[static_cast<size_t>(t - 1)],
           options.wand_sigma_mm});
    }
  }
  // A camera with nothing to contribute is named here, with what its identification found.
  std::map<std::string, long> per_station;
  for (const auto& m : network.measurements) ++per_station[m.station];
  for (const auto& [id, name] : station_of) {
    if (per_station[name] > 0) continue;
    const auto stats = identification.cameras.find(id);
    std::string why = "it reported no frames";
    if (stats != identification.cameras.end()) {
      const auto& s = stats->second;
      why = "of its " + std::to_string(s.frames) + " frames " + std::to_string(s.identified) +
            " had the wand identified (" + std::to_string(s.missing) + " missing, " +
            std::to_string(s.ambiguous) + " ambiguous), none shared with another camera";
    }
    throw CalibrationError("calibrate: camera " + std::to_string(id) + " has no usable " +
                           (wand.led ? "point" : "wand targets") + ": " + why);
  }
  return network;
}

CalibrationResult calibrate(const Observations& observations, const CalibrationOptions& options) {
  check_options(options);
  CalibrationResult out;
  say(options, "observations: " + std::to_string(observations.frames.size()) + " frames, " +
                   std::to_string(observations.cameras().size()) + " cameras, " +
                   std::to_string(observations.spot_count()) + " spots");
  out.identification = identify_targets(observations, options.wand, options.identification);
  {
    std::istringstream lines(format_identification(out.identification));
    for (std::string line; std::getline(lines, line);) say(options, "identified " + line);
  }
  scene::Network network = build_network(observations, out.identification, options);
  std::vector<int64_t> frames = frames_to_use(out.identification, options.max_frames);
  say(options, "network: " + std::to_string(network.stations.size()) + " cameras, " +
                   std::to_string(network.points.size()) + " points, " +
                   std::to_string(network.measurements.size()) + " measurements, " +
                   std::to_string(network.distances.size()) + " distances");

  const std::vector<scene::CameraModel> nominal = network.models;  // the bootstrap restarts there
  SecondStageStart second = second_stage_start(std::move(network), options);
  out.start = second.start;
  say(options, "start values: root " + second.start.root + ", " +
                   std::to_string(second.start.triangulated_points) + " points triangulated" +
                   (second.start.resected.empty()
                        ? std::string()
                        : ", " + std::to_string(second.start.resected.size()) + " resected"));
  say(options, "adjustment 1/2 (c, xp, yp, exterior): " + std::to_string(second.first.iterations) +
                   " iterations, sigma0 " + std::to_string(second.first.sigma0));
  network = std::move(second.network);
  out.adjustment = adjust_stage(network, options, {true, true});
  say(options, "adjustment 2/2 (all interior values, data snooping): " +
                   std::to_string(out.adjustment.adjustments) + " adjustments, " +
                   std::to_string(out.adjustment.rejected.size()) + " outliers removed, sigma0 " +
                   std::to_string(out.adjustment.sigma0));
  out.network = std::move(network);

  for (size_t s = 0; s < out.network.stations.size(); ++s) {
    const auto& m = out.adjustment.models[s];
    const auto& st = out.adjustment.stations[s];
    sensor::CameraModel camera;
    camera.id = st.camera_id;
    camera.sensor = out.network.models[s].sensor;
    camera.interior = m.interior;
    camera.exterior = st.exterior;
    if (out.adjustment.covariance_computed) {
      camera.std_devs =
          sensor::CameraStdDevs{sensor::interior_from_block(m.interior_sigma.data()),
                                sensor::exterior_from_block(st.exterior_sigma.data())};
    }
    out.cameras.push_back(camera);
  }
  for (size_t m = 0; m < out.network.measurements.size(); ++m) {
    out.measurements_of_point[out.network.measurements[m].point].push_back(m);
  }
  fill_report(out, observations, options, frames);
  if (options.bootstrap_samples > 1 && out.adjustment.converged) {
    add_bootstrap(out, options, nominal);
  }
  out.quality = quality_of(out, options);
  return out;
}

}  // namespace syncap::calibration
