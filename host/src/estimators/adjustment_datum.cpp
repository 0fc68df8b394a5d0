#include "estimators/adjustment_datum.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "sensor/rotation.hpp"

namespace syncap::estimators {
namespace {

using scene::ParameterMode;

// Whether fixed or observed exterior or point values define the datum. Without UNIFIED LEAST
// SQUARES observed values are plain unknowns (thesis: "the parameters are treated as being
// entirely unknown") and define nothing.
bool given_datum(const scene::Network& network) {
  const bool unified = network.design.unified_least_squares;
  auto defines = [&](const scene::ParameterPrior& prior) {
    return prior.mode == ParameterMode::kFixed ||
           (prior.mode == ParameterMode::kObserved && unified);
  };
  bool given = false;
  for (const auto& station : network.stations) {
    for (const auto& prior : station.priors) given |= defines(prior);
  }
  for (const auto& point : network.points) {
    for (const auto& prior : point.priors) given |= defines(prior);
  }
  return given;
}

// The station with the most measurements: it holds position and attitude.
int busiest_station(const ResolvedNetwork& resolved, int stations) {
  std::vector<long> count(stations, 0);
  for (int s : resolved.measurement_station) ++count[s];
  return static_cast<int>(std::max_element(count.begin(), count.end()) - count.begin());
}

// Without distances the scale: the largest coordinate difference of another station's centre
// to the first one's is held. Returns what it held for the message, or nothing.
std::string hold_scale(const scene::Network& network, const AdjustmentParameters& parameters,
                       int first, DatumChoice* choice) {
  int best_station = -1, best_axis = 0;
  double best = 0.0;
  for (int s = 0; s < static_cast<int>(parameters.exterior.size()); ++s) {
    for (int k = 0; k < 3; ++k) {
      const double d = std::abs(parameters.exterior[s][k] - parameters.exterior[first][k]);
      if (s != first && d > best) best = d, best_station = s, best_axis = k;
    }
  }
  if (best_station < 0) return "";
  choice->held[best_station][best_axis] = true;
  return ", station " + quoted(network.stations[best_station].name) + " " +
         sensor::ExteriorBlock::kNames[best_axis];
}

// The change of a position under translation k (columns 0-2), rotation about axis k (3-5) and
// scale (6), all about the centroid of the adjusted points.
class SimilarityMotion {
 public:
  explicit SimilarityMotion(const AdjustmentParameters& parameters) {
    int count = 0;
    for (const auto& points : parameters.group_points) {
      for (int p : points) centroid_ += parameters.points[p], ++count;
    }
    if (count > 0) centroid_ /= count;
  }

  Eigen::Vector3d operator()(const Eigen::Vector3d& x, int column) const {
    if (column < 3) return Eigen::Vector3d::Unit(column);
    if (column < 6) return Eigen::Vector3d::Unit(column - 3).cross(x - centroid_);
    return x - centroid_;
  }

