// The big-rig simulation (big_led_rig.hpp) at a size a test can afford: 10 of its cameras over
// 1500 frames, calibrated with every default of `syncap calibrate --led`. The minimum must be
// the truth's: focal lengths within 0.5 %, the centres after a similarity within 5 mm (0.25 %
// of the rig's radius), every blunder of 5-20 px gone, in a few rounds, and the sigmas must
// cover the errors (measured: centres 1.0 of their sigmas off, the camera constants 1.4 RMS).
// bench_calibrate_rig runs all 20 cameras and 5000 frames (scripts/bench.sh, calibrate-20cam).
#include <gtest/gtest.h>

#include <cmath>

#include "big_led_rig.hpp"
#include "calibration/calibrate.hpp"
#include "calibration/report.hpp"

namespace syncap::calibration {
namespace {

TEST(CalibrateBigRig, ReachesTheTruthsMinimumWithItsDefaults) {
  const test::BigLedRig rig = test::big_led_rig(10, 1500);
  CalibrationOptions options;
  options.wand.led = true;
  options.pixel_size_mm = test::kBigRigPixelMm;
  const CalibrationResult r = calibrate(rig.observations, options);
  ASSERT_TRUE(r.adjustment.converged);
  ASSERT_EQ(r.cameras.size(), rig.truth.size());
  const test::RigErrors e = test::rig_errors(rig, r);
  const double worst_focal = e.worst_focal, centres = e.centres, centre_sigma = e.centre_sigma;
  EXPECT_LT(worst_focal, 0.005);  // measured 0.28 %
  EXPECT_LT(centres, 5.0);        // mm; measured 2.4
  EXPECT_GE(static_cast<long>(r.adjustment.rejected.size()), rig.blunders);
  // Honest sigmas: the errors in units of their sigmas neither far above nor far below one.
  EXPECT_GT(centres / centre_sigma, 0.5);
  EXPECT_LT(centres / centre_sigma, 2.0);
  EXPECT_GT(e.focal_z_rms, 0.5);
  EXPECT_LT(e.focal_z_rms, 2.0);
  // Data snooping a point at a time: a few rounds, not one a blunder.
  EXPECT_LT(r.adjustment.adjustments, 15);
  EXPECT_LT(r.adjustment.adjustments, rig.blunders);
  EXPECT_NE(r.verdict, Verdict::kFailed);
  // Its report stays readable and small: one table of the cameras, one cell figure each.
  const std::string html = format_report_html(r.report);
  EXPECT_NE(html.find("<h2>Cameras</h2>"), std::string::npos);
  EXPECT_NE(html.find("Coverage and residuals by cell"), std::string::npos);
  EXPECT_LT(html.size(), 1000000u);
  RecordProperty("report_bytes", static_cast<int>(html.size()));
  RecordProperty("worst_focal_error", std::to_string(worst_focal));
  RecordProperty("centres_over_sigma", std::to_string(centres / centre_sigma));
  RecordProperty("focal_z_rms", std::to_string(e.focal_z_rms));
  RecordProperty("adjustments", r.adjustment.adjustments);
  RecordProperty("blunders", static_cast<int>(rig.blunders));
}

}  // namespace
}  // namespace syncap::calibration
