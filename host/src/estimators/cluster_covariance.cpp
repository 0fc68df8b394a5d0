#include "estimators/cluster_covariance.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace syncap::estimators {
namespace {

// Per image term, its frame; a point group's index where the measurement has none.
std::vector<int64_t> term_frames(const ResolvedNetwork& resolved, const std::vector<Term>& terms,
                                 const std::vector<TermJacobian>& jacobians) {
  std::vector<int64_t> frame(terms.size(), -1);
  for (size_t t = 0; t < terms.size(); ++t) {
    if (terms[t].kind != Term::Kind::kImage) continue;
    const int64_t f = resolved.network.measurements[terms[t].measurement].frame_number;
    frame[t] = f >= 0 ? f : jacobians[t].group;
  }
  return frame;
}

// The scores' columns: per cluster, the reduced camera rows (s_c - W_g s_g) and, for the datum,
// G_g^T N_gg^-1 s_g; then a column per term of its own and per parameter observation row.
struct Scores {
  Eigen::MatrixXd camera;
  Eigen::MatrixXd datum;  // defect rows; empty without a defect
};

int own_columns(const std::vector<Term>& terms, const std::vector<TermJacobian>& jacobians,
                const Clustering& clustering) {
  int columns = 0;
  for (size_t t = 0; t < terms.size(); ++t) {
    if (jacobians[t].group < 0)
      columns += static_cast<int>(jacobians[t].jacobian.rows());
    else if (clustering.cluster[t] < 0)
      ++columns;
  }
  return columns;
}

Scores scores(const AdjustmentParameters& parameters, const std::vector<TermJacobian>& jacobians,
              const ArrowCofactors& cofactors, const Clustering& clustering,
              const DatumDefect* defect, int columns) {
  Scores out;
  out.camera = Eigen::MatrixXd::Zero(parameters.camera_size(), columns);
  if (defect) out.datum = Eigen::MatrixXd::Zero(defect->size, columns);
  const double small_sample = std::sqrt(clustering.clusters / (clustering.clusters - 1.0));
  int own = clustering.clusters;
  for (size_t t = 0; t < jacobians.size(); ++t) {
    const TermJacobian& tj = jacobians[t];
    const Eigen::Index nc = static_cast<Eigen::Index>(tj.camera_columns.size());
    if (tj.group < 0) {
      // A parameter observation: its a priori sigma holds, each row a column of its own.
      for (Eigen::Index r = 0; r < tj.jacobian.rows(); ++r, ++own) {
        for (Eigen::Index a = 0; a < nc; ++a)
          out.camera(tj.camera_columns[a], own) += tj.jacobian(r, a);
      }
      continue;
    }
    const bool clustered = clustering.cluster[t] >= 0;
    const int column = clustered ? clustering.cluster[t] : own++;
    const Eigen::VectorXd score =
        (clustered ? small_sample : 1.0) * (tj.jacobian.transpose() * tj.residual);
    const Eigen::VectorXd group_score = score.tail(score.size() - nc);
    for (Eigen::Index a = 0; a < nc; ++a) out.camera(tj.camera_columns[a], column) += score[a];
    out.camera.col(column).noalias() -= cofactors.camera_weights[tj.group] * group_score;
    if (defect) {
      out.datum.col(column).noalias() +=
          defect->groups[tj.group].transpose() * (cofactors.group_inverse[tj.group] * group_score);
    }
  }
  return out;
}

}  // namespace

Clustering by_stretch(const ResolvedNetwork& resolved, const std::vector<Term>& terms,
                      const std::vector<TermJacobian>& jacobians, int stretches) {
  const std::vector<int64_t> frames = term_frames(resolved, terms, jacobians);
  std::map<int64_t, int> rank;
  for (int64_t f : frames) {
    if (f >= 0) rank[f] = 0;
  }
  const int distinct = static_cast<int>(rank.size());
  Clustering out;
  out.clusters = std::min(stretches, distinct / 2);
  int i = 0;
  for (auto& [frame, r] : rank) r = i++;
  for (int64_t f : frames) {
    out.cluster.push_back(
        f < 0 ? -1 : static_cast<int>(static_cast<int64_t>(rank[f]) * out.clusters / distinct));
  }
  return out;
}

