// RDLT relative orientation (thesis section 4.1.2, Fig 4.8). Layout of L used here: the
// coplanarity condition (eq 4.17) is p1^T L p2 = 0 with p = (x'/c, y'/c, -1) in each sensor
// frame and L = [b]x R (the thesis' axiator B is -[b]x; the sign is absorbed by the duality).
// The unknowns are L's elements row by row, l[3 i + j] = L(i, j). The thesis' L1..L9 of eq 4.20
// multiply y1 x2, y1 y2, y1 c2, c1 x2, c1 y2, c1 c2, x1 x2, x1 y2, x1 c2; in this layout its
// divisors are:
//   Bx dominant: L5 (c1 y2)  -> L(2, 1) = (b x r2)_z = Bx for R = I;
//   Bz dominant: L8 (x1 y2)  -> L(0, 1) = -Bz for R = I;
//   By dominant: the thesis names L3 (y1 c2), which is zero for a pure By base; the element that
//                is +-By for R = I is x1 c2 (L9), L(0, 2), and that one is used.
#include "estimators/relative_orientation.hpp"

#include <ceres/ceres.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <random>
#include <sstream>

#include "sensor/camera_model.hpp"

namespace syncap::estimators {
namespace {

constexpr int kMinimumPoints = 8;       // eq 4.22 has eight unknowns
constexpr int kRelativeParameters = 5;  // three rotations, two base directions
constexpr std::array<RdltSystem, 3> kSystems = {RdltSystem::kBx, RdltSystem::kBy, RdltSystem::kBz};

using CoplanarityRow = Eigen::Matrix<double, 1, 9>;

int divisor_index(RdltSystem system) {
  switch (system) {
    case RdltSystem::kBx:
      return 3 * 2 + 1;
    case RdltSystem::kBy:
      return 3 * 0 + 2;
    case RdltSystem::kBz:
      return 3 * 0 + 1;
  }
  return 0;
}

// Eq 4.20 for one correspondence: the coefficients of L's nine elements.
CoplanarityRow coplanarity_row(const Eigen::Vector3d& p1, const Eigen::Vector3d& p2) {
  CoplanarityRow row;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) row(3 * i + j) = p1(i) * p2(j);
  }
  return row;
}

// The pair of direction sets and their pixel scales: everything the estimation looks at.
struct Correspondences {
  const std::vector<Eigen::Vector3d>& first;
  const std::vector<Eigen::Vector3d>& second;
  double first_units_per_pixel;
  double second_units_per_pixel;
};

// The epipolar (Sampson) distance of one correspondence [px]: the coplanarity misclosure divided
// by its gradient with respect to the four pixel coordinates. Templated for Ceres.
template <typename T>
T sampson_distance_px(const Eigen::Matrix<T, 3, 1>& p1, const Eigen::Matrix<T, 3, 1>& l_p2,
                      const Eigen::Matrix<T, 3, 1>& lt_p1, double k1, double k2) {
  using std::sqrt;
  const T misclosure = p1.dot(l_p2);
  const T gradient = sqrt(l_p2(0) * l_p2(0) * k1 * k1 + l_p2(1) * l_p2(1) * k1 * k1 +
                          lt_p1(0) * lt_p1(0) * k2 * k2 + lt_p1(1) * lt_p1(1) * k2 * k2);
  return misclosure / gradient;
}

double sampson_distance_px(const Correspondences& c, const Eigen::Matrix3d& l, size_t i) {
  const Eigen::Vector3d l_p2 = l * c.second[i];
  const Eigen::Vector3d lt_p1 = l.transpose() * c.first[i];
  return sampson_distance_px<double>(c.first[i], l_p2, lt_p1, c.first_units_per_pixel,
                                     c.second_units_per_pixel);
}

// The coplanarity residual of the refinement, in pixels: camera 2's rotation as a unit
// quaternion (Eigen's x, y, z, w order) and the unit base.
struct CoplanarityResidual {
  CoplanarityResidual(const Eigen::Vector3d& p1, const Eigen::Vector3d& p2, double k1, double k2)
      : p1_(p1), p2_(p2), k1_(k1), k2_(k2) {}

