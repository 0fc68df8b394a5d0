#include "calibration/network_start.hpp"

#include "geometry/resection.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "geometry/triangulation.hpp"
#include "sensor/camera_model.hpp"
#include "sensor/rotation.hpp"

namespace syncap::calibration {
namespace {

using estimators::RelativeOrientation;

// One measurement as the start uses it: the image direction (x'/c, y'/c, -1) in the station's
// sensor frame, undistorted with the model's approximate interior orientation.
struct Observation {
  int station = 0;
  Eigen::Vector3d direction;
};

// All observations of one object point.
struct Track {
  std::string name;
  std::vector<Observation> observations;
  bool triangulated = false;
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero();

  const Observation* in(int station) const {
    for (const Observation& o : observations) {
      if (o.station == station) return &o;
    }
    return nullptr;
  }
};

struct Pose {
  bool oriented = false;
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // sensor axes in the start frame
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
};

// "camera 3 (station "cam03")", or "station "x"" when the station is not a live camera.
std::string station_label(const scene::Station& station) {
  std::ostringstream label;
  if (station.camera_id >= 0) label << "camera " << station.camera_id << " (";
  label << "station \"" << station.name << "\"";
  if (station.camera_id >= 0) label << ")";
  return label.str();
}

[[noreturn]] void fail(const std::string& message) {
  throw NetworkStartError("network start: " + message);
}

struct StartState {
  const scene::Network& network;
  const NetworkStartOptions& options;
  std::vector<double> pixels_per_unit;  // per station: c / mu
  std::vector<Track> tracks;
  std::vector<Pose> poses;
  NetworkStartReport report;

