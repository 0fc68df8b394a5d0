#include "estimators/bundle_adjustment.hpp"

#include <ceres/ceres.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <numeric>
#include <set>
#include <sstream>

#include "estimators/adjustment_covariance.hpp"
#include "estimators/adjustment_datum.hpp"
#include "estimators/adjustment_network.hpp"
#include "estimators/adjustment_parameters.hpp"
#include "estimators/adjustment_problem.hpp"
#include "estimators/cost_functors.hpp"
#include "estimators/covariance.hpp"
#include "geometry/triangulation.hpp"
#include "sensor/camera_model.hpp"
#include "sensor/rotation.hpp"
#include "util/printf_string.hpp"

namespace syncap::estimators {
namespace {

using geometry::NearestPoint;
using scene::ParameterMode;
using sensor::ExteriorBlock;
using sensor::InteriorBlock;

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

const auto& kInteriorNames = sensor::InteriorBlock::kNames;
const auto& kExteriorNames = sensor::ExteriorBlock::kNames;

// ", N of them with the M points whose wrong ray could not be told", or nothing.
std::string ambiguous_note(const std::vector<RejectedMeasurement>& rejected) {
  long rays = 0;
  for (const auto& r : rejected) rays += r.ambiguous;
  if (rays == 0) return "";
  return util::printf_string(", %ld of them with the %ld points whose wrong ray could not be told",
                             rays, rays / 2);
}

class Adjuster {
 public:
  Adjuster(const scene::Network& network, const BundleOptions& options)
      : network_(network), options_(options), resolved_(resolve(network)), parameters_(network) {
    status_.assign(network.measurements.size(), MeasurementStatus::kAccepted);
    result_.measurements.resize(network.measurements.size());
  }

  BundleAdjustmentResult run();

 private:
  // The sigma0 data snooping standardises with: the a posteriori one, or 1 (the a priori).
  double snooping_sigma0() const {
    return network_.residual_test.snoop_with_a_posteriori_sigma0 ? result_.sigma0 : 1.0;
  }

  bool solve(bool strict);
  void evaluate_residuals();
  bool compute_cofactors();
  bool reject_worst_blunder();
  void reject(size_t m, double w, bool ambiguous = false);
  double pair_square_sum(size_t a, size_t b) const;
  bool reject_ambiguous_points();
  void fill_result();

  const scene::Network& network_;
  const BundleOptions& options_;
  const ResolvedNetwork resolved_;

  AdjustmentParameters parameters_;
  std::vector<MeasurementStatus> status_;
  // Per measurement, the natural logarithm of the probability under H0 of its residual vector's
  // test statistic (both coordinates together; 0 when the network does not control it).
  std::vector<double> log_p_;

  DatumChoice datum_;

  std::vector<Term> terms_;
  long unknowns_ = 0;
  ArrowCofactors cofactors_;
  bool have_cofactors_ = false;