  template <typename T>
  bool operator()(const T* quaternion, const T* base, T* residual) const {
    const Eigen::Map<const Eigen::Quaternion<T>> rotation(quaternion);
    const Eigen::Map<const Eigen::Matrix<T, 3, 1>> b(base);
    const Eigen::Matrix<T, 3, 1> p1 = p1_.cast<T>();
    const Eigen::Matrix<T, 3, 1> l_p2 = b.cross(rotation * p2_.cast<T>());    // L p2 = b x R p2
    const Eigen::Matrix<T, 3, 1> lt_p1 = rotation.conjugate() * p1.cross(b);  // L^T p1
    residual[0] = sampson_distance_px<T>(p1, l_p2, lt_p1, k1_, k2_);
    return true;
  }

  static ceres::CostFunction* create(const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                                     double k1, double k2) {
    return new ceres::AutoDiffCostFunction<CoplanarityResidual, 1, 4, 3>(
        new CoplanarityResidual(p1, p2, k1, k2));
  }

 private:
  Eigen::Vector3d p1_, p2_;
  double k1_, k2_;
};

// Eq 4.22 for one system on the given correspondences: the linear elements with the divisor set
// to 1, the condition number of N = A^T A and the algebraic sigma0.
struct LinearSolution {
  Eigen::Matrix3d l = Eigen::Matrix3d::Zero();
  double condition_number = std::numeric_limits<double>::infinity();
  bool ok = false;
};

LinearSolution solve_linear_system(const Correspondences& c, const std::vector<size_t>& indices,
                                   RdltSystem system) {
  const int k = divisor_index(system);
  Eigen::MatrixXd a(indices.size(), 8);
  Eigen::VectorXd y(indices.size());
  for (size_t r = 0; r < indices.size(); ++r) {
    const CoplanarityRow row = coplanarity_row(c.first[indices[r]], c.second[indices[r]]);
    for (int j = 0, col = 0; j < 9; ++j) {
      if (j != k) a(r, col++) = row(j);
    }
    y(r) = -row(k);
  }
  const Eigen::MatrixXd normal = a.transpose() * a;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(normal, Eigen::EigenvaluesOnly);
  LinearSolution solution;
  const double smallest = eigen.eigenvalues().minCoeff();
  if (!(smallest > 0.0)) return solution;
  solution.condition_number = eigen.eigenvalues().maxCoeff() / smallest;
  const Eigen::VectorXd x = normal.ldlt().solve(a.transpose() * y);
  for (int j = 0, col = 0; j < 9; ++j) solution.l(j / 3, j % 3) = j == k ? 1.0 : x(col++);
  solution.ok = solution.l.allFinite();
  return solution;
}

int count_in_front(const Correspondences& c, const std::vector<size_t>& indices,
                   const Eigen::Matrix3d& rotation, const Eigen::Vector3d& base) {
  int count = 0;
  for (size_t i : indices) {
    const Eigen::Vector2d lambda = ray_parameters(c.first[i], c.second[i], rotation, base);
    if (lambda(0) > 0.0 && lambda(1) > 0.0) ++count;
  }
  return count;
}

// The base and rotation of the linear elements (eqs 4.23-4.28). L is scaled so that
// L L^T = B B^T with |B| = 1 (trace 2), which leaves the sign of L free (eq 4.23's square root:
// the dual solution, a turn of camera 2 by pi about the base) and the sign of B. Of the four
// candidates the one with the most points in front of both cameras wins (the 'in front' test).
// The rotation is taken from the singular value decomposition of L, which is eq 4.28's cofactor
// formula made orthonormal for noisy L.
struct Decomposition {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d base = Eigen::Vector3d::UnitX();
  int in_front = -1;
};