  int station_count() const { return static_cast<int>(network.stations.size()); }
  int oriented_count() const {
    return static_cast<int>(
        std::count_if(poses.begin(), poses.end(), [](const Pose& p) { return p.oriented; }));
  }
};

// Reads the measurements into tracks, checking that every station and model exists.
void read_measurements(StartState& s) {
  const scene::Network& network = s.network;
  std::map<std::string, int> station_index;
  for (int i = 0; i < s.station_count(); ++i) station_index[network.stations[i].name] = i;
  std::map<std::string, const scene::CameraModel*> model_of;
  for (const scene::CameraModel& model : network.models) model_of[model.name] = &model;

  std::vector<const scene::CameraModel*> station_model(network.stations.size());
  for (int i = 0; i < s.station_count(); ++i) {
    const scene::Station& station = network.stations[i];
    const auto model = model_of.find(station.model);
    if (model == model_of.end()) {
      fail(station_label(station) + " uses unknown camera model \"" + station.model + "\"");
    }
    const sensor::SensorGeometry& sensor = model->second->sensor;
    if (!(model->second->interior.c > 0.0) || !(sensor.pixel_width_mm > 0.0) ||
        !(sensor.pixel_height_mm > 0.0)) {
      fail("camera model \"" + station.model + "\" needs c > 0 and a positive pixel size");
    }
    station_model[i] = model->second;
    s.pixels_per_unit.push_back(model->second->interior.c /
                                (0.5 * (sensor.pixel_width_mm + sensor.pixel_height_mm)));
  }

  std::map<std::string, int> track_index;
  for (size_t m = 0; m < network.measurements.size(); ++m) {
    const scene::ImageMeasurement& measurement = network.measurements[m];
    const auto station = station_index.find(measurement.station);
    if (station == station_index.end()) {
      std::ostringstream message;
      message << "measurement " << m << " (point \"" << measurement.point
              << "\") names unknown station \"" << measurement.station << "\"";
      fail(message.str());
    }
    const auto [entry, added] =
        track_index.emplace(measurement.point, static_cast<int>(s.tracks.size()));
    if (added) s.tracks.push_back({measurement.point, {}, false, Eigen::Vector3d::Zero()});
    Track& track = s.tracks[entry->second];
    if (track.in(station->second) != nullptr) continue;  // a repeated measurement: the first
    const scene::CameraModel& model = *station_model[station->second];
    track.observations.push_back(
        {station->second, estimators::image_direction(model.sensor, model.interior,
                                                      {measurement.u, measurement.v})});
  }
}

// The pair graph: shared[a][b] = points both stations saw.
std::vector<std::vector<int>> shared_points(const StartState& s) {
  std::vector<std::vector<int>> shared(s.station_count(), std::vector<int>(s.station_count(), 0));
  for (const Track& track : s.tracks) {
    for (const Observation& a : track.observations) {
      for (const Observation& b : track.observations) {
        if (a.station != b.station) ++shared[a.station][b.station];
      }
    }
  }
  return shared;
}

// Every station must share enough observations (of points some other station saw too).
void check_connectivity(const StartState& s) {
  std::vector<int> shared_observations(s.station_count(), 0);
  for (const Track& track : s.tracks) {
    if (track.observations.size() < 2) continue;
    for (const Observation& o : track.observations) ++shared_observations[o.station];
  }
  std::string problems;
  for (int i = 0; i < s.station_count(); ++i) {
    if (shared_observations[i] >= s.options.min_shared_observations) continue;
    std::ostringstream message;
    message << (problems.empty() ? "" : "; ") << station_label(s.network.stations[i])
            << " shares only " << shared_observations[i]
            << " observations with the others; need >= " << s.options.min_shared_observations;
    problems += message.str();
  }
  if (!problems.empty()) fail(problems);
}

// Prim's maximum spanning tree on the shared counts from the best-connected station; edges
// weaker than min_shared_observations are not used. Returns the (parent, child) pairs in the
// order they were added; stations it cannot reach are left out.
std::vector<std::pair<int, int>> spanning_tree(const std::vector<std::vector<int>>& shared,
                                               int root, int min_shared) {
  const int n = static_cast<int>(shared.size());
  std::vector<bool> in_tree(n, false);
  in_tree[root] = true;
  std::vector<std::pair<int, int>> edges;
  for (;;) {
    int best = min_shared - 1, parent = -1, child = -1;
    for (int a = 0; a < n; ++a) {
      for (int b = 0; b < n; ++b) {
        if (in_tree[a] && !in_tree[b] && shared[a][b] > best) {
          best = shared[a][b];
          parent = a;
          child = b;
        }
      }
    }
    if (child < 0) return edges;
    in_tree[child] = true;
    edges.emplace_back(parent, child);
  }
}

// The point nearest to the rays of the oriented stations (least squares); rays farther than
// max_ray_error_px from it are left out one by one, the worst first.
void triangulate(StartState& s, Track& track) {
  std::vector<geometry::ViewRay> rays;
  for (const Observation& o : track.observations) {
    const Pose& pose = s.poses[o.station];
    if (!pose.oriented) continue;
    rays.push_back(
        {{pose.centre, (pose.rotation * o.direction).normalized()}, s.pixels_per_unit[o.station]});
  }
  // Equal weights: the start's frame has no scale yet (and its adjustment was tuned on them).
  const geometry::RayPoint point = geometry::triangulate_dropping_outliers(
      rays, 1.0, s.options.max_ray_error_px, nullptr, /*weigh_by_distance=*/false);
  track.triangulated = point.ok;
  if (point.ok) track.xyz = point.position;
}

void triangulate_all(StartState& s) {
  for (Track& track : s.tracks) triangulate(s, track);
}

double median(std::vector<double> values) {
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

// Orients `child` from its oriented `parent` by the relative orientation of the pair: the
// rotation directly, the base length from the points both see that are already triangulated
// (or default_base_mm for the very first base).
bool orient_by_relative_orientation(StartState& s, NetworkStartEdge& edge, int parent, int child) {
  std::vector<Eigen::Vector3d> first, second;
  std::vector<const Track*> tracks;
  for (const Track& track : s.tracks) {
    const Observation* a = track.in(parent);
    const Observation* b = track.in(child);
    if (a == nullptr || b == nullptr) continue;
    first.push_back(a->direction);
    second.push_back(b->direction);
    tracks.push_back(&track);
  }
  edge.relative = estimators::estimate_relative_orientation_from_directions(
      first, second, s.pixels_per_unit[parent], s.pixels_per_unit[child], s.options.relative);
  if (!edge.relative.ok()) return false;
  const RelativeOrientation& ro = edge.relative;
  const Pose& p = s.poses[parent];

  double base_length = s.options.default_base_mm;
  if (s.oriented_count() > 1) {
    std::vector<double> ratios;
    for (size_t i = 0; i < tracks.size(); ++i) {
      if (!ro.inliers[i] || !tracks[i]->triangulated) continue;
      const Eigen::Vector2d lambda =
          estimators::ray_parameters(first[i], second[i], ro.rotation, ro.base);
      const double relative_distance = lambda(0) * first[i].norm();
      if (!(lambda(0) > 0.0) || !(lambda(1) > 0.0)) continue;
      ratios.push_back((tracks[i]->xyz - p.centre).norm() / relative_distance);
    }
    if (ratios.size() < 3) return false;  // no scale: let resection place it
    base_length = median(ratios);
  }
  Pose& c = s.poses[child];
  c.rotation = p.rotation * ro.rotation;
  c.centre = p.centre + base_length * (p.rotation * ro.base);
  c.oriented = true;
  return true;
}

// Spatial resection on the triangulated points the station sees (geometry::resect: EPnP in
// RANSAC).
bool orient_by_resection(StartState& s, int station, int* usable) {
  std::vector<Eigen::Vector3d> object;
  std::vector<Eigen::Vector2d> directions;
  for (const Track& track : s.tracks) {
    const Observation* o = track.in(station);
    if (o == nullptr || !track.triangulated) continue;
    object.push_back(track.xyz);
    directions.emplace_back(o->direction.x(), o->direction.y());
  }
  *usable = static_cast<int>(object.size());
  geometry::ResectionOptions options;
  options.min_points = std::max(6, s.options.min_shared_observations);
  options.inlier_threshold = s.options.relative.ransac_threshold_px / s.pixels_per_unit[station];
  const auto resection = geometry::resect(object, directions, options);
  if (!resection) return false;
  Pose& pose = s.poses[station];
  pose.rotation = resection->rotation;
  pose.centre = resection->centre;
  pose.oriented = true;
  s.report.resected.push_back(s.network.stations[station].name);
  return true;
}

// The scale from the distance constraints: median of true / measured length.
void apply_scale(StartState& s) {
  std::map<std::string, const Track*> by_name;
  for (const Track& track : s.tracks) by_name[track.name] = &track;
  std::vector<double> ratios;
  for (const scene::DistanceConstraint& d : s.network.distances) {
    const auto a = by_name.find(d.point_a), b = by_name.find(d.point_b);
    if (a == by_name.end() || b == by_name.end() || !a->second->triangulated ||
        !b->second->triangulated || !(d.distance > 0.0)) {
      continue;
    }
    const double measured = (a->second->xyz - b->second->xyz).norm();
    if (measured > 0.0) ratios.push_back(d.distance / measured);
  }
  s.report.distances_used = static_cast<int>(ratios.size());
  if (ratios.empty()) return;
  const double scale = median(ratios);
  s.report.scale = scale;
  s.report.scale_from_distances = true;
  for (Pose& pose : s.poses) pose.centre *= scale;  // the root sits at the origin
  for (Track& track : s.tracks) track.xyz *= scale;
}

scene::Network filled_network(const StartState& s) {
  scene::Network network = s.network;
  for (int i = 0; i < s.station_count(); ++i) {
    const Pose& pose = s.poses[i];
    const sensor::RotationAngles angles = sensor::angles_from_rotation(pose.rotation);
    network.stations[i].exterior = {pose.centre.x(), pose.centre.y(), pose.centre.z(),
                                    angles.omega,    angles.phi,      angles.kappa};
    network.stations[i].has_approximation = true;
  }
  std::map<std::string, size_t> point_index;
  for (size_t i = 0; i < network.points.size(); ++i) point_index[network.points[i].name] = i;
  for (const Track& track : s.tracks) {
    if (!track.triangulated) continue;
    const std::array<double, 3> xyz{track.xyz.x(), track.xyz.y(), track.xyz.z()};
    const auto existing = point_index.find(track.name);
    if (existing == point_index.end()) {
      scene::ObjectPoint point;
      point.name = track.name;
      point.xyz = xyz;
      point.has_approximation = true;
      network.points.push_back(point);
      continue;
    }
    scene::ObjectPoint& point = network.points[existing->second];
    const bool control = std::any_of(point.priors.begin(), point.priors.end(), [](const auto& p) {
      return p.mode != scene::ParameterMode::kFree;
    });
    if (control && point.has_approximation) continue;  // known coordinates stay
    point.xyz = xyz;
    point.has_approximation = true;
  }
  return network;
}

}  // namespace

NetworkStart start_network(const scene::Network& network, const NetworkStartOptions& options) {
  StartState s{network, options, {}, {}, {}, {}};
  if (network.stations.size() < 2) fail("the network needs at least two stations");
  read_measurements(s);
  check_connectivity(s);
  const std::vector<std::vector<int>> shared = shared_points(s);

  int root = 0, root_weight = -1;
  for (int i = 0; i < s.station_count(); ++i) {
    int weight = 0;
    for (int j = 0; j < s.station_count(); ++j) weight += shared[i][j];
    if (weight > root_weight) {
      root = i;
      root_weight = weight;
    }
  }
  s.poses.assign(network.stations.size(), Pose{});
  s.poses[root].oriented = true;
  s.report.root = network.stations[root].name;

  std::vector<std::string> why(network.stations.size());
  for (const auto& [parent, child] : spanning_tree(shared, root, options.min_shared_observations)) {
    NetworkStartEdge edge{network.stations[parent].name,
                          network.stations[child].name,
                          shared[parent][child],
                          false,
                          {}};
    if (s.poses[parent].oriented) {
      edge.oriented = orient_by_relative_orientation(s, edge, parent, child);
      if (edge.oriented) triangulate_all(s);
      why[child] = edge.relative.ok() ? "the base to station \"" + edge.parent + "\" has no scale"
                                      : edge.relative.message;
    }
    s.report.edges.push_back(std::move(edge));
  }

  // Resection for whatever the tree did not place, until nothing more can be placed.
  std::vector<int> usable(network.stations.size(), 0);
  for (bool progress = true; progress;) {
    progress = false;
    for (int i = 0; i < s.station_count(); ++i) {
      if (!s.poses[i].oriented && orient_by_resection(s, i, &usable[i])) {
        triangulate_all(s);
        progress = true;
      }
    }
  }
  std::string problems;
  for (int i = 0; i < s.station_count(); ++i) {
    if (s.poses[i].oriented) continue;
    std::ostringstream message;
    message << (problems.empty() ? "" : "; ") << station_label(network.stations[i])
            << " could not be oriented";
    if (!why[i].empty()) message << " (" << why[i] << ")";
    message << ": it sees only " << usable[i]
            << " triangulated points; need >= " << std::max(6, options.min_shared_observations);
    problems += message.str();
  }
  if (!problems.empty()) fail(problems);

  apply_scale(s);
  for (const Track& track : s.tracks) {
    (track.triangulated ? s.report.triangulated_points : s.report.untriangulated_points)++;
  }
  return {filled_network(s), s.report};
}

}  // namespace syncap::calibration
