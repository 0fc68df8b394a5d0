#include "estimators/adjustment_network.hpp"

#include <cmath>
#include <map>

#include "estimators/bundle_adjustment.hpp"
#include "sensor/camera_parameters.hpp"

namespace syncap::estimators {
namespace {

using scene::ParameterMode;

const char* const kPointNames[3] = {"X", "Y", "Z"};

template <typename Item>
std::map<std::string, int> index_by_name(const std::vector<Item>& items, const char* what) {
  std::map<std::string, int> index;
  for (int i = 0; i < static_cast<int>(items.size()); ++i) {
    if (!index.emplace(items[i].name, i).second) {
      throw NetworkError(std::string("network: ") + what + " " + quoted(items[i].name) +
                         " is defined twice");
    }
  }
  return index;
}

void check_prior(const scene::ParameterPrior& prior, const std::string& owner, const char* name) {
  if (prior.mode == ParameterMode::kObserved && !(prior.sigma > 0.0)) {
    throw NetworkError("network: " + owner + ": parameter " + name +
                       " is observed but its sigma is not positive");
  }
}

using NameIndex = std::map<std::string, int>;

void check_model(const scene::CameraModel& model) {
  const std::string owner = "camera model " + quoted(model.name);
  if (!(model.interior.c > 0.0)) throw NetworkError("network: " + owner + ": c must be positive");
  if (model.sensor.width_px <= 0 || model.sensor.height_px <= 0 ||
      !(model.sensor.pixel_width_mm > 0.0) || !(model.sensor.pixel_height_mm > 0.0)) {
    throw NetworkError("network: " + owner + ": sensor size and pixel pitch must be positive");
  }
  for (int i = 0; i < sensor::InteriorBlock::kSize; ++i) {
    check_prior(model.priors[i], owner, sensor::InteriorBlock::kNames[i]);
  }
}

// The station's camera model.
int resolve_station(const scene::Station& station, const NameIndex& models) {
  const std::string owner = "station " + quoted(station.name);
  const auto model = models.find(station.model);
  if (model == models.end()) {
    throw NetworkError("network: " + owner + ": unknown camera model " + quoted(station.model));
  }
  if (!station.has_approximation) {
    throw NetworkError("network: " + owner +
                       ": no approximate exterior orientation (relative orientation or the "
                       "scene file must provide one)");
  }
  for (int i = 0; i < sensor::ExteriorBlock::kSize; ++i) {
    check_prior(station.priors[i], owner, sensor::ExteriorBlock::kNames[i]);
  }
  return model->second;
}

void check_point(const scene::ObjectPoint& point) {
  for (int i = 0; i < 3; ++i)
    check_prior(point.priors[i], "point " + quoted(point.name), kPointNames[i]);
}

// Measurement m's station and point.
std::pair<int, int> resolve_measurement(const scene::ImageMeasurement& meas, size_t m,
                                        const NameIndex& stations, const NameIndex& points) {
  const std::string place = "network: measurement " + std::to_string(m) + " (station " +
                            quoted(meas.station) + ", point " + quoted(meas.point) + ", frame " +
                            std::to_string(meas.frame_number) + "): ";
  const auto station = stations.find(meas.station);
  if (station == stations.end()) throw NetworkError(place + "unknown station");
  const auto point = points.find(meas.point);
  if (point == points.end()) throw NetworkError(place + "unknown point");
  if (!(meas.sigma_px > 0.0)) throw NetworkError(place + "sigma_px must be positive");
  if (!std::isfinite(meas.u) || !std::isfinite(meas.v)) {
    throw NetworkError(place + "u and v must be finite");
  }
  return {station->second, point->second};
}

// Distance d's two points.
std::pair<int, int> resolve_distance(const scene::DistanceConstraint& dist, size_t d,
                                     const NameIndex& points) {
  const std::string place = "network: distance " + std::to_string(d) + " (" + quoted(dist.point_a) +
                            " - " + quoted(dist.point_b) + "): ";
  const auto a = points.find(dist.point_a);
  const auto b = points.find(dist.point_b);
  if (a == points.end() || b == points.end()) throw NetworkError(place + "unknown point");
  if (a->second == b->second) throw NetworkError(place + "both ends are the same point");
  if (!(dist.distance > 0.0)) throw NetworkError(place + "distance must be positive");
  if (!(dist.sigma >= 0.0)) throw NetworkError(place + "sigma must not be negative");
  return {a->second, b->second};
}

}  // namespace

ResolvedNetwork resolve(const scene::Network& network) {
  ResolvedNetwork r(network);
  const NameIndex models = index_by_name(network.models, "camera model");
  const NameIndex stations = index_by_name(network.stations, "station");
  const NameIndex points = index_by_name(network.points, "point");
  for (const auto& model : network.models) check_model(model);
  for (const auto& station : network.stations) {
    r.station_model.push_back(resolve_station(station, models));
  }
  for (const auto& point : network.points) check_point(point);
  for (size_t m = 0; m < network.measurements.size(); ++m) {
    const auto [station, point] = resolve_measurement(network.measurements[m], m, stations, points);
    r.measurement_station.push_back(station);
    r.measurement_point.push_back(point);
  }
  for (size_t d = 0; d < network.distances.size(); ++d) {
    r.distance_points.push_back(resolve_distance(network.distances[d], d, points));
  }
  return r;
}

bool point_held(const scene::ObjectPoint& point) {
  for (const auto& prior : point.priors) {
    if (prior.mode == ParameterMode::kFree) return false;
  }
  return true;
}

}  // namespace syncap::estimators