Decomposition decompose(const Correspondences& c, const std::vector<size_t>& indices,
                        const Eigen::Matrix3d& l) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(l, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d u = svd.matrixU();
  Eigen::Matrix3d v = svd.matrixV();
  if (u.determinant() < 0.0) u = -u;
  if (v.determinant() < 0.0) v = -v;
  Eigen::Matrix3d w;
  w << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  Decomposition best;
  for (const Eigen::Matrix3d& rotation : {Eigen::Matrix3d(u * w * v.transpose()),
                                          Eigen::Matrix3d(u * w.transpose() * v.transpose())}) {
    for (double sign : {1.0, -1.0}) {
      const Eigen::Vector3d base = sign * u.col(2);
      const int in_front = count_in_front(c, indices, rotation, base);
      if (in_front > best.in_front) best = {rotation, base, in_front};
    }
  }
  return best;
}

// The nearest essential matrix (singular values 1, 1, 0) of a linear solution.
Eigen::Matrix3d nearest_essential(const Eigen::Matrix3d& l) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(l, Eigen::ComputeFullU | Eigen::ComputeFullV);
  return svd.matrixU() * Eigen::Vector3d(1, 1, 0).asDiagonal() * svd.matrixV().transpose();
}

std::vector<size_t> points_within(const Correspondences& c, const Eigen::Matrix3d& l,
                                  double threshold_px) {
  std::vector<size_t> inliers;
  for (size_t i = 0; i < c.first.size(); ++i) {
    if (std::abs(sampson_distance_px(c, l, i)) < threshold_px) inliers.push_back(i);
  }
  return inliers;
}

