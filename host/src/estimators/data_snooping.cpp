#include "estimators/data_snooping.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>

#include "geometry/triangulation.hpp"
#include "sensor/camera_model.hpp"
#include "util/printf_string.hpp"

namespace syncap::estimators {
namespace {

// A residual whose redundancy share q_vv / q_ll is below this is not controlled by the network
// (its point has barely more rays than unknowns): it cannot be standardised, and is not snooped.
constexpr double kMinRedundancyShare = 1e-6;

// log(erfc(x)) for x >= 0, without underflow (asymptotic series beyond x = 25).
double log_erfc(double x) {
  if (x < 25.0) return std::log(std::erfc(x));
  const double x2 = x * x;
  return -x2 - std::log(x * std::sqrt(M_PI)) + std::log1p(-0.5 / x2 + 0.75 / (x2 * x2));
}

// The log probability, under H0, of a measurement's residual test statistic: T = v^T Q_vv^+ v /
// sigma0^2 over the directions the network controls (whitened residual v, its cofactor block
// q_vv), chi-square with as many degrees of freedom as those directions.
double log_p_of_point(const Eigen::Matrix2d& q_vv, const Eigen::Vector2d& v, double sigma0) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(q_vv);
  double t = 0.0;
  int dof = 0;
  for (int k = 0; k < 2; ++k) {
    const double share = eigen.eigenvalues()(k);
    if (!(share > kMinRedundancyShare)) continue;
    const double along = eigen.eigenvectors().col(k).dot(v) / sigma0;
    t += along * along / share;
    ++dof;
  }
  if (dof == 0) return 0.0;
  return dof == 2 ? -0.5 * t : log_erfc(std::sqrt(0.5 * t));  // chi2(2): p = exp(-t/2)
}

// The 1-D |w| of the same probability: log_erfc(w / sqrt 2) = log_p, by bisection.
double w_of_log_p(double log_p) {
  if (log_p >= 0.0) return 0.0;
  double low = 0.0, high = 1.0;
  while (log_erfc(high / std::sqrt(2.0)) > log_p) high *= 2.0;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (low + high);
    (log_erfc(mid / std::sqrt(2.0)) > log_p ? low : high) = mid;
  }
  return 0.5 * (low + high);
}

}  // namespace

void test_residuals(const scene::Network& network, const std::vector<Term>& terms,
                    const std::vector<TermJacobian>& jacobians, const ArrowCofactors& cofactors,
                    double sigma0, std::vector<MeasurementResult>* measurements,
                    std::vector<double>* log_p) {
  // q_vv = q_ll - a Q_xx a^T per image coordinate, from the cofactors of the values it touches;
  // whitened, q_ll = 1.
  log_p->assign(network.measurements.size(), 0.0);
  for (size_t t = 0; t < terms.size(); ++t) {
    if (terms[t].kind != Term::Kind::kImage) continue;
    const TermJacobian& tj = jacobians[t];
    const Eigen::Matrix2d h =
        tj.jacobian * touched_cofactors(tj, cofactors) * tj.jacobian.transpose();
    auto& out = (*measurements)[terms[t].measurement];
    const double sigma_px = network.measurements[terms[t].measurement].sigma_px;
    out.redundancy_u = 1.0 - h(0, 0);
    out.redundancy_v = 1.0 - h(1, 1);
    auto standardised = [&](double v_px, double share) {
      return share > kMinRedundancyShare ? v_px / sigma_px / (sigma0 * std::sqrt(share)) : 0.0;
    };
    out.w_u = standardised(out.residual_u, out.redundancy_u);
    out.w_v = standardised(out.residual_v, out.redundancy_v);
    const Eigen::Vector2d v(out.residual_u / sigma_px, out.residual_v / sigma_px);
    (*log_p)[terms[t].measurement] = log_p_of_point(Eigen::Matrix2d::Identity() - h, v, sigma0);
  }
}

std::vector<double> goodness_of_fit_sample(const BundleAdjustmentResult& result,
                                           const std::vector<MeasurementStatus>& status,
                                           bool snoop_with_a_posteriori_sigma0) {
  std::vector<double> w;
  for (size_t m = 0; m < status.size(); ++m) {
    if (status[m] != MeasurementStatus::kAccepted) continue;
    const auto& out = result.measurements[m];
    const double scale =
        snoop_with_a_posteriori_sigma0 || !(result.sigma0 > 0.0) ? 1.0 : result.sigma0;
    if (out.redundancy_u > kMinRedundancyShare) w.push_back(out.w_u / scale);
    if (out.redundancy_v > kMinRedundancyShare) w.push_back(out.w_v / scale);
  }
  return w;
}

// ", N of them with the M points whose wrong ray could not be told", or nothing.
std::string ambiguous_note(const std::vector<RejectedMeasurement>& rejected) {
  long rays = 0;
  for (const auto& r : rejected) rays += r.ambiguous;
  if (rays == 0) return "";
  return util::printf_string(", %ld of them with the %ld points whose wrong ray could not be told",
                             rays, rays / 2);
}

