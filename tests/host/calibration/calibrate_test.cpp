// The calibration pipeline on simulated observations (estimators::simulate_wand_network: Basler
// A620f-like cameras with the thesis' lens, 0.2 px noise): the spots of every image, with
// reflections that are not targets and lost targets, go through identification, the network
// start from the image size alone and the two-stage adjustment. The result must find the truth's
// interior orientation, geometry and wand, and data snooping the injected blunders.
#include "calibration/calibrate.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>
#include <set>

#include "estimators/bundle_adjustment_simulation.hpp"
#include "simulated_observations.hpp"

namespace syncap::calibration {
namespace {

CalibrationOptions wand_options() {
  CalibrationOptions o;
  o.wand.length_mm = 1000;
  o.wand.targets = 3;
  o.wand.middle_ratio = 0.4;
  o.pixel_size_mm = 0.0067;
  o.sigma_px = 0.2;
  return o;
}

TEST(Calibrate, WandAmongReflectionsFindsTheTruthFromTheImageSizeAlone) {
  estimators::WandSimulation sim;
  sim.frames = 120;
  const Simulated s = observe(sim, false, 0.3, 0.03);
  std::vector<std::string> progress;
  CalibrationOptions options = wand_options();
  options.progress = [&](const std::string& line) { progress.push_back(line); };
  const CalibrationResult r = calibrate(s.observations, options);

  ASSERT_TRUE(r.adjustment.converged);
  EXPECT_GE(progress.size(), 6u);
  long identified = 0;
  for (const auto& [camera, stats] : r.identification.cameras) identified += stats.identified;
  EXPECT_GT(identified, 3 * 120 * 8 / 10);  // reflections do not hide the wand
  // sigma0 near the simulated 0.2 px noise; the residuals are smaller by the redundancy share
  // (three rays a point: about sqrt(1/2)).
  EXPECT_NEAR(r.quality.sigma0_px, 0.2, 0.03);
  EXPECT_NEAR(r.quality.rms_px, 0.2 * std::sqrt(0.5), 0.03);
  EXPECT_EQ(r.quality.per_camera_rms_px.size(), 3u);
  ASSERT_TRUE(r.quality.wand_length_mean_mm.has_value());
  EXPECT_NEAR(*r.quality.wand_length_mean_mm, 1000.0, 0.5);
  EXPECT_LT(*r.quality.wand_length_sd_mm, 2.0);
  for (size_t i = 0; i < r.cameras.size(); ++i) {
    const auto& c = r.cameras[i];
    const auto& t = s.truth[i];
    ASSERT_EQ(c.id, t.id);
    EXPECT_NEAR(c.interior.c, t.interior.c, 0.02) << "camera " << c.id;  // from 7.4 mm at start
    EXPECT_NEAR(c.interior.xp, t.interior.xp, 0.05);
    // k1, k2, k3 correlate strongly (thesis Table 4.6): compare the radial correction itself,
    // where the wand was seen (the 2 m volume fills the middle third of the images, r < 2 mm).
    for (double radius : {0.5, 1.0, 1.5}) {
      const auto radial = [&](const sensor::InteriorOrientation& io) {
        const double r2 = radius * radius;
        return radius * r2 * (io.k1 + r2 * (io.k2 + r2 * io.k3));
      };
      EXPECT_NEAR(radial(c.interior), radial(t.interior), 0.3 * 0.0067)
          << "camera " << c.id << " at " << radius << " mm";
    }
    ASSERT_TRUE(c.std_devs.has_value());
    EXPECT_GT(c.std_devs->interior.c, 0.0);
  }
  // The geometry up to the datum: distances between the projection centres.
  for (size_t i = 0; i < 3; ++i) {
    const size_t j = (i + 1) % 3;
    const double estimated =
        (r.cameras[i].projection_centre() - r.cameras[j].projection_centre()).norm();
    const double truth = (s.truth[i].projection_centre() - s.truth[j].projection_centre()).norm();
    EXPECT_NEAR(estimated / truth, 1.0, 0.003);
  }
  // The levelled frame: the wand positions centred on the origin, the cameras upright (their
  // image-up axes along +Z on average), the first camera on -Y looking towards the origin.
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero(), up = Eigen::Vector3d::Zero();
  int points = 0;
  for (size_t p = 0; p < r.adjustment.points.size(); ++p) {
    if (!r.adjustment.points[p].adjusted) continue;
    centroid += Eigen::Vector3d(r.adjustment.points[p].xyz.data());
    ++points;
  }
  ASSERT_GT(points, 0);
  EXPECT_LT((centroid / points).norm(), 100.0)
      << "mm: the last adjustment shifts the frame a little";
  // The truth's vertical, carried into the result's frame by each camera's rotation.
  for (size_t i = 0; i < r.cameras.size(); ++i) {
    up += r.cameras[i].rotation() * s.truth[i].rotation().transpose() * Eigen::Vector3d::UnitZ();
  }
  EXPECT_GT(up.normalized().z(), 0.9995) << "the result's Z is the truth's vertical";
  EXPECT_NEAR(r.cameras[0].projection_centre().x(), 0.0, 50.0);
  EXPECT_LT(r.cameras[0].projection_centre().y(), -1000.0);
  // The report carries what the files need.
  EXPECT_EQ(r.report.cameras.size(), 3u);
  EXPECT_EQ(r.report.residuals.size(), r.network.measurements.size());
  EXPECT_EQ(r.report.tests.size(), 2u);
  EXPECT_FALSE(r.report.wand_lengths_mm.empty());
}

// Three cameras, two or three rays a point: a blunder on a three-ray point can lie along the
// epipolar line of one good ray, so that data snooping takes the good ray. Where the rejected
// ray then fits one kept ray about as well as the kept two fit each other, the point goes
// (estimators: reject_ambiguous_points). In frame 16 here no pair of rays shows the blunder
// grossly (it lies nearly along the epipolar lines of both good rays: cameras on an arc at one
// height): the test allows one such miss and names it.
TEST(Calibrate, LedModeFlagsTheInjectedBlunders) {
  estimators::WandSimulation sim;
  sim.frames = 150;
  sim.target_offsets_mm = {0.0};
  sim.blunder_fraction = 0.05;
  const Simulated s = observe(sim, false, 0.0, 0.0);
  ASSERT_GT(s.blunders.size(), 10u);
  CalibrationOptions options;
  options.wand.led = true;
  options.sigma_px = 0.2;
  const CalibrationResult r = calibrate(s.observations, options);
  ASSERT_TRUE(r.adjustment.converged);
  EXPECT_FALSE(r.quality.wand_length_mean_mm.has_value());
  size_t missed = 0;
  const std::set<int64_t> held_out(r.check_frames.begin(), r.check_frames.end());
  for (const auto& [frame, camera] : s.blunders) {
    if (held_out.count(frame)) continue;  // a check point, not adjusted
    const auto& indices = r.measurements_of_point.at("f" + std::to_string(frame));
    bool flagged = false;
    for (size_t m : indices) {
      if (r.network.measurements[m].station == "camera0" + std::to_string(camera)) {
        flagged = r.adjustment.measurements[m].status != estimators::MeasurementStatus::kAccepted;
      }
    }
    if (!flagged) {
      ++missed;
      std::cout << "  not flagged: blunder in frame " << frame << ", camera " << camera << "\n";
    }
  }
  EXPECT_LE(missed, 1u);
  // The removed: the blunders, a few good rays beyond the critical value, and the two other rays
  // of each point whose wrong ray could not be told (two here).
  long ambiguous = 0;
  for (const auto& rejection : r.adjustment.rejected) ambiguous += rejection.ambiguous;
  EXPECT_LE(ambiguous, 4);
  EXPECT_LE(r.quality.outliers_removed - ambiguous, static_cast<long>(s.blunders.size()) + 5);
  EXPECT_GT(r.quality.rms_px, 0.1);  // two or three rays a point: below the 0.2 px noise
  EXPECT_LT(r.quality.rms_px, 0.2);
  EXPECT_NEAR(r.quality.sigma0_px, 0.2, 0.03);
}

TEST(Calibrate, ErrorsNameTheCameraOrTheOption) {
  Observations obs;
  obs.source = "csv:x.csv";
  obs.image_sizes[0] = {640, 480};
  obs.frames[1][0] = {Spot{}};
  CalibrationOptions led;
  led.wand.led = true;
  try {
    calibrate(obs, led);
    FAIL();
  } catch (const CalibrationError& e) {
    EXPECT_STREQ(e.what(), "calibrate: csv:x.csv has 1 camera(s); a calibration needs at least 2");
  }
  obs.frames[1][3] = {Spot{}};
  try {
    calibrate(obs, led);
    FAIL();
  } catch (const CalibrationError& e) {
    EXPECT_STREQ(e.what(), "calibrate: camera 3 of csv:x.csv has no image size");
  }
  CalibrationOptions no_length;
  EXPECT_THROW(calibrate(obs, no_length), CalibrationError);
  CalibrationOptions one_sample = wand_options();
  one_sample.bootstrap_samples = 1;
  EXPECT_THROW(calibrate(obs, one_sample), CalibrationError);
}

bool says_weak(const CalibrationResult& r) {
  for (const std::string& m : r.report.messages) {
    if (m.rfind("weak network", 0) == 0) return true;
  }
  return false;
}

// Fewer than 40 wand positions adjusted: the report says the linearised sigmas may fall short and
// points to --bootstrap; not with 40 or more, nor when the bootstrap ran.
TEST(Calibrate, AWeakNetworkPointsToTheBootstrap) {
  estimators::WandSimulation sim;
  sim.frames = 20;
  const Simulated weak = observe(sim, false, 0.0, 0.0);
  CalibrationOptions options = wand_options();
  const CalibrationResult r = calibrate(weak.observations, options);
  ASSERT_TRUE(r.adjustment.converged);
  EXPECT_TRUE(says_weak(r));
  EXPECT_NE(format_report_text(r.report).find("note: weak network (20 wand positions)"),
            std::string::npos);
  options.bootstrap_samples = 3;
  EXPECT_FALSE(says_weak(calibrate(weak.observations, options)));
  sim.frames = 40;
  options.bootstrap_samples = 0;
  EXPECT_FALSE(says_weak(calibrate(observe(sim, false, 0.0, 0.0).observations, options)));
}

// --bootstrap: the report carries the bootstrap's interior sigmas beside the linearised ones;
// in this strong network (120 wand positions) they agree to the bootstrap's sampling error.
TEST(Calibrate, BootstrapSigmasBesideTheLinearisedOnes) {
  estimators::WandSimulation sim;
  sim.frames = 120;
  const Simulated s = observe(sim, false, 0.0, 0.0);
  CalibrationOptions options = wand_options();
  options.bootstrap_samples = 20;
  std::vector<std::string> progress;
  options.progress = [&](const std::string& line) { progress.push_back(line); };
  const CalibrationResult r = calibrate(s.observations, options);
  ASSERT_TRUE(r.adjustment.converged);
  EXPECT_EQ(r.report.bootstrap_samples, 20);
  EXPECT_NE(std::find_if(progress.begin(), progress.end(),
                         [](const std::string& line) {
                           return line.rfind("bootstrap: 20 converged", 0) == 0;
                         }),
            progress.end());
  EXPECT_EQ(progress.back(), "verdict: good");
  for (const ReportCamera& camera : r.report.cameras) {
    for (const ReportParameter& p : camera.parameters) {
      if (p.name == "c" || p.name == "xp" || p.name == "yp") {
        EXPECT_NEAR(p.bootstrap_sigma / p.sigma, 1.0, 0.5) << p.name;
      }
      if (p.mode == "fixed" || p.name == "X0") {
        EXPECT_EQ(p.bootstrap_sigma, 0.0) << p.name;  // held, or an exterior value
      }
    }
  }
  EXPECT_NE(format_report_text(r.report).find("(bootstrap +- "), std::string::npos);
}

}  // namespace
}  // namespace syncap::calibration
