#include "estimators/bootstrap.hpp"

#include <glog/logging.h>

#include <cmath>
#include <map>
#include <random>
#include <set>
#include <stdexcept>
#include <string>

#include "sensor/camera_model.hpp"

namespace syncap::estimators {
namespace {

Eigen::Vector3d xyz_of(const scene::ObjectPoint& point) {
  return {point.xyz[0], point.xyz[1], point.xyz[2]};
}

// Replaces every observation of `network` (its values taken for the truth) by a noisy one:
// sigma x `scale` of Gaussian noise on the measurements, the distances and the observed
// parameters.
void simulate_observations(scene::Network& network, double scale, std::mt19937& rng) {
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::map<std::string, const scene::ObjectPoint*> points;
  for (const auto& p : network.points) points[p.name] = &p;
  std::map<std::string, sensor::CameraModel> cameras;
  for (const auto& station : network.stations) {
    for (const auto& model : network.models) {
      if (model.name != station.model) continue;
      sensor::CameraModel& camera = cameras[station.name];
      camera.sensor = model.sensor;
      camera.interior = model.interior;
      camera.exterior = station.exterior;
    }
  }
  for (auto& m : network.measurements) {
    const auto projection = cameras.at(m.station).project(xyz_of(*points.at(m.point)));
    m.u = projection.pixel.x() + scale * m.sigma_px * gauss(rng);
    m.v = projection.pixel.y() + scale * m.sigma_px * gauss(rng);
  }
  for (auto& d : network.distances) {
    const double length = (xyz_of(*points.at(d.point_a)) - xyz_of(*points.at(d.point_b))).norm();
    d.distance = length + scale * d.sigma * gauss(rng);
  }
  for (auto& model : network.models) {
    auto values = sensor::interior_block(model.interior);
    for (int i = 0; i < sensor::InteriorBlock::kSize; ++i) {
      const auto& prior = model.priors[static_cast<size_t>(i)];
      if (prior.mode == scene::ParameterMode::kObserved) {
        values[static_cast<size_t>(i)] += scale * prior.sigma * gauss(rng);
      }
    }
    model.interior = sensor::interior_from_block(values.data());
  }
}

}  // namespace

scene::Network with_adjusted_values(scene::Network network,
                                    const BundleAdjustmentResult& adjusted) {
  for (auto& model : network.models) {
    for (const auto& r : adjusted.models) {
      if (r.name == model.name) model.interior = r.interior;
    }
  }
  for (auto& station : network.stations) {
    for (const auto& r : adjusted.stations) {
      if (r.name != station.name) continue;
      station.exterior = r.exterior;
      station.has_approximation = true;
    }
  }
  for (auto& point : network.points) {
    for (const auto& r : adjusted.points) {
      if (r.name != point.name || !r.adjusted) continue;
      point.xyz = r.xyz;
      point.has_approximation = true;
    }
  }
  return network;
}

scene::Network accepted_part(scene::Network network, const BundleAdjustmentResult& adjusted) {
  std::vector<scene::ImageMeasurement> accepted;
  for (size_t m = 0; m < network.measurements.size() && m < adjusted.measurements.size(); ++m) {
    if (adjusted.measurements[m].status == MeasurementStatus::kAccepted) {
      accepted.push_back(network.measurements[m]);
    }
  }
  network.measurements = std::move(accepted);
  std::set<std::string> kept;
  for (const auto& r : adjusted.points) {
    if (r.adjusted) kept.insert(r.name);
  }
  return scene::restricted_to_points(std::move(network), kept);
}

BootstrapResult bootstrap_precision(const scene::Network& network,
                                    const BundleAdjustmentResult& adjusted,
                                    const BootstrapOptions& options) {
  if (!adjusted.converged || adjusted.models.empty()) {
    throw std::invalid_argument("bootstrap: the adjustment has no converged solution");
  }
  scene::Network base = accepted_part(with_adjusted_values(network, adjusted), adjusted);
  // Each sample is a plain least-squares solution from the adjusted values: no covariance, no
  // tests, no rejections.
  base.design.simulate = false;
  base.design.ignore_approximates = false;
  base.design.calculate_covariance = false;
  base.design.statistical_tests = false;
  base.residual_test.iterative_rejection = false;
  const double scale = adjusted.sigma0 > 0.0 ? adjusted.sigma0 : 1.0;

  const size_t models = adjusted.models.size();
  std::vector<std::vector<std::array<double, 10>>> values(models);
  std::mt19937 rng(options.seed);
  BootstrapResult out;
  // Ceres warns on stderr whenever a Levenberg-Marquardt step's dense Cholesky fails; started at
  // a solution, the samples' first steps do that now and then and the solver recovers by
  // damping more. Dozens of such lines would bury the progress: errors only, for the samples.
  struct ErrorsOnly {
    int level = FLAGS_minloglevel;
    ErrorsOnly() { FLAGS_minloglevel = google::GLOG_ERROR; }
    ~ErrorsOnly() { FLAGS_minloglevel = level; }
  };
  {
    const ErrorsOnly quiet;
    for (int s = 0; s < options.samples; ++s) {
      scene::Network sample = base;
      simulate_observations(sample, scale, rng);
      const BundleAdjustmentResult r = adjust(sample, options.bundle);
      if (!r.converged || r.models.size() != models) {
        ++out.failed;
        continue;
      }
      ++out.samples;
      for (size_t c = 0; c < models; ++c)
        values[c].push_back(sensor::interior_block(r.models[c].interior));
    }
  }
  out.interior_sigma.assign(models, {});
  out.interior_covariance.assign(models, Eigen::Matrix<double, 10, 10>::Zero());
  if (out.samples < 2) return out;
  for (size_t c = 0; c < models; ++c) {
    Eigen::Matrix<double, 10, 1> mean = Eigen::Matrix<double, 10, 1>::Zero();
    for (const auto& v : values[c])
      mean += Eigen::Map<const Eigen::Matrix<double, 10, 1>>(v.data());
    mean /= out.samples;
    Eigen::Matrix<double, 10, 10> covariance = Eigen::Matrix<double, 10, 10>::Zero();
    for (const auto& v : values[c]) {
      const Eigen::Matrix<double, 10, 1> d =
          Eigen::Map<const Eigen::Matrix<double, 10, 1>>(v.data()) - mean;
      covariance += d * d.transpose();
    }
    covariance /= out.samples - 1;
    out.interior_covariance[c] = covariance;
    for (int i = 0; i < 10; ++i)
      out.interior_sigma[c][static_cast<size_t>(i)] = std::sqrt(covariance(i, i));
  }
  return out;
}

}  // namespace syncap::estimators
