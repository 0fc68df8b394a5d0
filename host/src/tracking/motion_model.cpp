#include "tracking/motion_model.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>

namespace syncap::tracking {
namespace {

using Matrix6 = Eigen::Matrix<double, 6, 6>;
using Vector6 = Eigen::Matrix<double, 6, 1>;

// White acceleration of sigma held over dt (Bar-Shalom's piecewise-constant model).
Matrix6 process_noise(double dt, double acceleration_sigma) {
  const double q = acceleration_sigma * acceleration_sigma;
  Matrix6 noise = Matrix6::Zero();
  noise.topLeftCorner<3, 3>().diagonal().setConstant(q * dt * dt * dt * dt / 4);
  noise.topRightCorner<3, 3>().diagonal().setConstant(q * dt * dt * dt / 2);
  noise.bottomLeftCorner<3, 3>().diagonal().setConstant(q * dt * dt * dt / 2);
  noise.bottomRightCorner<3, 3>().diagonal().setConstant(q * dt * dt);
  return noise;
}

// Constant velocity over dt plus the process noise.
void predict_cv(KinematicState& s, double dt, double acceleration_sigma) {
  Matrix6 f = Matrix6::Identity();
  f.topRightCorner<3, 3>().diagonal().setConstant(dt);
  s.x = f * s.x;
  s.p = f * s.p * f.transpose() + process_noise(dt, acceleration_sigma);
}

// The update with H = [I 0]; returns the log-likelihood of the innovation.
double correct_cv(KinematicState& s, const Eigen::Vector3d& z, const Eigen::Matrix3d& r) {
  const Eigen::Matrix3d innovation_cov = s.p.topLeftCorner<3, 3>() + r;
  const Eigen::LLT<Eigen::Matrix3d> llt(innovation_cov);
  const Eigen::Vector3d innovation = z - s.x.head<3>();
  const Eigen::Matrix<double, 6, 3> gain =
      llt.solve(s.p.leftCols<3>().transpose()).transpose();  // P H^T S^-1
  s.x += gain * innovation;
  s.p -= gain * s.p.topRows<3>();
  s.p = 0.5 * (s.p + s.p.transpose()).eval();
  const double mahalanobis = innovation.dot(llt.solve(innovation));
  const double log_det = 2.0 * llt.matrixL().toDenseMatrix().diagonal().array().log().sum();
  return -0.5 * (mahalanobis + log_det + 3.0 * std::log(2.0 * M_PI));
}

}  // namespace

MotionModel::MotionModel(const MotionModelOptions& options, double time_s,
                         const Eigen::Vector3d& position, const Eigen::Matrix3d& position_cov,
                         double speed_sigma_mm_s)
    : time_s_(time_s), single_(!(options.manoeuvre_acceleration_mm_s2 > 0)) {
  KinematicState s;
  s.x.head<3>() = position;
  s.p.topLeftCorner<3, 3>() = position_cov;
  s.p.bottomRightCorner<3, 3>().diagonal().setConstant(speed_sigma_mm_s * speed_sigma_mm_s);
  models_ = {s, s};
  if (!single_) {
    // The chain's stationary state: the share of time spent in each model.
    const double quiet = options.quiet_sojourn_s, manoeuvre = options.manoeuvre_sojourn_s;
    probability_ = {quiet / (quiet + manoeuvre), manoeuvre / (quiet + manoeuvre)};
  }
  combine();
}

void MotionModel::predict(double time_s, const MotionModelOptions& options) {
  const double dt = std::max(0.0, time_s - time_s_);
  time_s_ = std::max(time_s_, time_s);
  if (single_) {
    predict_cv(models_[0], dt, options.quiet_acceleration_mm_s2);
    combined_ = models_[0];
    return;
  }
  // Mixing: the chance of having left each model during dt, then each model's start as the
  // mixture of the models weighted by the chance of coming from each.
  const double leave_quiet = 1.0 - std::exp(-dt / options.quiet_sojourn_s);
  const double leave_manoeuvre = 1.0 - std::exp(-dt / options.manoeuvre_sojourn_s);
  const double transition[2][2] = {{1.0 - leave_quiet, leave_quiet},
                                   {leave_manoeuvre, 1.0 - leave_manoeuvre}};
  std::array<double, 2> predicted{};
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 2; ++i) predicted[j] += transition[i][j] * probability_[i];
  }
  std::array<KinematicState, 2> mixed;
  for (int j = 0; j < 2; ++j) {
    const double total = std::max(predicted[j], 1e-300);
    Vector6 x = Vector6::Zero();
    for (int i = 0; i < 2; ++i) x += transition[i][j] * probability_[i] / total * models_[i].x;
    Matrix6 p = Matrix6::Zero();
    for (int i = 0; i < 2; ++i) {
      const Vector6 d = models_[i].x - x;
      p += transition[i][j] * probability_[i] / total * (models_[i].p + d * d.transpose());
    }
    mixed[j] = {x, p};
  }
  models_ = mixed;
  probability_ = predicted;
  predict_cv(models_[0], dt, options.quiet_acceleration_mm_s2);
  predict_cv(models_[1], dt, options.manoeuvre_acceleration_mm_s2);
  combine();
}

void MotionModel::correct(const Eigen::Vector3d& z, const Eigen::Matrix3d& r) {
  if (single_) {
    correct_cv(models_[0], z, r);
    combined_ = models_[0];
    return;
  }
  std::array<double, 2> log_likelihood{};
  for (int j = 0; j < 2; ++j) log_likelihood[j] = correct_cv(models_[j], z, r);
  const double top = std::max(log_likelihood[0], log_likelihood[1]);
  double total = 0;
  for (int j = 0; j < 2; ++j) total += probability_[j] *= std::exp(log_likelihood[j] - top);
  for (double& p : probability_) p = std::clamp(p / total, 1e-9, 1.0);
  combine();
}

void MotionModel::widen(double dt, double acceleration_sigma) {
  const Matrix6 noise = process_noise(dt, acceleration_sigma);
  for (KinematicState& m : models_) m.p += noise;
  if (single_) {
    combined_ = models_[0];
  } else {
    combine();
  }
}

void MotionModel::combine() {
  KinematicState c;
  for (int j = 0; j < 2; ++j) c.x += probability_[j] * models_[j].x;
  for (int j = 0; j < 2; ++j) {
    const Vector6 d = models_[j].x - c.x;
    c.p += probability_[j] * (models_[j].p + d * d.transpose());
  }
  combined_ = c;
}

}  // namespace syncap::tracking
