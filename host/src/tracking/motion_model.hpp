// A marker's motion as an interacting-multiple-model filter (Blom & Bar-Shalom 1988) of two
// constant-velocity models that differ only in the white acceleration they allow: a quiet one
// (a marker on the trunk, a limb between steps) and a manoeuvring one (a foot at heel strike, a
// hand turning, a runner's whole body: real markers reach 31-176 m/s^2 at the 99th percentile).
//
// Why two models rather than one with a large acceleration: one filter must choose between gates
// wide enough for the fastest marker, which take ghosts and neighbours while a slow marker is
// hidden, and gates that lose every heel strike (the tracker's former single model at 10 m/s^2:
// 61 breaks per 1000 marker-frames on a real run at 60 Hz). The mixture follows each marker's own
// motion: its innovations raise the manoeuvring model's probability within a frame or two, and
// the gate is that of the combined prediction. The switching between the models is a Markov chain
// in time (mean sojourns below).
#pragma once

#include <Eigen/Core>
#include <array>

namespace syncap::tracking {

struct MotionModelOptions {
  double quiet_acceleration_mm_s2 = 10000;  // 10 m/s^2
  // 0: the quiet model alone, a plain constant-velocity Kalman filter. The default 20 m/s^2 with
  // the sojourns below: the gates grow a little faster while a walking or running marker is
  // hidden (running at 60 Hz: 10.8 -> 8.0 breaks per 1000 with the tracker's wide gate) without
  // reaching neighbours at 30 Hz. 150 m/s^2 alone follows running at 60 Hz but at 30 Hz its gate
  // (83 mm a frame) covers neighbouring markers (13 id switches per 1000 on the synthetic
  // motion); the tracker's wide gate takes single-frame manoeuvres instead.
  double manoeuvre_acceleration_mm_s2 = 20000;
  double quiet_sojourn_s = 0.5;  // mean time in each model before switching
  double manoeuvre_sojourn_s = 0.3;
};

// Position then velocity [mm, mm/s] and their covariance.
struct KinematicState {
  Eigen::Matrix<double, 6, 1> x = Eigen::Matrix<double, 6, 1>::Zero();
  Eigen::Matrix<double, 6, 6> p = Eigen::Matrix<double, 6, 6>::Zero();
};

class MotionModel {
 public:
  // At rest at `position` with covariance `position_cov`, velocity unknown by `speed_sigma` a
  // component; the models' probabilities those of the chain's stationary state.
  MotionModel() = default;
  MotionModel(const MotionModelOptions& options, double time_s, const Eigen::Vector3d& position,
              const Eigen::Matrix3d& position_cov, double speed_sigma_mm_s);

  // Mixes the models and predicts each to `time_s` (not before the current time).
  void predict(double time_s, const MotionModelOptions& options);
  // The position measurement z with covariance r: each model updated, their probabilities by
  // their likelihoods.
  void correct(const Eigen::Vector3d& z, const Eigen::Matrix3d& r);
  // Adds the uncertainty of a white acceleration of `acceleration_sigma` held over `dt` to every
  // model: the state as if the marker had manoeuvred over that interval.
  void widen(double dt, double acceleration_sigma);

  // The moment-matched combination of the models: what gates, and what the track reports.
  const KinematicState& combined() const { return combined_; }
  double time_s() const { return time_s_; }
  double manoeuvre_probability() const { return probability_[1]; }

 private:
  void combine();

  std::array<KinematicState, 2> models_;
  std::array<double, 2> probability_{1.0, 0.0};
  KinematicState combined_;
  double time_s_ = 0;
  bool single_ = false;
};

}  // namespace syncap::tracking
