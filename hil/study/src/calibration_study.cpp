#include "calibration_study.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <stdexcept>

#include "calibration/network_start.hpp"
#include "camera_rig.hpp"
#include "estimators/bootstrap.hpp"
#include "estimators/bundle_adjustment.hpp"
#include "geometry/triangulation.hpp"
#include "sensor/camera_model.hpp"

namespace syncap::study {
namespace {

using estimators::BundleAdjustmentResult;
using estimators::SimulatedWandNetwork;
using estimators::WandSimulation;
using sensor::InteriorBlock;

// The parameters of Table 4.3 in its column order.
constexpr std::array<int, 5> kTableParameters{InteriorBlock::kC, InteriorBlock::kXp,
                                              InteriorBlock::kYp, InteriorBlock::kSc,
                                              InteriorBlock::kK1};
constexpr std::array<int, 3> kPrincipalParameters{InteriorBlock::kC, InteriorBlock::kXp,
                                                  InteriorBlock::kYp};

// Thesis Table 4.3 (thesis.txt lines 3283-3286).
struct ThesisRow {
  int wands;
  std::array<double, 8> values;
};
constexpr std::array<ThesisRow, 3> kThesisTable43{{
    {10, {0.431, 0.522, 0.983, 0.0065, 0.00009, 1.479, 1.171, 2.567}},
    {40, {0.051, 0.031, 0.155, 0.0015, 0.00011, 0.643, 0.551, 1.301}},
    {100, {0.041, 0.021, 0.085, 0.0012, 0.00010, 0.591, 0.488, 1.107}},
}};

// Weak networks (10 wand positions, 1 px) creep along the valley of the correlated k1, k2, k3 and
// need up to ~110 iterations; the default of 50 stops them short of convergence.
constexpr int kMaxIterations = 300;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The point nearest to the rays, then Gauss-Newton on the reprojection errors (the maximum
// likelihood point for equal image noise). False when fewer than two cameras see it.
bool triangulate(const std::vector<const sensor::CameraModel*>& cameras,
                 const std::vector<Eigen::Vector2d>& pixels, Eigen::Vector3d& point) {
  if (cameras.size() < 2) return false;
  geometry::NearestPoint nearest;
  for (size_t i = 0; i < cameras.size(); ++i) nearest.add(cameras[i]->back_project(pixels[i]));
  const auto refined = geometry::refine_by_reprojection(cameras, pixels, nearest.solve());
  if (refined) point = *refined;
  return refined.has_value();
}

// The estimated cameras by station name.
std::map<std::string, sensor::CameraModel> estimated_cameras(const BundleAdjustmentResult& r,
                                                             const scene::Network& network) {
  std::map<std::string, const estimators::ModelResult*> models;
  for (const auto& model : r.models) models[model.name] = &model;
  std::map<std::string, sensor::CameraModel> cameras;
  for (size_t s = 0; s < r.stations.size(); ++s) {
    const scene::Station& station = network.stations[s];
    const scene::CameraModel* given = nullptr;
    for (const auto& model : network.models) {
      if (model.name == station.model) given = &model;
    }
    sensor::CameraModel camera;
    camera.id = station.camera_id;
    camera.sensor = given->sensor;
    camera.interior = models.at(station.model)->interior;
    camera.exterior = r.stations[s].exterior;
    cameras[station.name] = camera;
  }
  return cameras;
}

double mean_of(const std::vector<double>& values) {
  double sum = 0.0;
  for (double v : values) sum += v;
  return sum / static_cast<double>(values.size());
}

double standard_deviation(const std::vector<double>& values) {
  const double m = mean_of(values);
  double squares = 0.0;
  for (double v : values) squares += (v - m) * (v - m);
  return std::sqrt(squares / static_cast<double>(values.size() - 1));
}

// The true cameras in place of the estimated ones of a ray list.
std::vector<const sensor::CameraModel*> truth_of(
    const std::vector<const sensor::CameraModel*>& estimated,
    const std::map<std::string, sensor::CameraModel>& estimated_by_name,
    const std::map<std::string, sensor::CameraModel>& true_by_name) {
  std::vector<const sensor::CameraModel*> out;
  for (const sensor::CameraModel* camera : estimated) {
    for (const auto& [name, model] : estimated_by_name) {
      if (&model == camera) out.push_back(&true_by_name.at(name));
    }
  }
  return out;
}

// The simulation's true cameras by station name (each station has a model of that name).
std::map<std::string, const sensor::CameraModel*> true_cameras_by_name(
    const SimulatedWandNetwork& simulated) {
  std::map<std::string, const sensor::CameraModel*> cameras;
  for (const auto& camera : simulated.cameras) {
    cameras["camera" + std::to_string(camera.id)] = &camera;
  }
  return cameras;
}

// The simulation's true points by name.
std::map<std::string, Eigen::Vector3d> true_points_by_name(const SimulatedWandNetwork& simulated) {
  std::map<std::string, Eigen::Vector3d> points;
  for (size_t i = 0; i < simulated.points.size(); ++i) {
    points[simulated.network.points[i].name] = simulated.points[i];
  }
  return points;
}

// Measures the wand's end-to-end length on fresh wand positions with the estimated cameras.
void check_wand_length(const WandSimulation& simulation,
                       const std::map<std::string, sensor::CameraModel>& cameras, int frames,
                       RunResult& out) {
  WandSimulation check = simulation;
  check.frames = frames;
  check.seed = simulation.seed ^ 0x5eed0001u;
  const SimulatedWandNetwork fresh = estimators::simulate_wand_network(check);
  std::map<std::string,
           std::pair<std::vector<const sensor::CameraModel*>, std::vector<Eigen::Vector2d>>>
      rays;
  for (const auto& m : fresh.network.measurements) {
    auto& [who, pixels] = rays[m.point];
    who.push_back(&cameras.at(m.station));
    pixels.emplace_back(m.u, m.v);
  }
  const auto& offsets = simulation.target_offsets_mm;
  out.wand_length_mm = offsets.back() - offsets.front();
  std::map<std::string, sensor::CameraModel> true_cameras;
  for (const auto& camera : fresh.cameras) {
    true_cameras["camera" + std::to_string(camera.id)] = camera;
  }
  std::vector<double> deviations, true_deviations;
  for (int frame = 0; frame < frames; ++frame) {
    const std::string first = "f" + std::to_string(frame) + "t0";
    const std::string last = "f" + std::to_string(frame) + "t" + std::to_string(offsets.size() - 1);
    Eigen::Vector3d a, b;
    if (!rays.count(first) || !rays.count(last)) continue;
    if (!triangulate(rays[first].first, rays[first].second, a)) continue;
    if (!triangulate(rays[last].first, rays[last].second, b)) continue;
    deviations.push_back((a - b).norm() - out.wand_length_mm);
    const auto& [cameras_a, pixels_a] = rays[first];
    const auto& [cameras_b, pixels_b] = rays[last];
    if (!triangulate(truth_of(cameras_a, cameras, true_cameras), pixels_a, a)) continue;
    if (!triangulate(truth_of(cameras_b, cameras, true_cameras), pixels_b, b)) continue;
    true_deviations.push_back((a - b).norm() - out.wand_length_mm);
  }
  out.wand_frames = static_cast<int>(deviations.size());
  if (deviations.size() < 2 || true_deviations.size() < 2) return;
  out.wand_length_bias_mm = mean_of(deviations);
  out.wand_length_sd_mm = standard_deviation(deviations);
  out.wand_length_sd_true_cameras_mm = standard_deviation(true_deviations);
}

// The network adjusted again from the true values (all of them approximate values): where it
// ends against where the adjustment from the start values ended (`r`): the largest difference of
// c, xp, yp, sc, k1 in r's sigmas, and of v^T P v.
void adjust_from_truth(const scene::Network& network, const SimulatedWandNetwork& simulated,
                       const BundleAdjustmentResult& r, RunResult& out) {
  scene::Network truth = network;
  const auto cameras = true_cameras_by_name(simulated);
  for (auto& station : truth.stations) {
    station.exterior = cameras.at(station.name)->exterior;
    station.has_approximation = true;
  }
  for (auto& model : truth.models) model.interior = cameras.at(model.name)->interior;
  const auto points = true_points_by_name(simulated);
  for (auto& point : truth.points) {
    const Eigen::Vector3d& xyz = points.at(point.name);
    point.xyz = {xyz.x(), xyz.y(), xyz.z()};
    point.has_approximation = true;
  }
  truth.design.calculate_covariance = false;
  const BundleAdjustmentResult t = estimators::adjust(truth, {});
  if (!t.converged) return;
  out.from_truth_converged = true;
  const auto square_sum = [](const BundleAdjustmentResult& a) {
    return a.sigma0 * a.sigma0 * static_cast<double>(a.redundancy);
  };
  out.from_truth_square_sum_difference = square_sum(t) - square_sum(r);
  for (size_t c = 0; c < r.models.size() && c < t.models.size(); ++c) {
    const auto a = sensor::interior_block(r.models[c].interior);
    const auto b = sensor::interior_block(t.models[c].interior);
    for (const int k : kTableParameters) {
      const double sigma = r.models[c].interior_sigma[static_cast<size_t>(k)];
      if (sigma <= 0.0) continue;
      out.from_truth_shift =
          std::max(out.from_truth_shift,
                   std::abs(b[static_cast<size_t>(k)] - a[static_cast<size_t>(k)]) / sigma);
    }
  }
}

// The adjusted points against the truth after the rigid motion that fits them best (the
// inner-constraint datum of the covariance: minimum trace over the points, scale from the wand).
// `bootstrap`: the points' covariances from the bootstrap (empty: none).
void compare_points(const BundleAdjustmentResult& r, const SimulatedWandNetwork& simulated,
                    const std::map<std::string, Eigen::Matrix3d>& bootstrap, RunResult& out) {
  const auto truth = true_points_by_name(simulated);
  std::vector<const estimators::PointResult*> adjusted;
  for (const auto& p : r.points) {
    if (p.adjusted && truth.count(p.name)) adjusted.push_back(&p);
  }
  if (adjusted.size() < 3) return;
  Eigen::Matrix3Xd from(3, adjusted.size()), to(3, adjusted.size());
  for (size_t i = 0; i < adjusted.size(); ++i) {
    from.col(i) = Eigen::Vector3d(adjusted[i]->xyz.data());
    to.col(i) = truth.at(adjusted[i]->name);
    for (int k = 0; k < 3; ++k) out.mean_point_sigma[k] += adjusted[i]->sigma[k] / adjusted.size();
  }
  const Eigen::Matrix4d motion = Eigen::umeyama(from, to, false);
  const Eigen::Matrix3d rotation = motion.topLeftCorner<3, 3>();
  for (size_t i = 0; i < adjusted.size(); ++i) {
    const Eigen::Vector3d error =
        rotation * from.col(i) + motion.topRightCorner<3, 1>() - to.col(i);
    const Eigen::Matrix3d covariance = rotation * adjusted[i]->covariance * rotation.transpose();
    for (int k = 0; k < 3; ++k) out.point_errors_3.add(error[k], std::sqrt(covariance(k, k)));
    const auto spread = bootstrap.find(adjusted[i]->name);
    if (spread == bootstrap.end()) continue;
    const Eigen::Matrix3d b = rotation * spread->second * rotation.transpose();
    for (int k = 0; k < 3; ++k) out.point_errors_3_bootstrap.add(error[k], std::sqrt(b(k, k)));
  }
}

void image_residual_figures(const BundleAdjustmentResult& r, double noise_px, RunResult& out) {
  double squares = 0.0;
  long coordinates = 0;
  for (const auto& m : r.measurements) {
    if (m.status != estimators::MeasurementStatus::kAccepted) continue;
    squares += m.residual_u * m.residual_u + m.residual_v * m.residual_v;
    coordinates += 2;
  }
  out.noise_px = noise_px;
  out.rms_px = coordinates > 0 ? std::sqrt(squares / coordinates) : 0.0;
  out.sigma_image_px = r.sigma0 * noise_px;
  out.expected_rms_px =
      noise_px * std::sqrt(static_cast<double>(r.redundancy) / static_cast<double>(r.observations));
}

void image_coverage(const SimulatedWandNetwork& simulated, RunResult& out) {
  const auto cameras = true_cameras_by_name(simulated);
  for (const auto& m : simulated.network.measurements) {
    const sensor::CameraModel& camera = *cameras.at(m.station);
    const Eigen::Vector2d image = camera.image_from_pixel({m.u, m.v}) -
                                  Eigen::Vector2d(camera.interior.xp, camera.interior.yp);
    out.max_image_radius_mm = std::max(out.max_image_radius_mm, image.norm());
    out.half_diagonal_mm =
        0.5 * std::hypot(camera.sensor.width_px * camera.sensor.pixel_width_mm,
                         camera.sensor.height_px * camera.sensor.pixel_height_mm);
  }
}

double mean(double sum, int count) { return count > 0 ? sum / count : 0.0; }

}  // namespace

void SigmaCount::add(double error, double sigma) {
  const double normalised = error / sigma;
  ++total;
  if (std::abs(normalised) <= k) ++within;
  sum_squares += normalised * normalised;
}

void SigmaCount::merge(const SigmaCount& other) {
  within += other.within;
  total += other.total;
  sum_squares += other.sum_squares;
}

double SigmaCount::rms() const { return total > 0 ? std::sqrt(sum_squares / total) : 0.0; }

double normal_within(double k) { return std::erf(k / std::sqrt(2.0)); }

WandSimulation simulation_from_scenario(const sim::Scenario& scenario, int frames, double noise_px,
                                        double wand_sigma_mm, uint32_t seed) {
  const auto wand = std::find_if(scenario.phases.begin(), scenario.phases.end(),
                                 [](const sim::PhaseSpec& p) { return p.type == "wand"; });
  if (wand == scenario.phases.end()) {
    throw std::invalid_argument(scenario.file.string() + ": scenario \"" + scenario.name +
                                "\" has no wand phase");
  }
  WandSimulation simulation;
  simulation.true_cameras = sim::build_rig(scenario);
  simulation.cameras = static_cast<int>(simulation.true_cameras.size());
  simulation.sensor = simulation.true_cameras.front().sensor;
  simulation.interior = simulation.true_cameras.front().interior;
  simulation.look_at_mm = scenario.cameras.look_at_mm;
  simulation.volume_min_mm = scenario.volume_min_mm;
  simulation.volume_max_mm = scenario.volume_max_mm;
  simulation.target_offsets_mm = wand->wand.target_offsets_mm;
  simulation.frames = frames;
  simulation.noise_px = noise_px;
  simulation.wand_sigma_mm = wand_sigma_mm;
  simulation.seed = seed;
  return simulation;
}

RunResult run_calibration(const WandSimulation& simulation, int wand_check_frames,
                          int bootstrap_samples) {
  const auto start_time = std::chrono::steady_clock::now();
  RunResult out;
  const SimulatedWandNetwork simulated = estimators::simulate_wand_network(simulation);
  scene::Network network = simulated.network;
  // No blunders are simulated: data snooping would only remove the ~0.1 % good measurements
  // beyond its critical value, and each removal costs a re-adjustment.
  network.residual_test.iterative_rejection = false;
  network.design.max_iterations = kMaxIterations;
  for (auto& station : network.stations) station.has_approximation = false;
  try {
    const calibration::NetworkStart start = calibration::start_network(network);
    const BundleAdjustmentResult r = estimators::adjust(start.network, {});
    out.iterations = r.iterations;
    if (!r.converged || !r.covariance_computed) {
      out.failure =
          "adjustment: " + r.termination + (r.covariance_computed ? "" : " (no covariance)");
      out.seconds = seconds_since(start_time);
      return out;
    }
    out.observations = r.observations;
    out.redundancy = r.redundancy;
    out.sigma0 = r.sigma0;
    image_residual_figures(r, simulation.noise_px, out);
    image_coverage(simulated, out);
    const auto truth = true_cameras_by_name(simulated);
    for (const auto& model : r.models) {
      const auto estimate = sensor::interior_block(model.interior);
      const auto true_values = sensor::interior_block(truth.at(model.name)->interior);
      std::array<double, InteriorBlock::kSize> error{};
      for (int k = 0; k < InteriorBlock::kSize; ++k) error[k] = estimate[k] - true_values[k];
      out.interior_error.push_back(error);
      out.interior_sigma.push_back(model.interior_sigma);
    }
    estimators::BootstrapResult bootstrap;
    if (bootstrap_samples > 0) {
      estimators::BootstrapOptions options;
      options.samples = bootstrap_samples;
      options.seed = simulation.seed;
      options.restart = [](scene::Network sample) {
        return calibration::start_network(sample).network;
      };
      bootstrap = estimators::bootstrap_precision(start.network, r, options);
      out.interior_sigma_bootstrap = bootstrap.interior_sigma;
    }
    compare_points(r, simulated, bootstrap.point_covariance, out);
    if (bootstrap_samples > 0) adjust_from_truth(start.network, simulated, r, out);
    if (wand_check_frames > 0) {
      check_wand_length(simulation, estimated_cameras(r, start.network), wand_check_frames, out);
    }
    out.ok = true;
  } catch (const std::exception& e) {
    out.failure = e.what();
  }
  out.seconds = seconds_since(start_time);
  return out;
}

namespace {

Table43Row run_table_4_3_row(const sim::Scenario& basler, const Table43Options& options,
                             double noise_px, int wands) {
  const auto start_time = std::chrono::steady_clock::now();
  Table43Row row;
  row.wands = wands;
  row.noise_px = noise_px;
  for (const ThesisRow& thesis : kThesisTable43) {
    if (thesis.wands == wands) row.thesis = thesis.values;
  }
  double sigma0_sum = 0.0;
  int cameras = 0;
  for (int run = 0; run < options.runs; ++run) {
    const uint32_t seed = options.seed + 1000u * static_cast<uint32_t>(wands) + run;
    const RunResult r = run_calibration(
        simulation_from_scenario(basler, wands, noise_px, options.wand_sigma_mm, seed), 0,
        options.bootstrap_samples);
    ++row.runs;
    if (!r.ok) {
      ++row.failed;
      row.failures.push_back("seed " + std::to_string(seed) + ": " + r.failure);
      continue;
    }
    sigma0_sum += r.sigma0;
    for (size_t c = 0; c < r.interior_sigma.size(); ++c, ++cameras) {
      for (size_t p = 0; p < kTableParameters.size(); ++p) {
        const int k = kTableParameters[p];
        row.ours[p] += r.interior_sigma[c][k];
        row.interior_3.add(r.interior_error[c][k], r.interior_sigma[c][k]);
        row.interior_2.add(r.interior_error[c][k], r.interior_sigma[c][k]);
        row.per_parameter[p].add(r.interior_error[c][k], r.interior_sigma[c][k]);
        if (c < r.interior_sigma_bootstrap.size() && r.interior_sigma_bootstrap[c][k] > 0.0) {
          const double sigma = r.interior_sigma_bootstrap[c][k];
          row.interior_3_bootstrap.add(r.interior_error[c][k], sigma);
          row.per_parameter_bootstrap[p].add(r.interior_error[c][k], sigma);
        }
      }
    }
    for (int k = 0; k < 3; ++k) row.ours[5 + k] += r.mean_point_sigma[k];
    row.points_3.merge(r.point_errors_3);
    row.points_3_bootstrap.merge(r.point_errors_3_bootstrap);
    if (r.from_truth_converged) {
      ++row.from_truth_runs;
      if (r.from_truth_shift > 3.0) {
        ++row.other_minimum_runs;
        row.other_minimum_square_sums.push_back(r.from_truth_square_sum_difference);
      }
    }
    row.max_image_radius_mm = std::max(row.max_image_radius_mm, r.max_image_radius_mm);
    row.half_diagonal_mm = r.half_diagonal_mm;
  }
  const int good = row.runs - row.failed;
  for (size_t p = 0; p < kTableParameters.size(); ++p) row.ours[p] = mean(row.ours[p], cameras);
  for (int k = 0; k < 3; ++k) row.ours[5 + k] = mean(row.ours[5 + k], good);
  row.mean_sigma0 = mean(sigma0_sum, good);
  row.seconds = seconds_since(start_time);
  return row;
}

}  // namespace

std::vector<Table43Row> run_table_4_3(const sim::Scenario& basler, const Table43Options& options) {
  std::vector<Table43Row> rows;
  for (double noise_px : options.noise_px) {
    for (int wands : options.wands)
      rows.push_back(run_table_4_3_row(basler, options, noise_px, wands));
  }
  return rows;
}

RingStudy run_ring_study(const sim::Scenario& ring, const RingOptions& options) {
  const auto start_time = std::chrono::steady_clock::now();
  RingStudy study;
  study.wands = options.wands;
  study.noise_px = options.noise_px;
  for (int run = 0; run < options.runs; ++run) {
    const uint32_t seed = options.seed + static_cast<uint32_t>(run);
    RunResult r = run_calibration(simulation_from_scenario(ring, options.wands, options.noise_px,
                                                           options.wand_sigma_mm, seed),
                                  options.wand_check_frames);
    ++study.runs;
    if (!r.ok) {
      ++study.failed;
      study.failures.push_back("seed " + std::to_string(seed) + ": " + r.failure);
      continue;
    }
    for (size_t c = 0; c < r.interior_sigma.size(); ++c) {
      for (int k : kPrincipalParameters) {
        study.principal_2.add(r.interior_error[c][k], r.interior_sigma[c][k]);
        study.principal_3.add(r.interior_error[c][k], r.interior_sigma[c][k]);
      }
    }
    study.worst_sigma_image_deviation =
        std::max(study.worst_sigma_image_deviation, std::abs(r.sigma_image_px / r.noise_px - 1.0));
    const double share = r.wand_frames >= 2 ? r.wand_length_sd_mm / r.wand_length_mm : 1.0;
    study.worst_wand_sd_share = std::max(study.worst_wand_sd_share, share);
    study.results.push_back(std::move(r));
  }
  double variance = 0.0, true_variance = 0.0;
  for (const RunResult& r : study.results) {
    study.wand_length_mm = r.wand_length_mm;
    variance += r.wand_length_sd_mm * r.wand_length_sd_mm / study.results.size();
    true_variance +=
        r.wand_length_sd_true_cameras_mm * r.wand_length_sd_true_cameras_mm / study.results.size();
  }
  study.pooled_wand_sd_mm = std::sqrt(variance);
  study.pooled_wand_sd_true_cameras_mm = std::sqrt(true_variance);
  study.seconds = seconds_since(start_time);
  return study;
}

double calibration_share_mm(const RingStudy& ring) {
  const double sd = ring.pooled_wand_sd_mm, floor = ring.pooled_wand_sd_true_cameras_mm;
  return std::sqrt(std::max(0.0, sd * sd - floor * floor));
}

}  // namespace syncap::study