  BundleAdjustmentResult result_;
};

// A strict solve follows the design's convergence control; a relaxed one (the rounds of data
// snooping, which only rank residuals) stops at Ceres' default tolerances and accepts any usable
// solution.
bool Adjuster::solve(bool strict) {
  parameters_.update_groups(resolved_, &status_);
  ceres::Problem::Options problem_options;
  problem_options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_options.manifold_ownership = ceres::TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  terms_ = build_problem(resolved_, options_, datum_, status_, &parameters_, &problem);
  const auto& design = network_.design;
  ceres::Solver::Summary summary;
  ceres::Solve(solver_options(design, options_, strict, &parameters_, problem), &problem, &summary);
  parameters_.read_points_from_groups();
  unknowns_ = estimated_values(problem);
  ++result_.adjustments;
  result_.iterations = static_cast<int>(summary.iterations.size()) - 1;
  result_.termination = summary.BriefReport();
  result_.converged = summary.termination_type == ceres::CONVERGENCE;
  if (!strict) return summary.IsSolutionUsable();
  return result_.converged || design.force_complete || design.exact_iterations.has_value();
}

void Adjuster::evaluate_residuals() {
  const ResidualSums sums =
      estimators::evaluate_residuals(terms_, parameters_, network_, &result_.measurements);
  result_.observations = sums.count;
  result_.unknowns = unknowns_;
  result_.redundancy = sums.count - unknowns_;
  result_.sigma0 =
      result_.redundancy > 0
          ? std::sqrt(sums.weighted_square_sum / static_cast<double>(result_.redundancy))
          : 0.0;
}

bool Adjuster::compute_cofactors() {
  std::vector<TermJacobian> jacobians;
  if (!estimators::compute_cofactors(resolved_, parameters_, datum_, terms_, &cofactors_,
                                     &jacobians, &result_.messages)) {
    return false;
  }

  // q_vv = q_ll - a Q_xx a^T per image coordinate, from the cofactors of the values it touches;
  // whitened, q_ll = 1.
  const double sigma0 = snooping_sigma0();
  log_p_.assign(network_.measurements.size(), 0.0);
  for (size_t t = 0; t < terms_.size(); ++t) {
    if (terms_[t].kind != Term::Kind::kImage) continue;
    const TermJacobian& tj = jacobians[t];
    const int nc = static_cast<int>(tj.camera_columns.size());
    const int ng = static_cast<int>(tj.jacobian.cols()) - nc;
    Eigen::MatrixXd q(nc + ng, nc + ng);
    for (int a = 0; a < nc; ++a) {
      for (int b = 0; b < nc; ++b)
        q(a, b) = cofactors_.camera_camera(tj.camera_columns[a], tj.camera_columns[b]);
      for (int b = 0; b < ng; ++b)
        q(a, nc + b) = q(nc + b, a) = cofactors_.camera_group[tj.group](tj.camera_columns[a], b);
    }
    q.bottomRightCorner(ng, ng) = cofactors_.group_group[tj.group];
    const Eigen::Matrix2d h = tj.jacobian * q * tj.jacobian.transpose();
    auto& out = result_.measurements[terms_[t].measurement];
    const double sigma_px = network_.measurements[terms_[t].measurement].sigma_px;
    out.redundancy_u = 1.0 - h(0, 0);
    out.redundancy_v = 1.0 - h(1, 1);
    auto standardised = [&](double v_px, double share) {
      return share > kMinRedundancyShare ? v_px / sigma_px / (sigma0 * std::sqrt(share)) : 0.0;
    };
    out.w_u = standardised(out.residual_u, out.redundancy_u);
    out.w_v = standardised(out.residual_v, out.redundancy_v);
    const Eigen::Vector2d v(out.residual_u / sigma_px, out.residual_v / sigma_px);
    log_p_[terms_[t].measurement] = log_p_of_point(Eigen::Matrix2d::Identity() - h, v, sigma0);
  }
  have_cofactors_ = true;
  return true;
}

// Data snooping tests a measurement's two coordinates together: a blunder displaces an image
// point in some direction, and split over u and v it can hide behind a good ray of the same
// point whose single coordinate looks worse (a 4-ray point of the strawlab data did just that).
// The most improbable measurement goes first; its statistic is reported, and tested, as the 1-D
// |w| of equal probability, so the critical value keeps its meaning (eq 4.31).
bool Adjuster::reject_worst_blunder() {
  const auto& test = network_.residual_test;
  if (!test.iterative_rejection ||
      static_cast<int>(result_.rejected.size()) >= test.max_rejections) {
    return false;
  }
  double worst = 0.0;
  size_t worst_index = 0;
  for (size_t m = 0; m < status_.size(); ++m) {
    if (status_[m] != MeasurementStatus::kAccepted) continue;
    if (log_p_[m] < worst) worst = log_p_[m], worst_index = m;
  }
  const double w = w_of_log_p(worst);
  if (!(w > test.critical_snooping)) return false;
  reject(worst_index, w);
  return true;
}

void Adjuster::reject(size_t m, double w, bool ambiguous) {
  status_[m] = MeasurementStatus::kRejectedBlunder;
  const auto& meas = network_.measurements[m];
  result_.rejected.push_back({m, meas.station, meas.point, meas.frame_number, w, ambiguous});
}

// v^T P v of two rays after their point is triangulated from them alone, with the current
// cameras: 1 degree of freedom, 0 for rays that meet. From the point nearest to both rays, a few
// Gauss-Newton steps on the image residuals (numeric derivatives: 3 unknowns, 4 residuals).
double Adjuster::pair_square_sum(size_t a, size_t b) const {
  const std::array<size_t, 2> index{a, b};
  std::array<sensor::CameraModel, 2> cameras;
  NearestPoint nearest;
  for (int i = 0; i < 2; ++i) {
    const auto& meas = network_.measurements[index[i]];
    cameras[i] = parameters_.camera(resolved_, resolved_.measurement_station[index[i]]);
    nearest.add(cameras[i].back_project({meas.u, meas.v}));
  }
  const auto residuals = [&](const Eigen::Vector3d& x) {
    Eigen::Vector4d r;
    for (int i = 0; i < 2; ++i) {
      const auto& meas = network_.measurements[index[i]];
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
bool Adjuster::reject_ambiguous_points() {
  const double sigma0 = snooping_sigma0();
  const double critical = std::pow(network_.residual_test.critical_snooping * sigma0, 2);
  constexpr double kGross = 4.0;  // a gross error: v^T P v beyond 4 x critical (2 x critical |w|)
  std::vector<std::vector<size_t>> kept(parameters_.points.size());
  for (size_t m = 0; m < status_.size(); ++m) {
    if (status_[m] == MeasurementStatus::kAccepted) {
      kept[resolved_.measurement_point[m]].push_back(m);
    }
  }
  bool any = false;
  for (size_t r = 0; r < result_.rejected.size(); ++r) {
    const size_t m = result_.rejected[r].index;
    const int point = resolved_.measurement_point[m];
    const std::vector<size_t> rays = kept[point];
    if (rays.size() != 2 || point_held(network_.points[point])) continue;
    const double without_m = pair_square_sum(rays[0], rays[1]);
    const double a = pair_square_sum(m, rays[1]), b = pair_square_sum(m, rays[0]);
    if (std::max(a, b) <= kGross * critical || std::min(a, b) - without_m > critical) continue;
    for (size_t k : rays) reject(k, w_of_log_p(log_p_[k]), true);
    kept[point].clear();
    any = true;
  }
  return any;
}

void Adjuster::fill_result() {
  const double variance = result_.sigma0 * result_.sigma0;
  if (have_cofactors_ && result_.datum == Datum::kInnerConstraints)
    s_transform(network_, parameters_, &cofactors_);
  result_.covariance_computed = have_cofactors_;
  if (have_cofactors_) result_.camera_covariance = variance * cofactors_.camera_camera;

  for (size_t m = 0; m < parameters_.interior.size(); ++m) {
    ModelResult model;
    model.name = network_.models[m].name;
    model.interior = sensor::interior_from_block(parameters_.interior[m].data());
    if (have_cofactors_) {
      set_interior_precision(result_.camera_covariance,
                             parameters_.interior_column(static_cast<int>(m), 0), &model);
    }
    result_.models.push_back(model);
  }
  for (size_t s = 0; s < parameters_.exterior.size(); ++s) {
    StationResult station;
    station.name = network_.stations[s].name;
    station.camera_id = network_.stations[s].camera_id;
    station.exterior = sensor::exterior_from_block(parameters_.exterior[s].data());
    if (have_cofactors_) {
      set_exterior_precision(result_.camera_covariance,
                             parameters_.exterior_column(static_cast<int>(s), 0), &station);
    }
    result_.stations.push_back(station);
  }
  std::vector<double> square_sum(parameters_.exterior.size(), 0.0);
  for (size_t m = 0; m < status_.size(); ++m) {
    auto& station = result_.stations[resolved_.measurement_station[m]];
    auto& out = result_.measurements[m];
    out.status = status_[m];
    if (status_[m] == MeasurementStatus::kAccepted) {
      ++station.measurements;
      square_sum[resolved_.measurement_station[m]] +=
          out.residual_u * out.residual_u + out.residual_v * out.residual_v;
    } else {
      ++station.rejected;
    }
  }
  for (size_t s = 0; s < parameters_.exterior.size(); ++s) {
    auto& station = result_.stations[s];
    if (station.measurements > 0)
      station.rms_px = std::sqrt(square_sum[s] / (2.0 * station.measurements));
  }
  for (size_t p = 0; p < parameters_.points.size(); ++p) {
    PointResult point;
    point.name = network_.points[p].name;
    point.xyz = {parameters_.points[p].x(), parameters_.points[p].y(), parameters_.points[p].z()};
    point.adjusted = parameters_.slot[p].group >= 0;
    if (point.adjusted && have_cofactors_) {
      const PointSlot slot = parameters_.slot[p];
      set_point_precision(cofactors_.group_group[slot.group], slot.offset, variance, &point);
    }
    result_.points.push_back(point);
  }
  for (size_t s = 0; s < parameters_.exterior.size(); ++s) {
    if (result_.stations[s].rejected > 0) {
      result_.messages.push_back("station " + quoted(result_.stations[s].name) + ": " +
                                 std::to_string(result_.stations[s].rejected) +
                                 " measurements removed");
    }
  }
}

BundleAdjustmentResult Adjuster::run() {
  parameters_.triangulate_approximations(resolved_, &status_, &result_.messages);
  datum_ = choose_datum(resolved_, parameters_, &result_.messages);
  result_.datum = datum_.datum;
  const auto& design = network_.design;
  const auto& test = network_.residual_test;
  result_.critical_w = test.critical_snooping;
  const bool snoop =
      design.statistical_tests && design.calculate_covariance && test.iterative_rejection;
  // Snooping rounds are relaxed; the last adjustment, after the last rejection, is strict.
  bool strict = !snoop;
  while (true) {
    const bool usable = solve(strict);
    evaluate_residuals();
    if (!usable) {
      result_.messages.push_back("adjustment did not converge (" + result_.termination +
                                 "); no covariance or tests (FORCE COMPLETE computes them)");
      break;
    }
    if (!design.calculate_covariance || !compute_cofactors()) break;
    if (snoop && (reject_worst_blunder() || reject_ambiguous_points())) {
      strict = false;
    } else if (strict) {
      break;
    } else {
      strict = true;
    }
    have_cofactors_ = false;
  }
  if (have_cofactors_ && design.statistical_tests) {
    result_.tests_computed = true;
    result_.variance_test = test_variance_factor(result_.sigma0 * result_.sigma0,
                                                 result_.redundancy, test.alpha_variance);
    // The shape of the distribution; its scale is the variance test's.
    std::vector<double> w;
    for (size_t m = 0; m < status_.size(); ++m) {
      if (status_[m] != MeasurementStatus::kAccepted) continue;
      const auto& out = result_.measurements[m];
      const double scale =
          test.snoop_with_a_posteriori_sigma0 || !(result_.sigma0 > 0.0) ? 1.0 : result_.sigma0;
      if (out.redundancy_u > kMinRedundancyShare) w.push_back(out.w_u / scale);
      if (out.redundancy_v > kMinRedundancyShare) w.push_back(out.w_v / scale);
    }
    result_.goodness_of_fit = test_goodness_of_fit(w, test.alpha_goodness);
  }
  if (!result_.rejected.empty()) {
    result_.messages.push_back("data snooping removed " + std::to_string(result_.rejected.size()) +
                               " measurements (|w| > " + std::to_string(test.critical_snooping) +
                               ")" + ambiguous_note(result_.rejected));
  }
  fill_result();
  return std::move(result_);
}

using util::printf_string;

}  // namespace

std::string format_summary(const BundleAdjustmentResult& r) {
  std::string out;
  out += printf_string("adjustments %d, last %d iterations, %s\n", r.adjustments, r.iterations,
                       r.converged ? "converged" : "NOT converged");
  out += printf_string("observations %ld, unknowns %ld, redundancy %ld, sigma0 %.4f\n",
                       r.observations, r.unknowns, r.redundancy, r.sigma0);
  if (r.tests_computed) {
    const auto& v = r.variance_test;
    out +=
        printf_string("variance factor %.4f in [%.4f, %.4f] (chi-square, alpha %.3g): %s\n",
                      v.variance_factor, v.lower, v.upper, v.alpha, v.passed ? "passed" : "FAILED");
    const auto& g = r.goodness_of_fit;
    out += printf_string(
        "goodness of fit y %.2f <= %.2f (%d classes, %ld residuals): %s; KS D %.4f p %.3f\n",
        g.statistic, g.critical, g.bins, g.samples, g.passed ? "passed" : "FAILED", g.ks_distance,
        g.ks_p_value);
    out += printf_string("data snooping |w| > %.2f: %zu removed%s\n", r.critical_w,
                         r.rejected.size(), ambiguous_note(r.rejected).c_str());
  }
  for (const auto& m : r.models) {
    out += "camera model " + m.name + ":";
    const auto values = sensor::interior_block(m.interior);
    for (int i = 0; i < kInteriorSize; ++i) {
      out += printf_string(" %s %.6g +- %.2g", kInteriorNames[i], values[i], m.interior_sigma[i]);
    }
    out += "\n";
  }
  for (const auto& s : r.stations) {
    out += printf_string("station %s: rms %.3f px, %ld measurements, %ld removed\n", s.name.c_str(),
                         s.rms_px, s.measurements, s.rejected);
  }
  for (const auto& m : r.models) {
    const int n = static_cast<int>(m.estimated_interior.size());
    if (n == 0) continue;
    out += "Camera " + m.name;
    for (int i : m.estimated_interior) out += printf_string(" %6s", kInteriorNames[i]);
    out += "\n";
    for (int a = 0; a < n; ++a) {
      out += printf_string("%-6s", kInteriorNames[m.estimated_interior[a]]);
      for (int b = 0; b < n; ++b) {
        out += b < a ? std::string(7, ' ') : printf_string(" %6.3f", m.interior_correlation(a, b));
      }
      out += "\n";
    }
  }
  return out;
}

BundleAdjustmentResult adjust(const scene::Network& network, const BundleOptions& options) {
  Adjuster adjuster(network, options);
  return adjuster.run();
}

}  // namespace syncap::estimators