// The null vector of eq 4.20 on the given correspondences (homogeneous least squares), made
// essential.
Eigen::Matrix3d homogeneous_solution(const Correspondences& c, const std::vector<size_t>& indices) {
  Eigen::Matrix<double, 9, 9> normal = Eigen::Matrix<double, 9, 9>::Zero();
  for (size_t i : indices) {
    const CoplanarityRow row = coplanarity_row(c.first[i], c.second[i]);
    normal += row.transpose() * row;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 9, 9>> eigen(normal);
  const Eigen::Matrix<double, 9, 1> null = eigen.eigenvectors().col(0);
  return nearest_essential(
      Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(null.data()));
}

// The best sample's model is only as good as its eight points: solving again on its whole
// consensus and taking the consensus anew, until it stops growing, recovers the good points the
// sample's error kept out.
void polish_consensus(const Correspondences& c, const RelativeOrientationOptions& options,
                      std::vector<size_t>& inliers) {
  for (int round = 0; round < 5 && inliers.size() > kMinimumPoints; ++round) {
    std::vector<size_t> next =
        points_within(c, homogeneous_solution(c, inliers), options.ransac_threshold_px);
    if (next.size() <= inliers.size()) return;
    inliers = std::move(next);
  }
}

// RANSAC start: eight-point samples solved as eq 4.22 (with eight points the three systems
// share one solution, the null vector of the 8 x 9 coefficients, so it is solved once), scored
// by the number of correspondences within the threshold.
struct Consensus {
  std::vector<size_t> inliers;
  int iterations = 0;
};

Consensus find_consensus(const Correspondences& c, const RelativeOrientationOptions& options) {
  const size_t n = c.first.size();
  std::mt19937 rng(options.ransac_seed);
  std::vector<size_t> all(n);
  std::iota(all.begin(), all.end(), size_t{0});
  Consensus best;
  int needed = options.ransac_max_iterations;
  for (int iteration = 0; iteration < needed; ++iteration) {
    std::vector<size_t> sample = all;
    for (int i = 0; i < kMinimumPoints; ++i) {
      std::uniform_int_distribution<size_t> pick(i, n - 1);
      std::swap(sample[i], sample[pick(rng)]);
    }
    sample.resize(kMinimumPoints);
    std::vector<size_t> inliers =
        points_within(c, homogeneous_solution(c, sample), options.ransac_threshold_px);
    best.iterations = iteration + 1;
    if (inliers.size() <= best.inliers.size()) continue;
    best.inliers = std::move(inliers);
    const double inlier_ratio = static_cast<double>(best.inliers.size()) / static_cast<double>(n);
    const double all_good = std::pow(inlier_ratio, kMinimumPoints);
    if (all_good >= 1.0 - 1e-12) break;
    const double required =
        std::log(1.0 - options.ransac_confidence) / std::log(1.0 - std::max(all_good, 1e-12));
    needed = static_cast<int>(std::min<double>(options.ransac_max_iterations, std::ceil(required)));
  }
  polish_consensus(c, options, best.inliers);
  return best;
}

// Least-squares refinement of the five relative parameters on the coplanarity residuals.
struct Refinement {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d base = Eigen::Vector3d::UnitX();
  bool converged = false;
  int iterations = 0;
  double sigma0_px = 0.0;
  Eigen::VectorXd residuals;  // per index [px]
  Eigen::MatrixXd jacobian;   // per index, five tangent columns
};

Refinement refine(const Correspondences& c, const std::vector<size_t>& indices,
                  const Eigen::Matrix3d& rotation, const Eigen::Vector3d& base,
                  const RelativeOrientationOptions& options) {
  Eigen::Quaterniond quaternion(rotation);
  Eigen::Vector3d b = base.normalized();
  ceres::Problem problem;
  for (size_t i : indices) {
    problem.AddResidualBlock(
        CoplanarityResidual::create(c.first[i], c.second[i], c.first_units_per_pixel,
                                    c.second_units_per_pixel),
        nullptr, quaternion.coeffs().data(), b.data());
  }
  problem.SetManifold(quaternion.coeffs().data(), new ceres::EigenQuaternionManifold);
  problem.SetManifold(b.data(), new ceres::SphereManifold<3>);

  ceres::Solver::Options solver_options;
  solver_options.linear_solver_type = ceres::DENSE_QR;
  solver_options.max_num_iterations = options.max_iterations;
  solver_options.function_tolerance = 1e-12;
  solver_options.gradient_tolerance = 1e-14;
  solver_options.parameter_tolerance = 1e-12;
  solver_options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(solver_options, &problem, &summary);

  Refinement result;
  result.rotation = quaternion.normalized().toRotationMatrix();
  result.base = b.normalized();
  result.converged = summary.termination_type == ceres::CONVERGENCE;
  result.iterations = summary.num_successful_steps + summary.num_unsuccessful_steps;

  std::vector<double> residuals;
  ceres::CRSMatrix jacobian;
  problem.Evaluate(ceres::Problem::EvaluateOptions(), nullptr, &residuals, nullptr, &jacobian);
  result.residuals = Eigen::Map<const Eigen::VectorXd>(residuals.data(), residuals.size());
  result.jacobian = Eigen::MatrixXd::Zero(jacobian.num_rows, jacobian.num_cols);
  for (int r = 0; r < jacobian.num_rows; ++r) {
    for (int k = jacobian.rows[r]; k < jacobian.rows[r + 1]; ++k) {
      result.jacobian(r, jacobian.cols[k]) = jacobian.values[k];
    }
  }
  const double redundancy = static_cast<double>(indices.size()) - kRelativeParameters;
  result.sigma0_px = redundancy > 0 ? std::sqrt(result.residuals.squaredNorm() / redundancy) : 0.0;
  return result;
}

// One normal system carried through Fig 4.8: linear solution, dual solution, refinement.
struct SystemTrial {
  RdltSystem system = RdltSystem::kBx;
  double condition_number = 0.0;
  Refinement refinement;
};

std::optional<SystemTrial> try_system(const Correspondences& c, const std::vector<size_t>& indices,
                                      const LinearSolution& linear, RdltSystem system,
                                      const RelativeOrientationOptions& options) {
  if (!linear.ok || !(linear.condition_number <= options.max_condition_number)) {
    return std::nullopt;
  }
  const Decomposition start = decompose(c, indices, linear.l);
  if (start.in_front <= 0) return std::nullopt;
  return SystemTrial{system, linear.condition_number,
                     refine(c, indices, start.rotation, start.base, options)};
}

// The thesis' decision between the systems: converged before not converged, then the smaller
// sigma0 (differences below 0.1 % count as equal), then fewer iterations, then the better
// condition number.
bool better_trial(const SystemTrial& a, const SystemTrial& b) {
  if (a.refinement.converged != b.refinement.converged) return a.refinement.converged;
  const double sa = a.refinement.sigma0_px, sb = b.refinement.sigma0_px;
  if (std::abs(sa - sb) > 1e-3 * std::max(sa, sb)) return sa < sb;
  if (a.refinement.iterations != b.refinement.iterations) {
    return a.refinement.iterations < b.refinement.iterations;
  }
  return a.condition_number < b.condition_number;
}

// Data snooping (eqs 4.29-4.31, P = I): w_i = v_i / (sigma0 sqrt(q_vv,i)) with
// Q_vv = I - A (A^T A)^-1 A^T; the index of the largest |w| above the critical value, if any.
std::optional<size_t> worst_blunder(const Refinement& refinement, double critical) {
  const Eigen::MatrixXd& a = refinement.jacobian;
  const Eigen::MatrixXd normal_inverse = (a.transpose() * a).inverse();
  double worst = critical;
  std::optional<size_t> worst_index;
  for (Eigen::Index i = 0; i < a.rows(); ++i) {
    const double q_vv = 1.0 - a.row(i) * normal_inverse * a.row(i).transpose();
    if (!(q_vv > 1e-12) || !(refinement.sigma0_px > 0.0)) continue;
    const double w = std::abs(refinement.residuals(i)) / (refinement.sigma0_px * std::sqrt(q_vv));
    if (w > worst) {
      worst = w;
      worst_index = static_cast<size_t>(i);
    }
  }
  return worst_index;
}

RelativeOrientation failure(RelativeOrientationStatus status, const std::string& message) {
  RelativeOrientation result;
  result.status = status;
  result.message = "relative orientation: " + message;
  return result;
}

}  // namespace

