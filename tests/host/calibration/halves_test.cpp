// The halves' disagreement beyond their own sigmas (calibration/halves.hpp, halves_excess): the
// variance it adds to the whole's values, zero where the halves agree within their sigmas.
#include <gtest/gtest.h>

#include <cmath>

#include "calibration/halves.hpp"

namespace syncap::calibration {
namespace {

// Three cameras on a line 1000 mm apart, c 5 mm with sigma 0.1 mm, centres with sigma 1 mm a
// coordinate.
std::vector<sensor::CameraModel> cameras(double c) {
  std::vector<sensor::CameraModel> out;
  for (int i = 0; i < 3; ++i) {
    sensor::CameraModel camera;
    camera.id = i;
    camera.interior.c = c;
    camera.exterior.X0 = 1000.0 * i;
    camera.exterior.Y0 = i == 1 ? 500.0 : 0.0;
    sensor::CameraStdDevs sigma;
    sigma.interior.c = 0.1;
    sigma.exterior.X0 = sigma.exterior.Y0 = sigma.exterior.Z0 = 1.0;
    camera.std_devs = sigma;
    out.push_back(camera);
  }
  return out;
}

HalvesAgreement halves(double c_a, double c_b) {
  HalvesAgreement h;
  h.compared = true;
  h.a = cameras(c_a);
  h.b = cameras(c_b);
  return h;
}

TEST(HalvesExcess, HalvesApartBeyondTheirSigmasAddTheRestAsVariance) {
  // 0.6 mm apart against sigmas of 0.1 each: tau^2 = (0.36 - 0.02) / 2, the whole carries half.
  const HalvesExcess e = halves_excess(halves(5.0, 5.6), cameras(5.3));
  ASSERT_EQ(e.interior_variance.size(), 3u);
  EXPECT_NEAR(e.interior_variance[0][sensor::InteriorBlock::kC], 0.085, 1e-12);
  EXPECT_EQ(e.interior_variance[0][sensor::InteriorBlock::kK1], 0.0);  // not estimated
  EXPECT_NEAR(e.centre_variance[1], 0.0, 1e-9);                        // the centres agree
}

TEST(HalvesExcess, HalvesWithinTheirSigmasAddNothing) {
  const HalvesExcess e = halves_excess(halves(5.0, 5.1), cameras(5.05));
  for (const auto& v : e.interior_variance) EXPECT_EQ(v[sensor::InteriorBlock::kC], 0.0);
}

TEST(HalvesExcess, ACentreApartAddsTheKindsShareInTheWholesUnits) {
  HalvesAgreement h = halves(5.0, 5.0);
  h.b[1].exterior.Y0 += 30.0;  // camera 1 moved 30 mm in the second half
  std::vector<sensor::CameraModel> twice = cameras(5.0);
  for (sensor::CameraModel& c : twice) c.exterior.X0 *= 2.0, c.exterior.Y0 *= 2.0;  // units: x2
  const HalvesExcess same = halves_excess(h, cameras(5.0));
  const HalvesExcess scaled = halves_excess(h, twice);
  ASSERT_EQ(same.centre_variance.size(), 3u);
  // One kind, one Birge ratio: every camera's centre carries the same share (equal sigmas).
  EXPECT_GT(same.centre_variance[0], 1.0);
  EXPECT_NEAR(same.centre_variance[1], same.centre_variance[0], 1e-9);
  EXPECT_NEAR(scaled.centre_variance[1], 4.0 * same.centre_variance[1], 1e-6);
  for (const auto& v : same.interior_variance) EXPECT_EQ(v[sensor::InteriorBlock::kC], 0.0);
}

TEST(HalvesExcess, OneChanceOutlierAmongAgreeingCamerasAddsNothing) {
  HalvesAgreement h = halves(5.0, 5.0);
  h.b[0].interior.c += 0.4;  // z 2.8 in one camera of three: below the 99 % bound of the kind
  EXPECT_EQ(halves_excess(h, cameras(5.0)).interior_variance[0][sensor::InteriorBlock::kC], 0.0);
}

TEST(HalvesExcess, NothingWithoutCompared) {
  HalvesAgreement h;
  EXPECT_TRUE(halves_excess(h, cameras(5.0)).interior_variance.empty());
}

}  // namespace
}  // namespace syncap::calibration