 private:
  Eigen::Vector3d centroid_ = Eigen::Vector3d::Zero();
};

// The change of a station's angles under the rotation about axis k, by central differences (the
// angles are smooth away from phi = +-pi/2).
Eigen::Vector3d angle_motion(const std::array<double, kExteriorSize>& exterior, int axis_index) {
  const Eigen::Matrix3d r = sensor::rotation_matrix(exterior[3], exterior[4], exterior[5]);
  const double step = 1e-6;
  const Eigen::Vector3d axis = Eigen::Vector3d::Unit(axis_index);
  const auto plus = sensor::angles_from_rotation(Eigen::AngleAxisd(step, axis) * r);
  const auto minus = sensor::angles_from_rotation(Eigen::AngleAxisd(-step, axis) * r);
  auto wrapped = [](double a) { return std::remainder(a, 2.0 * M_PI); };
  return Eigen::Vector3d(wrapped(plus.omega - minus.omega) / (2 * step),
                         wrapped(plus.phi - minus.phi) / (2 * step),
                         wrapped(plus.kappa - minus.kappa) / (2 * step));
}

}  // namespace

DatumDefect datum_defect(const scene::Network& network, const AdjustmentParameters& parameters) {
  DatumDefect defect;
  const bool scale = network.distances.empty();
  defect.size = scale ? 7 : 6;
  const SimilarityMotion motion(parameters);
  defect.camera = Eigen::MatrixXd::Zero(parameters.camera_size(), defect.size);
  for (int s = 0; s < static_cast<int>(parameters.exterior.size()); ++s) {
    const auto& exterior = parameters.exterior[s];
    const Eigen::Vector3d centre(exterior[0], exterior[1], exterior[2]);
    for (int column = 0; column < defect.size; ++column) {
      defect.camera.block(parameters.exterior_column(s, 0), column, 3, 1) = motion(centre, column);
      if (column < 3 || column > 5) continue;
      defect.camera.block(parameters.exterior_column(s, 3), column, 3, 1) =
          angle_motion(exterior, column - 3);
    }
  }
  for (const auto& points : parameters.group_points) {
    Eigen::MatrixXd rows(3 * points.size(), defect.size);
    for (size_t i = 0; i < points.size(); ++i) {
      for (int column = 0; column < defect.size; ++column) {
        rows.block(3 * i, column, 3, 1) = motion(parameters.points[points[i]], column);
      }
    }
    defect.groups.push_back(rows);
  }
  return defect;
}

DatumChoice choose_datum(const ResolvedNetwork& resolved, const AdjustmentParameters& parameters,
                         std::vector<std::string>* messages) {
  const scene::Network& network = resolved.network;
  DatumChoice choice;
  choice.held.assign(parameters.exterior.size(), {false, false, false, false, false, false});
  if (given_datum(network) || parameters.exterior.empty()) {
    choice.datum = Datum::kGivenParameters;
    messages->push_back("datum: from the fixed and observed exterior/point parameters");
    return choice;
  }
  choice.datum = Datum::kInnerConstraints;
  const int first = busiest_station(resolved, static_cast<int>(parameters.exterior.size()));
  choice.held[first].fill(true);
  std::string held = "station " + quoted(network.stations[first].name) + " exterior";
  if (network.distances.empty() && parameters.exterior.size() > 1) {
    held += hold_scale(network, parameters, first, &choice);
  }
  messages->push_back("datum: free network; solved with " + held +
                      " held, covariance S-transformed to inner constraints on the object points");
  return choice;
}

// Q' = S Q S^T with S = I - G (G_p^T G_p)^-1 G_p^T: G spans the datum defect, G_p is its object
// point rows. Q' is the cofactor matrix of the solution whose object points do not move on
// average under any similarity (inner constraints G_p^T dx = 0); the image residuals, sigma0 and
// the interior orientation's cofactors do not depend on the datum.
void s_transform(const scene::Network& network, const AdjustmentParameters& parameters,
                 ArrowCofactors* q) {
  const DatumDefect g = datum_defect(network, parameters);
  Eigen::MatrixXd gp_gp = Eigen::MatrixXd::Zero(g.size, g.size);
  for (const auto& rows : g.groups) gp_gp += rows.transpose() * rows;
  const Eigen::MatrixXd m = gp_gp.inverse();
  Eigen::MatrixXd y_camera;
  std::vector<Eigen::MatrixXd> y_groups;
  q->solve(Eigen::MatrixXd::Zero(parameters.camera_size(), g.size), g.groups, &y_camera, &y_groups);
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(g.size, g.size);
  for (size_t i = 0; i < g.groups.size(); ++i) c += g.groups[i].transpose() * y_groups[i];
  auto transform = [&](Eigen::MatrixXd* block, const Eigen::MatrixXd& rows,
                       const Eigen::MatrixXd& y) {
    const Eigen::MatrixXd gm = rows * m;
    *block += -gm * y.transpose() - y * gm.transpose() + gm * c * gm.transpose();
  };
  transform(&q->camera_camera, g.camera, y_camera);
  for (size_t i = 0; i < g.groups.size(); ++i)
    transform(&q->group_group[i], g.groups[i], y_groups[i]);
}

}  // namespace syncap::estimators
