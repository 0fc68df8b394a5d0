// Internal to adjust() (bundle_adjustment.hpp): the values the bundle adjustment estimates, laid
// out as Ceres parameter blocks (cost_functors.hpp):
//
//   interior[10] per camera model, exterior[6] per station, and per point group the X, Y, Z of
//   its points one after another: points linked by distance constraints share a group, so that
//   Ceres' Schur complement still eliminates every point block.
//
// The camera parameters also have columns, the layout of the camera covariance: the models'
// interior values in order, then the stations' exterior values.
#pragma once

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "estimators/adjustment_network.hpp"
#include "estimators/bundle_adjustment.hpp"
#include "sensor/camera_model.hpp"
#include "sensor/camera_parameters.hpp"

namespace syncap::estimators {

constexpr int kInteriorSize = sensor::InteriorBlock::kSize;
constexpr int kExteriorSize = sensor::ExteriorBlock::kSize;

// Where an object point's values live: the parameter block of its group, at an offset.
struct PointSlot {
  int group = -1;  // -1: not adjusted (undetermined)
  int offset = 0;
};

enum class BlockKind { kInterior, kExterior, kGroup };

struct AdjustmentParameters {
  // The network's values: its approximations, or observed or fixed values.
  explicit AdjustmentParameters(const scene::Network& network);

  int camera_size() const {
    return static_cast<int>(interior.size()) * kInteriorSize +
           static_cast<int>(exterior.size()) * kExteriorSize;
  }
  int interior_column(int model, int i) const { return model * kInteriorSize + i; }
  int exterior_column(int station, int i) const {
    return static_cast<int>(interior.size()) * kInteriorSize + station * kExteriorSize + i;
  }
  double* block(BlockKind kind, int id);
  const double* block(BlockKind kind, int id) const;
  // The camera of a station with the current values.
  sensor::CameraModel camera(const ResolvedNetwork& resolved, int station) const;

  // Starting values of the points without approximation (all with IGNORE APPROXIMATES), from the
  // stations' approximate orientations; a point fewer than two distinct rays see is undetermined.
  void triangulate_approximations(const ResolvedNetwork& resolved,
                                  std::vector<MeasurementStatus>* status,
                                  std::vector<std::string>* messages);
  // The point groups of the next adjustment, from the accepted measurements; measurements of
  // points it cannot determine become undetermined.
  void update_groups(const ResolvedNetwork& resolved, std::vector<MeasurementStatus>* status);
  // The points' values from their groups' blocks, after a solve.
  void read_points_from_groups();

  std::vector<std::array<double, kInteriorSize>> interior;
  std::vector<std::array<double, kExteriorSize>> exterior;
  std::vector<Eigen::Vector3d> points;

  // The point groups of the current adjustment.
  std::vector<PointSlot> slot;  // per point
  std::vector<std::vector<int>> group_points;
  std::vector<std::vector<double>> group_values;
  std::vector<int> active_distances;  // indices of the distances between adjusted points
};

}  // namespace syncap::estimators