// Data snooping tests a measurement's two coordinates together: a blunder displaces an image
// point in some direction, and split over u and v it can hide behind a good ray of the same
// point whose single coordinate looks worse (a 4-ray point of the strawlab data did just that).
// The most improbable measurement goes first; its statistic is reported, and tested, as the 1-D
// |w| of equal probability, so the critical value keeps its meaning (eq 4.31).
bool DataSnooping::reject_worst_blunder(const std::vector<double>& log_p) {
  const auto& test = resolved_.network.residual_test;
  if (!test.iterative_rejection || static_cast<int>(rejected_.size()) >= test.max_rejections) {
    return false;
  }
  // The most improbable accepted measurement of each point (of the whole network unless per
  // point), by log p: -1 where none is.
  const std::size_t groups = test.reject_per_point ? parameters_.points.size() : 1;
  std::vector<double> worst(groups, 0.0);
  std::vector<std::ptrdiff_t> worst_index(groups, -1);
  for (size_t m = 0; m < status_.size(); ++m) {
    if (status_[m] != MeasurementStatus::kAccepted) continue;
    const std::size_t g =
        test.reject_per_point ? static_cast<std::size_t>(resolved_.measurement_point[m]) : 0;
    if (log_p[m] < worst[g]) worst[g] = log_p[m], worst_index[g] = static_cast<std::ptrdiff_t>(m);
  }
  // Per point, only those within kRoundShare of the round's worst |w|: the worst blunders bend
  // the adjustment and lift good rays elsewhere past the critical value (a small wand network
  // with 5 % blunders lost four times the good rays when every point's worst beyond it went at
  // once); they go first, the lesser ones in the next rounds.
  constexpr double kRoundShare = 0.25;
  const double round_worst = w_of_log_p(*std::ranges::min_element(worst));
  const double threshold = std::max(test.critical_snooping, kRoundShare * round_worst);
  bool any = false;
  for (std::size_t g = 0; g < groups; ++g) {
    if (worst_index[g] < 0 || static_cast<int>(rejected_.size()) >= test.max_rejections) continue;
    const double w = w_of_log_p(worst[g]);
    if (!(w > threshold)) continue;
    reject(static_cast<size_t>(worst_index[g]), w);
    any = true;
  }
  return any;
}

void DataSnooping::reject(size_t m, double w, bool ambiguous) {
  status_[m] = MeasurementStatus::kRejectedBlunder;
  const auto& meas = resolved_.network.measurements[m];
  rejected_.push_back({m, meas.station, meas.point, meas.frame_number, w, ambiguous});
}

// v^T P v of two rays after their point is triangulated from them alone, with the current
// cameras: 1 degree of freedom, 0 for rays that meet. From the point nearest to both rays, a few
// Gauss-Newton steps on the image residuals (numeric derivatives: 3 unknowns, 4 residuals).
double DataSnooping::pair_square_sum(size_t a, size_t b) const {
  const std::array<size_t, 2> index{a, b};
  std::array<sensor::CameraModel, 2> cameras;
  geometry::NearestPoint nearest;
  for (int i = 0; i < 2; ++i) {
    const auto& meas = resolved_.network.measurements[index[i]];
    cameras[i] = parameters_.camera(resolved_, resolved_.measurement_station[index[i]]);
    nearest.add(cameras[i].back_project({meas.u, meas.v}));
  }
  const auto residuals = [&](const Eigen::Vector3d& x) {
    Eigen::Vector4d r;
    for (int i = 0; i < 2; ++i) {
      const auto& meas = resolved_.network.measurements[index[i]];
      r.segment<2>(2 * i) =
          (cameras[i].project(x).pixel - Eigen::Vector2d(meas.u, meas.v)) / meas.sigma_px;
    }
    return r;
  };
  Eigen::Vector3d x = nearest.solve();
  for (int step = 0; step < 5; ++step) {
    const Eigen::Vector4d r = residuals(x);
    Eigen::Matrix<double, 4, 3> jacobian;
    for (int k = 0; k < 3; ++k) {
      const double h = 1e-6 * std::max(1.0, x.norm());
      jacobian.col(k) = (residuals(x + h * Eigen::Vector3d::Unit(k)) - r) / h;
    }
    const Eigen::Vector3d dx =
        (jacobian.transpose() * jacobian).ldlt().solve(-jacobian.transpose() * r);
    if (!dx.allFinite()) break;
    x += dx;
  }
  return residuals(x).squaredNorm();
}

// Once no measurement is left to reject, the points that lost a ray to data snooping and kept
// two are looked at again, with the cleaned cameras. A blunder along the epipolar line of one
// good ray can make the other good ray look worst; rejecting that one keeps the blunder,
// undetectable in a two-ray point. Each two-ray subset of the three rays stands for the
// hypothesis that the third ray is the wrong one, its v^T P v for the evidence against it.
// When a gross error is there (a subset far beyond the critical value) but the evidence for
// the rejection (the kept pair) over the best other hypothesis is less than the critical value,
// the data cannot tell which ray was wrong: the kept rays go too, and with them the point.
// True when any went.
bool DataSnooping::reject_ambiguous_points(const std::vector<double>& log_p, double sigma0) {
  const double critical = std::pow(resolved_.network.residual_test.critical_snooping * sigma0, 2);
  constexpr double kGross = 4.0;  // a gross error: v^T P v beyond 4 x critical (2 x critical |w|)
  std::vector<std::vector<size_t>> kept(parameters_.points.size());
  for (size_t m = 0; m < status_.size(); ++m) {
    if (status_[m] == MeasurementStatus::kAccepted) {
      kept[resolved_.measurement_point[m]].push_back(m);
    }
  }
  bool any = false;
  for (size_t r = 0; r < rejected_.size(); ++r) {
    const size_t m = rejected_[r].index;
    const int point = resolved_.measurement_point[m];
    const std::vector<size_t> rays = kept[point];
    if (rays.size() != 2 || point_held(resolved_.network.points[point])) continue;
    const double without_m = pair_square_sum(rays[0], rays[1]);
    const double a = pair_square_sum(m, rays[1]), b = pair_square_sum(m, rays[0]);
    if (std::max(a, b) <= kGross * critical || std::min(a, b) - without_m > critical) continue;
    for (size_t k : rays) reject(k, w_of_log_p(log_p[k]), true);
    kept[point].clear();
    any = true;
  }
  return any;
}

}  // namespace syncap::estimators