const char* to_string(RdltSystem system) {
  switch (system) {
    case RdltSystem::kBx:
      return "Bx";
    case RdltSystem::kBy:
      return "By";
    case RdltSystem::kBz:
      return "Bz";
  }
  return "?";
}

Eigen::Vector3d image_direction(const sensor::SensorGeometry& sensor,
                                const sensor::InteriorOrientation& interior,
                                const Eigen::Vector2d& pixel) {
  sensor::CameraModel camera;  // exterior zero: object frame = sensor frame
  camera.sensor = sensor;
  camera.interior = interior;
  const Eigen::Vector3d d = camera.back_project(pixel).direction;
  return d / -d.z();
}

Eigen::Vector2d ray_parameters(const Eigen::Vector3d& first, const Eigen::Vector3d& second,
                               const Eigen::Matrix3d& rotation, const Eigen::Vector3d& base) {
  Eigen::Matrix<double, 3, 2> a;
  a << first, -(rotation * second);
  return (a.transpose() * a).ldlt().solve(a.transpose() * base);
}

RelativeOrientation estimate_relative_orientation(const ImageObservations& first,
                                                  const ImageObservations& second,
                                                  const RelativeOrientationOptions& options) {
  if (first.pixels.size() != second.pixels.size()) {
    std::ostringstream message;
    message << "the two images have different numbers of points (" << first.pixels.size() << " and "
            << second.pixels.size() << ")";
    return failure(RelativeOrientationStatus::kTooFewPoints, message.str());
  }
  std::vector<Eigen::Vector3d> d1, d2;
  for (size_t i = 0; i < first.pixels.size(); ++i) {
    d1.push_back(image_direction(first.sensor, first.interior, first.pixels[i]));
    d2.push_back(image_direction(second.sensor, second.interior, second.pixels[i]));
  }
  const auto pixels_per_unit = [](const ImageObservations& o) {
    return o.interior.c / (0.5 * (o.sensor.pixel_width_mm + o.sensor.pixel_height_mm));
  };
  return estimate_relative_orientation_from_directions(d1, d2, pixels_per_unit(first),
                                                       pixels_per_unit(second), options);
}

