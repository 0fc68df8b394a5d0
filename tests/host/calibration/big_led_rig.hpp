// A simulated big LED rig of the kind issue 37 names (a Braid/flydra insect or mocap arena):
// 20 cameras of 1920x1200 px (5.86 um pixels, c ~ 2600 px, barrel lenses of k1 ~ 0.33 on
// coordinates normalised by c), two rings of ten round a 1.0 x 1.0 x 0.6 m volume, one LED on a
// smooth random path through it, each camera seeing it in stretches (hidden for a mean 150
// frames after a mean 300 seen: the body of the arena, the LED's own angle), frames seen by fewer
// than 3 cameras left out as a detector would find nothing useful; centroids with noise of
// 0.1-0.3 px (per camera) plus a systematic bias that grows over the image to 0.15 px, and a
// few blunders of 5-20 px. The truth comes with it. Used by the calibration's test of the big
// rig and by bench_calibrate_rig.
#pragma once

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "calibration/calibrate.hpp"
#include "calibration/halves.hpp"
#include "calibration/observations.hpp"
#include "sensor/camera_model.hpp"
#include "sensor/test_cameras.hpp"

namespace syncap::calibration::test {

inline constexpr double kBigRigPixelMm = 0.00586;

struct BigLedRig {
  Observations observations;
  std::vector<sensor::CameraModel> truth;
  long blunders = 0;
};

inline std::vector<sensor::CameraModel> big_rig_cameras(int cameras, std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<sensor::CameraModel> out;
  for (int i = 0; i < cameras; ++i) {
    const bool upper = i % 2 == 0;
    const double azimuth = 2.0 * M_PI * i / cameras + 0.05 * unit(rng);
    const double radius = 1900.0 + 150.0 * unit(rng);
    const Eigen::Vector3d centre(radius * std::cos(azimuth), radius * std::sin(azimuth),
                                 upper ? 900.0 : -250.0);
    sensor::CameraModel c;
    c.id = i + 1;
    c.sensor = {1920, 1200, kBigRigPixelMm, kBigRigPixelMm};
    const double focal_px = 2600.0 + 120.0 * unit(rng);
    c.interior.c = focal_px * kBigRigPixelMm;
    c.interior.xp = 8.0 * unit(rng) * kBigRigPixelMm;
    c.interior.yp = 8.0 * unit(rng) * kBigRigPixelMm;
    c.interior.k1 = (0.33 + 0.03 * unit(rng)) / std::pow(c.interior.c, 2);
    c.interior.k2 = 0.04 / std::pow(c.interior.c, 4);
    c.exterior = sensor::test::looking_at(centre, {60.0 * unit(rng), 60.0 * unit(rng), 250.0});
    out.push_back(c);
  }
  return out;
}

// The LED's path: a damped random walk kept inside the volume, ~0.5 m/s at 100 Hz.
inline std::vector<Eigen::Vector3d> big_rig_path(int frames, std::mt19937& rng) {
  std::normal_distribution<double> gauss(0.0, 1.0);
  const Eigen::Vector3d lo(-500, -500, 0), hi(500, 500, 600);
  Eigen::Vector3d p(0, 0, 300), v(0, 0, 0);
  std::vector<Eigen::Vector3d> path;
  for (int f = 0; f < frames; ++f) {
    v = 0.95 * v + Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng));
    p += v;
    for (int k = 0; k < 3; ++k) {
      if (p[k] < lo[k] || p[k] > hi[k]) {
        p[k] = std::clamp(p[k], lo[k], hi[k]);
        v[k] = -v[k];
      }
    }
    path.push_back(p);
  }
  return path;
}