Clustering by_cell(const ResolvedNetwork& resolved, const std::vector<Term>& terms, int cells) {
  std::map<std::pair<int, int>, int> index;  // (station, cell) -> cluster
  Clustering out;
  for (const Term& term : terms) {
    if (term.kind != Term::Kind::kImage || cells < 1) {
      out.cluster.push_back(-1);
      continue;
    }
    const scene::ImageMeasurement& m = resolved.network.measurements[term.measurement];
    const int station = resolved.measurement_station[term.measurement];
    const sensor::SensorGeometry& sensor =
        resolved.network.models[resolved.station_model[station]].sensor;
    const int rows =
        std::max(1, static_cast<int>(std::lround(cells * static_cast<double>(sensor.height_px) /
                                                 std::max(1, sensor.width_px))));
    const int cx =
        std::clamp(static_cast<int>(m.u * cells / std::max(1, sensor.width_px)), 0, cells - 1);
    const int cy =
        std::clamp(static_cast<int>(m.v * rows / std::max(1, sensor.height_px)), 0, rows - 1);
    const auto [it, added] =
        index.try_emplace({station, cy * cells + cx}, static_cast<int>(index.size()));
    out.cluster.push_back(it->second);
  }
  out.clusters = static_cast<int>(index.size());
  return out;
}

Eigen::MatrixXd cluster_covariance(const AdjustmentParameters& parameters,
                                   const std::vector<Term>& terms,
                                   const std::vector<TermJacobian>& jacobians,
                                   const ArrowCofactors& cofactors, const Clustering& clustering,
                                   const DatumDefect* defect) {
  if (clustering.clusters < 2) return {};
  const int columns = clustering.clusters + own_columns(terms, jacobians, clustering);
  const Scores s = scores(parameters, jacobians, cofactors, clustering, defect, columns);
  Eigen::MatrixXd steps = cofactors.camera_camera * s.camera;
  if (defect) {
    // d' = S d = d - G (G_p^T G_p)^-1 G_p^T d_p, with G_p^T d_p = sum_g G_g^T N_gg^-1 s_g
    // - (sum_g W_g G_g)^T d_c (datum.hpp's S-transform, applied to the steps).
    Eigen::MatrixXd gp_gp = Eigen::MatrixXd::Zero(defect->size, defect->size);
    Eigen::MatrixXd wg = Eigen::MatrixXd::Zero(parameters.camera_size(), defect->size);
    for (size_t g = 0; g < defect->groups.size(); ++g) {
      gp_gp += defect->groups[g].transpose() * defect->groups[g];
      wg += cofactors.camera_weights[g] * defect->groups[g];
    }
    const Eigen::MatrixXd moved = s.datum - wg.transpose() * steps;
    steps -= defect->camera * gp_gp.ldlt().solve(moved);
  }
  return steps * steps.transpose();
}

Eigen::MatrixXd larger_covariance(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  if (a.size() == 0) return b;
  if (b.size() == 0) return a;
  const bool a_base = a.trace() >= b.trace();
  const Eigen::MatrixXd& base = a_base ? a : b;
  const Eigen::MatrixXd& other = a_base ? b : a;
  Eigen::VectorXd scale = Eigen::VectorXd::Ones(base.rows());
  for (Eigen::Index i = 0; i < base.rows(); ++i) {
    if (base(i, i) > 0.0 && other(i, i) > base(i, i))
      scale[i] = std::sqrt(other(i, i) / base(i, i));
  }
  Eigen::MatrixXd out = scale.asDiagonal() * base * scale.asDiagonal();
  for (Eigen::Index i = 0; i < base.rows(); ++i) {
    if (!(base(i, i) > 0.0)) out(i, i) = other(i, i);
  }
  return out;
}

}  // namespace syncap::estimators
