#include "estimators/adjustment_parameters.hpp"

#include <Eigen/Dense>
#include <map>
#include <numeric>
#include <set>
#include <utility>

#include "geometry/triangulation.hpp"

namespace syncap::estimators {
namespace {

int find_root(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace

AdjustmentParameters::AdjustmentParameters(const scene::Network& network) {
  for (const auto& model : network.models)
    interior.push_back(sensor::interior_block(model.interior));
  for (const auto& station : network.stations) {
    exterior.push_back(sensor::exterior_block(station.exterior));
  }
  for (const auto& point : network.points) points.emplace_back(point.xyz.data());
}

double* AdjustmentParameters::block(BlockKind kind, int id) {
  return const_cast<double*>(std::as_const(*this).block(kind, id));
}

const double* AdjustmentParameters::block(BlockKind kind, int id) const {
  switch (kind) {
    case BlockKind::kInterior:
      return interior[id].data();
    case BlockKind::kExterior:
      return exterior[id].data();
    case BlockKind::kGroup:
      return group_values[id].data();
  }
  return nullptr;
}

sensor::CameraModel AdjustmentParameters::camera(const ResolvedNetwork& resolved,
                                                 int station) const {
  const int model = resolved.station_model[station];
  sensor::CameraModel c;
  c.sensor = resolved.network.models[model].sensor;
  c.interior = sensor::interior_from_block(interior[model].data());
  c.exterior = sensor::exterior_from_block(exterior[station].data());
  return c;
}

void AdjustmentParameters::triangulate_approximations(const ResolvedNetwork& resolved,
                                                      std::vector<MeasurementStatus>* status,
                                                      std::vector<std::string>* messages) {
  const scene::Network& network = resolved.network;
  std::vector<std::vector<size_t>> rays(points.size());
  for (size_t m = 0; m < status->size(); ++m) rays[resolved.measurement_point[m]].push_back(m);
  int triangulated = 0;
  for (size_t p = 0; p < points.size(); ++p) {
    if (network.points[p].has_approximation && !network.design.ignore_approximates) continue;
    if (point_held(network.points[p])) continue;  // a control point keeps its given value
    geometry::NearestPoint nearest;
    std::set<int> stations;
    for (size_t m : rays[p]) {
      const auto& meas = network.measurements[m];
      const int s = resolved.measurement_station[m];
      nearest.add(camera(resolved, s).back_project({meas.u, meas.v}));
      stations.insert(s);
    }
    const Eigen::JacobiSVD<Eigen::Matrix3d> svd(nearest.normal);
    if (stations.size() < 2 || svd.singularValues()[2] < 1e-9 * svd.singularValues()[0]) {
      messages->push_back("point " + quoted(network.points[p].name) +
                          ": no approximation and fewer than two distinct rays; not "
                          "adjusted");
      for (size_t m : rays[p]) (*status)[m] = MeasurementStatus::kUndetermined;
      continue;
    }
    points[p] = nearest.solve();
    ++triangulated;
  }
  if (triangulated > 0) {
    messages->push_back("triangulated " + std::to_string(triangulated) +
                        " point approximations from the stations");
  }
}

// Points with fewer than two rays from distinct stations (and not held by their priors) are not
// adjusted; points linked by distances share a parameter block.
void AdjustmentParameters::update_groups(const ResolvedNetwork& resolved,
                                         std::vector<MeasurementStatus>* status) {
  const scene::Network& network = resolved.network;
  const int n = static_cast<int>(points.size());
  std::vector<std::set<int>> stations(n);
  for (size_t m = 0; m < status->size(); ++m) {
    if ((*status)[m] == MeasurementStatus::kAccepted) {
      stations[resolved.measurement_point[m]].insert(resolved.measurement_station[m]);
    }
  }
  std::vector<bool> active(n);
  for (int p = 0; p < n; ++p) {
    active[p] = stations[p].size() >= 2 || (point_held(network.points[p]) && !stations[p].empty());
  }
  for (size_t m = 0; m < status->size(); ++m) {
    if ((*status)[m] == MeasurementStatus::kAccepted && !active[resolved.measurement_point[m]]) {
      (*status)[m] = MeasurementStatus::kUndetermined;
    }
  }
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  active_distances.clear();
  for (size_t d = 0; d < resolved.distance_points.size(); ++d) {
    const auto [a, b] = resolved.distance_points[d];
    if (!active[a] || !active[b]) continue;
    active_distances.push_back(static_cast<int>(d));
    parent[find_root(parent, a)] = find_root(parent, b);
  }
  slot.assign(n, PointSlot{});
  group_points.clear();
  std::map<int, int> group_of_root;
  for (int p = 0; p < n; ++p) {
    if (!active[p]) continue;
    const auto [it, inserted] =
        group_of_root.emplace(find_root(parent, p), static_cast<int>(group_points.size()));
    if (inserted) group_points.emplace_back();
    slot[p] = {it->second, 3 * static_cast<int>(group_points[it->second].size())};
    group_points[it->second].push_back(p);
  }
  group_values.assign(group_points.size(), {});
  for (size_t g = 0; g < group_points.size(); ++g) {
    for (int p : group_points[g]) {
      group_values[g].insert(group_values[g].end(), points[p].data(), points[p].data() + 3);
    }
  }
}

void AdjustmentParameters::read_points_from_groups() {
  for (size_t g = 0; g < group_points.size(); ++g) {
    for (int p : group_points[g])
      points[p] = Eigen::Map<Eigen::Vector3d>(&group_values[g][slot[p].offset]);
  }
}

}  // namespace syncap::estimators