inline BigLedRig big_led_rig(int cameras = 20, int frames = 5000, uint32_t seed = 37) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  BigLedRig rig;
  rig.truth = big_rig_cameras(cameras, rng);
  const std::vector<Eigen::Vector3d> path = big_rig_path(frames, rng);
  std::vector<double> noise_px, bias_sign;
  std::vector<bool> visible;
  for (const sensor::CameraModel& c : rig.truth) {
    rig.observations.image_sizes[c.id] = {c.sensor.width_px, c.sensor.height_px};
    noise_px.push_back(0.1 + 0.2 * unit(rng));
    bias_sign.push_back(unit(rng) < 0.5 ? -1.0 : 1.0);
    visible.push_back(unit(rng) < 0.67);
  }
  for (int f = 0; f < frames; ++f) {
    std::map<int, std::vector<Spot>> seen;
    for (std::size_t i = 0; i < rig.truth.size(); ++i) {
      // Stretches seen (mean 300 frames) and hidden (mean 150).
      if (unit(rng) < (visible[i] ? 1.0 / 300.0 : 1.0 / 150.0)) visible[i] = !visible[i];
      if (!visible[i]) continue;
      const sensor::CameraModel& c = rig.truth[i];
      const sensor::Projection q = c.project(path[static_cast<std::size_t>(f)]);
      if (!q.ok() || !c.contains(q.pixel)) continue;
      // The centroid's systematic error: outwards (or inwards) in proportion to the distance from
      // the image's centre, 0.15 px at the corners (a spot's asymmetric blur off axis).
      const Eigen::Vector2d from_centre(q.pixel.x() - 0.5 * c.sensor.width_px,
                                        q.pixel.y() - 0.5 * c.sensor.height_px);
      const Eigen::Vector2d bias = bias_sign[i] * 0.15 * from_centre / 1131.0;
      Spot s;
      s.x = q.pixel.x() + bias.x() + noise_px[i] * gauss(rng);
      s.y = q.pixel.y() + bias.y() + noise_px[i] * gauss(rng);
      s.area = 20;
      if (unit(rng) < 0.002) {
        const double size = 5.0 + 15.0 * unit(rng), angle = 2.0 * M_PI * unit(rng);
        s.x += size * std::cos(angle);
        s.y += size * std::sin(angle);
        ++rig.blunders;
      }
      seen[c.id].push_back(s);
    }
    if (seen.size() >= 3) rig.observations.frames[f] = std::move(seen);
  }
  rig.observations.source = "simulated big LED rig";
  return rig;
}

// How far a calibration of the rig is from its truth: the worst focal length's relative error,
// the centres' RMS distance after a similarity [mm] and the RMS of their 3-D sigmas.
struct RigErrors {
  double worst_focal = 0.0;
  double centres = 0.0;
  double centre_sigma = 0.0;
  double focal_z_rms = 0.0;  // RMS over the cameras of (c - true c) / sigma c
};

// The scale of the similarity that fits b's projection centres onto a's.
inline double similarity_scale(const std::vector<sensor::CameraModel>& a,
                               const std::vector<sensor::CameraModel>& b) {
  Eigen::Matrix3Xd pa(3, a.size()), pb(3, b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    pa.col(static_cast<Eigen::Index>(i)) = a[i].projection_centre();
    pb.col(static_cast<Eigen::Index>(i)) = b[i].projection_centre();
  }
  return std::cbrt(Eigen::umeyama(pb, pa, true).topLeftCorner<3, 3>().determinant());
}

inline RigErrors rig_errors(const BigLedRig& rig, const CalibrationResult& r) {
  RigErrors e;
  double sigma2 = 0.0;
  for (std::size_t i = 0; i < r.cameras.size(); ++i) {
    e.worst_focal =
        std::max(e.worst_focal, std::abs(r.cameras[i].interior.c / rig.truth[i].interior.c - 1.0));
    const double sc = r.cameras[i].std_devs ? r.cameras[i].std_devs->interior.c : 0.0;
    const double zc = (r.cameras[i].interior.c - rig.truth[i].interior.c) / std::max(sc, 1e-30);
    e.focal_z_rms += zc * zc / static_cast<double>(r.cameras.size());
    const auto& sx = r.adjustment.stations[i].exterior_sigma;
    sigma2 += sx[0] * sx[0] + sx[1] * sx[1] + sx[2] * sx[2];
  }
  e.focal_z_rms = std::sqrt(e.focal_z_rms);
  e.centres = centres_apart_mm(rig.truth, r.cameras);
  // The LED leaves the scale free: the sigmas are in the result's units, the errors in mm.
  e.centre_sigma =
      similarity_scale(rig.truth, r.cameras) *
      std::sqrt(sigma2 / static_cast<double>(std::max<std::size_t>(1, r.cameras.size())));
  return e;
}

}  // namespace syncap::calibration::test
