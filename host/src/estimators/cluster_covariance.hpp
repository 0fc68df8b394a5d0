// Internal to adjust() (bundle_adjustment.hpp): the camera parameters' covariance from the scatter
// of the data's scores over clusters of measurements whose errors may be alike, a cluster-robust
// ("sandwich") covariance:
//
//   C = N^-1 M N^-1,   M = K/(K-1) sum_k s_k s_k^T + sum_j a_j a_j^T
//
// with s_k = J_k^T v_k the score (whitened Jacobian times residuals) of the image measurements of
// cluster k of K (a distance is a cluster of its own), and a_j the whitened Jacobian rows of the
// parameter observations (their sigmas are given, not estimated). Where every measurement's error
// is independent with sigma0, E[M] = sigma0^2 N and C is the linearised sigma0^2 N^-1. Where the
// errors of a cluster are alike, its residuals push the cameras the same way and C grows with
// them, which the linearised covariance, the curvature at the minimum alone, cannot see. Two
// clusterings (Liang & Zeger 1986; the block bootstrap's analytic counterpart, one solve with K
// right-hand sides instead of K re-adjustments):
//
//   stretches  contiguous runs of the recording's frames: an error that follows the target along
//              its path (a drifting camera, an LED's centroid bias over a sweep);
//   cells      each camera's image cut into a grid: an error that belongs to a place in the image
//              (a centroid bias that varies over the image, a lens model that is not the lens),
//              the same in every frame, which no resampling of frames can see.
//
// The residuals at the solution already carry the points' elimination (J_p^T v = 0 in every
// point group), so no leverage correction is needed beyond K/(K-1).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "estimators/adjustment_covariance.hpp"
#include "estimators/adjustment_datum.hpp"
#include "estimators/adjustment_network.hpp"
#include "estimators/adjustment_parameters.hpp"
#include "estimators/adjustment_problem.hpp"
#include "estimators/covariance.hpp"

namespace syncap::estimators {

// Per term, its cluster (0 .. clusters-1), or -1: a cluster of its own.
struct Clustering {
  std::vector<int> cluster;
  int clusters = 0;
};

// Image measurements by their frames' rank cut into `stretches` runs of equal count (a point
// group's order where a measurement has no frame). Fewer clusters where frames are few: at least
// two frames a stretch.
Clustering by_stretch(const ResolvedNetwork& resolved, const std::vector<Term>& terms,
                      const std::vector<TermJacobian>& jacobians, int stretches);

// Image measurements by their station and the cell of a grid `cells` wide (rows in proportion
// to the sensor's height) they fall in.
Clustering by_cell(const ResolvedNetwork& resolved, const std::vector<Term>& terms, int cells);

// C of the camera parameters (the layout of ArrowCofactors::camera_camera), in the datum of
// `defect` when given (a free network's inner constraints) else in the cofactors' own. Empty
// with fewer than two clusters.
Eigen::MatrixXd cluster_covariance(const AdjustmentParameters& parameters,
                                   const std::vector<Term>& terms,
                                   const std::vector<TermJacobian>& jacobians,
                                   const ArrowCofactors& cofactors, const Clustering& clustering,
                                   const DatumDefect* defect);

// The covariance whose every variance is the larger of `a`'s and `b`'s: the correlations of the
// one with the larger trace, its rows and columns scaled up where the other's variance is larger
// (so the result stays positive semi-definite). Either may be empty.
Eigen::MatrixXd larger_covariance(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b);

}  // namespace syncap::estimators
