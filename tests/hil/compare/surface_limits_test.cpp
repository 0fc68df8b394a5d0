// The surface check's pass limits (hil/compare/src/surface_limits.hpp): each limit missed is
// named with both numbers, none given passes everything, and a limit exactly met passes.
#include "surface_limits.hpp"

#include <gtest/gtest.h>

namespace syncap::compare {
namespace {

SurfaceErrors frame() {
  SurfaceErrors e;
  e.points = 200;
  e.blunders = 1;
  e.rms_normal_mm = 1.2;
  e.rms_normalised = 1.4;
  e.within_3_sigma = 0.95;
  e.sweep_rms_normal_mm = 6.0;
  return e;
}

SurfaceLimits bench() {
  SurfaceLimits l;
  l.max_rms_mm = 1.5;
  l.min_points = 100;
  l.max_blunder_fraction = 0.01;
  l.max_rms_error_over_sigma = 2.0;
  l.min_within_3_sigma = 0.9;
  l.min_gain_over_gc3 = 3.5;
  return l;
}

TEST(SurfaceLimits, AFrameWithinEveryLimitPasses) {
  EXPECT_TRUE(surface_failures(frame(), bench()).empty());
  EXPECT_TRUE(surface_failures(frame(), SurfaceLimits{}).empty());
  EXPECT_FALSE(SurfaceLimits{}.any());
  SurfaceLimits exact;
  exact.max_rms_mm = 1.2;
  exact.min_points = 200;
  EXPECT_TRUE(surface_failures(frame(), exact).empty());
}

TEST(SurfaceLimits, EachLimitMissedIsNamedWithItsNumbers) {
  SurfaceErrors e = frame();
  e.rms_normal_mm = 1.62;
  e.points = 80;
  e.blunders = 4;
  e.rms_normalised = 2.5;
  e.within_3_sigma = 0.85;
  e.sweep_rms_normal_mm = 3.0;
  const std::vector<std::string> failed = surface_failures(e, bench());
  ASSERT_EQ(failed.size(), 6u);
  EXPECT_EQ(failed[0], "RMS on the normal 1.620 mm > 1.5 mm");
  EXPECT_EQ(failed[1], "80 points < 100");
  EXPECT_EQ(failed[2], "blunders 5.00 % > 1.00 %");
  EXPECT_EQ(failed[3], "RMS error/sigma 2.50 > 2.00 (the sigmas are far from honest)");
  EXPECT_EQ(failed[4], "85.0 % within 3 sigma < 90.0 %");
  EXPECT_EQ(failed[5], "least squares 1.9x more precise than GC3 < 3.5x");
}

TEST(SurfaceLimits, NoPointsFailsTheLimitsThatNeedThem) {
  SurfaceErrors none;
  const std::vector<std::string> failed = surface_failures(none, bench());
  EXPECT_FALSE(failed.empty());
}

}  // namespace
}  // namespace syncap::compare
