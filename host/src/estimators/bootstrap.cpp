#include "estimators/bootstrap.hpp"

#include <glog/logging.h>

#include <Eigen/Geometry>

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

// The observations of `from` (measurements, distances, observed interior values) into `to`, the
// same network with other approximate values.
void take_observations(const scene::Network& from, scene::Network& to) {
  to.measurements = from.measurements;
  to.distances = from.distances;
  for (size_t m = 0; m < to.models.size(); ++m) {
    auto values = sensor::interior_block(to.models[m].interior);
    const auto observed = sensor::interior_block(from.models[m].interior);
    for (int i = 0; i < sensor::InteriorBlock::kSize; ++i) {
      if (to.models[m].priors[static_cast<size_t>(i)].mode == scene::ParameterMode::kObserved) {
        values[static_cast<size_t>(i)] = observed[static_cast<size_t>(i)];
      }
    }
    to.models[m].interior = sensor::interior_from_block(values.data());
  }
}

// Each sample is a plain least-squares solution: no covariance, no tests, no rejections.
void as_plain_solution(scene::Network& network) {
  network.design.simulate = false;
  network.design.calculate_covariance = false;
  network.design.statistical_tests = false;
  network.residual_test.iterative_rejection = false;
}

// The sample covariance of the vectors added.
template <int N>
struct Spread {
  using Vector = Eigen::Matrix<double, N, 1>;
  int count = 0;
  Vector sum = Vector::Zero();
  Eigen::Matrix<double, N, N> squares = Eigen::Matrix<double, N, N>::Zero();
  void add(const Vector& v) {
    ++count;
    sum += v;
    squares += v * v.transpose();
  }
  Eigen::Matrix<double, N, N> covariance() const {
    const Vector mean = sum / count;
    return (squares - count * mean * mean.transpose()) / (count - 1);
  }
};

// The sample's points moved by the rigid motion that fits them best onto the adjusted ones: the
// free network's datum differs from sample to sample, its shape is what the bootstrap measures.
std::map<std::string, Eigen::Vector3d> fitted_points(const BundleAdjustmentResult& sample,
                                                     const BundleAdjustmentResult& adjusted) {
  std::map<std::string, Eigen::Vector3d> reference;
  for (const auto& p : adjusted.points) {
    if (p.adjusted) reference[p.name] = Eigen::Vector3d(p.xyz.data());
  }
  std::vector<std::pair<std::string, Eigen::Vector3d>> common;
  for (const auto& p : sample.points) {
    if (p.adjusted && reference.count(p.name)) common.emplace_back(p.name, p.xyz.data());
  }
  std::map<std::string, Eigen::Vector3d> out;
  if (common.size() < 3) return out;
  Eigen::Matrix3Xd from(3, common.size()), to(3, common.size());
  for (size_t i = 0; i < common.size(); ++i) {
    from.col(static_cast<long>(i)) = common[i].second;
    to.col(static_cast<long>(i)) = reference.at(common[i].first);
  }
  const Eigen::Matrix4d motion = Eigen::umeyama(from, to, false);
  for (const auto& [name, xyz] : common) {
    out[name] = motion.topLeftCorner<3, 3>() * xyz + motion.topRightCorner<3, 1>();
  }
  return out;
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
  const scene::Network truth = accepted_part(with_adjusted_values(network, adjusted), adjusted);
  scene::Network start = options.from_approximate_values ? accepted_part(network, adjusted) : truth;
  start.design.ignore_approximates =
      options.from_approximate_values && network.design.ignore_approximates;
  as_plain_solution(start);
  const double scale = adjusted.sigma0 > 0.0 ? adjusted.sigma0 : 1.0;

  const size_t models = adjusted.models.size();
  std::vector<Spread<10>> interior(models);
  std::map<std::string, Spread<3>> points;
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
      scene::Network simulated = truth;
      simulate_observations(simulated, scale, rng);
      scene::Network sample = start;
      take_observations(simulated, sample);
      if (options.from_approximate_values && options.restart) {
        for (auto& station : sample.stations) station.has_approximation = false;
        for (auto& point : sample.points) point.has_approximation = false;
        try {
          sample = options.restart(std::move(sample));
          as_plain_solution(sample);
        } catch (const std::exception&) {
          ++out.failed;  // no start from these observations: the estimator would fail too
          continue;
        }
      }
      const BundleAdjustmentResult r = adjust(sample, options.bundle);
      if (!r.converged || r.models.size() != models) {
        ++out.failed;
        continue;
      }
      ++out.samples;
      for (size_t c = 0; c < models; ++c) {
        const auto values = sensor::interior_block(r.models[c].interior);
        interior[c].add(Eigen::Map<const Eigen::Matrix<double, 10, 1>>(values.data()));
      }
      for (const auto& [name, xyz] : fitted_points(r, adjusted)) points[name].add(xyz);
    }
  }
  out.interior_sigma.assign(models, {});
  out.interior_covariance.assign(models, Eigen::Matrix<double, 10, 10>::Zero());
  if (out.samples < 2) return out;
  for (size_t c = 0; c < models; ++c) {
    out.interior_covariance[c] = interior[c].covariance();
    for (int i = 0; i < 10; ++i) {
      out.interior_sigma[c][static_cast<size_t>(i)] = std::sqrt(out.interior_covariance[c](i, i));
    }
  }
  for (const auto& [name, spread] : points) {
    if (spread.count == out.samples) out.point_covariance[name] = spread.covariance();
  }
  return out;
}

}  // namespace syncap::estimators
