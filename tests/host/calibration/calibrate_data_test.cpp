// `syncap calibrate`'s pipeline on real detections: the strawlab MultiCamSelfCal recordings
// (flydra, 752x480 cameras watching one moving bright point) in LED mode, from the image sizes
// alone. 300 frames evenly spread keep a run to seconds (the whole recordings take minutes of
// data snooping; `syncap calibrate --input mcsc:DIR --led` runs them whole).
#include <gtest/gtest.h>

#include <iostream>

#include "calibration/calibrate.hpp"
#include "syncap_test_data.hpp"

namespace syncap::calibration {
namespace {

constexpr double kMaxRmsPx = 0.25;

CalibrationOptions led_options() {
  CalibrationOptions o;
  o.wand.led = true;
  o.max_frames = 300;
  return o;
}

void expect_calibrated(const CalibrationResult& r, size_t cameras) {
  EXPECT_TRUE(r.adjustment.converged) << r.adjustment.termination;
  EXPECT_EQ(r.cameras.size(), cameras);
  EXPECT_LE(r.quality.rms_px, kMaxRmsPx);
  for (const auto& [id, rms] : r.quality.per_camera_rms_px) {
    EXPECT_LE(rms, 0.3) << "camera " << id;
  }
  // Data snooping removes some real outliers, never a large share.
  EXPECT_LT(r.quality.outliers_removed, r.quality.observations / 10);
  std::cout << "  " << r.report.input << ": sigma0 " << r.quality.sigma0_px << " px, RMS "
            << r.quality.rms_px << " px, " << r.quality.observations << " observations, "
            << r.quality.outliers_removed << " outliers removed\n";
}

TEST(CalibrateStrawlab, FourCamerasConvergeFromTheImageSizes) {
  SYNCAP_REQUIRE_DATA(dir, "calibration/strawlab-DATA20100906_134124");
  const CalibrationResult r = calibrate(read_mcsc_observations(dir), led_options());
  expect_calibrated(r, 4);
}

TEST(CalibrateStrawlab, ThreeCamerasConvergeFromTheImageSizes) {
  SYNCAP_REQUIRE_DATA(dir, "calibration/strawlab-DATA20090709_111010");
  const CalibrationResult r = calibrate(read_mcsc_observations(dir), led_options());
  expect_calibrated(r, 3);
}

}  // namespace
}  // namespace syncap::calibration