RelativeOrientation estimate_relative_orientation_from_directions(
    const std::vector<Eigen::Vector3d>& first, const std::vector<Eigen::Vector3d>& second,
    double first_pixels_per_unit, double second_pixels_per_unit,
    const RelativeOrientationOptions& options) {
  if (first.size() != second.size()) {
    return failure(RelativeOrientationStatus::kTooFewPoints,
                   "the two images have different numbers of points");
  }
  if (first.size() < static_cast<size_t>(kMinimumPoints)) {
    std::ostringstream message;
    message << first.size() << " corresponding points; need >= " << kMinimumPoints;
    return failure(RelativeOrientationStatus::kTooFewPoints, message.str());
  }
  if (!(first_pixels_per_unit > 0.0) || !(second_pixels_per_unit > 0.0)) {
    return failure(RelativeOrientationStatus::kDegenerate,
                   "the cameras' c / pixel size must be positive");
  }
  const Correspondences c{first, second, 1.0 / first_pixels_per_unit, 1.0 / second_pixels_per_unit};

  const Consensus consensus = find_consensus(c, options);
  if (consensus.inliers.size() <
      static_cast<size_t>(std::max(options.min_inliers, kMinimumPoints + 1))) {
    std::ostringstream message;
    message << "no consensus: the best of " << consensus.iterations << " samples explains "
            << consensus.inliers.size() << " of " << first.size() << " points within "
            << options.ransac_threshold_px << " px";
    return failure(RelativeOrientationStatus::kDegenerate, message.str());
  }
  std::vector<size_t> inliers = consensus.inliers;

  std::optional<SystemTrial> chosen;
  std::array<double, 3> condition_numbers{};
  for (size_t s = 0; s < kSystems.size(); ++s) {
    const LinearSolution linear = solve_linear_system(c, inliers, kSystems[s]);
    condition_numbers[s] = linear.condition_number;
    std::optional<SystemTrial> trial = try_system(c, inliers, linear, kSystems[s], options);
    if (trial && (!chosen || better_trial(*trial, *chosen))) chosen = std::move(trial);
  }
  if (!chosen) {
    return failure(RelativeOrientationStatus::kDegenerate,
                   "none of the normal systems (Bx, By, Bz) is solvable with points in front of "
                   "both cameras");
  }

  int rejections = 0;
  while (rejections < options.max_rejections && inliers.size() > kMinimumPoints + 1) {
    const std::optional<size_t> blunder =
        worst_blunder(chosen->refinement, options.critical_snooping);
    if (!blunder) break;
    inliers.erase(inliers.begin() + static_cast<std::ptrdiff_t>(*blunder));
    ++rejections;
    chosen->refinement =
        refine(c, inliers, chosen->refinement.rotation, chosen->refinement.base, options);
  }

  RelativeOrientation result;
  const Refinement& r = chosen->refinement;
  result.rotation = r.rotation;
  result.base = r.base;
  result.sigma0_px = r.sigma0_px;
  result.inliers.assign(first.size(), false);
  for (size_t i : inliers) result.inliers[i] = true;
  result.inlier_count = static_cast<int>(inliers.size());
  result.iterations = r.iterations;
  result.ransac_iterations = consensus.iterations;
  result.snooping_rejections = rejections;
  result.system = chosen->system;
  result.condition_number = chosen->condition_number;
  result.condition_numbers = condition_numbers;
  result.points_in_front = count_in_front(c, inliers, r.rotation, r.base);
  if (!r.converged) {
    result.status = RelativeOrientationStatus::kNotConverged;
    std::ostringstream message;
    message << "relative orientation: the refinement did not converge in " << r.iterations
            << " iterations (sigma0 " << r.sigma0_px << " px)";
    result.message = message.str();
  } else {
    result.status = RelativeOrientationStatus::kOk;
  }
  return result;
}

}  // namespace syncap::estimators
