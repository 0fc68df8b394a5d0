#include "sensor/exposure_numbering.hpp"

#include <gtest/gtest.h>

namespace syncap::edge {
namespace {

constexpr int64_t kMs = 1'000'000;
constexpr int64_t kTolerance = kMs / 2;

// Pulses first..last at 100 Hz: frame f at f * 10 ms.
void note_pulses(ExposureNumbering& numbering, int64_t first, int64_t last) {
  for (int64_t f = first; f <= last; ++f) numbering.note_trigger(f, f * 10 * kMs);
}

TEST(ExposureNumbering, AnAcquisitionFromTheRunsStartNumbersByBlockId) {
  ExposureNumbering numbering(false, kTolerance);
  EXPECT_EQ(numbering.number(1, 0, 0), ExposureNumbering::numbered(0));
  EXPECT_EQ(numbering.number(2, 0, 0), ExposureNumbering::numbered(1));
  EXPECT_EQ(numbering.number(5, 0, 0), ExposureNumbering::numbered(4));  // 2 and 3 lost
}

// The edge reopened the camera while grabbing frame 100; the camera's first exposure after that
// was frame 105's (the reopen took four pulses). Its block id restarts at 1 (a real camera).
TEST(ExposureNumbering, AReopenedCameraIsNumberedByItsTimestamp) {
  ExposureNumbering numbering(true, kTolerance);
  note_pulses(numbering, 101, 106);
  EXPECT_EQ(numbering.number(1, 105 * 10 * kMs, 105 * 10 * kMs + 4 * kMs),
            ExposureNumbering::numbered(105));
  EXPECT_EQ(numbering.number(2, 106 * 10 * kMs, 0), ExposureNumbering::numbered(106));
  EXPECT_EQ(numbering.number(4, 0, 0), ExposureNumbering::numbered(108));  // block ids count on
}

// The fake cameras send block id = frame number + 1: the time still decides, not the block id.
TEST(ExposureNumbering, AReopenedFakeCameraKeepsItsTrueNumbers) {
  ExposureNumbering numbering(true, kTolerance);
  note_pulses(numbering, 101, 110);
  EXPECT_EQ(numbering.number(108, 107 * 10 * kMs, 107 * 10 * kMs + kMs),
            ExposureNumbering::numbered(107));
  EXPECT_EQ(numbering.number(109, 0, 0), ExposureNumbering::numbered(108));
}

// A camera whose clock is not the trigger's: the last pulse before the exposure arrived, once a
// later pulse shows that no nearer one is on its way.
TEST(ExposureNumbering, WithoutACommonClockTheArrivalDecidesOnceALaterPulseIsNoted) {
  ExposureNumbering numbering(true, kTolerance);
  const int64_t camera_clock = 987'654'321'000;  // its own, unrelated
  const int64_t arrival = 103 * 10 * kMs + 3 * kMs;
  note_pulses(numbering, 101, 103);
  EXPECT_EQ(numbering.number(1, camera_clock, arrival),
            ExposureNumbering::wait());  // 104 may come earlier
  note_pulses(numbering, 104, 104);
  EXPECT_EQ(numbering.number(1, camera_clock, arrival), ExposureNumbering::numbered(103));
  EXPECT_EQ(numbering.number(2, camera_clock, 0), ExposureNumbering::numbered(104));
}

// The edge's trigger messages can lag the camera: an exposure newer than every noted pulse waits.
TEST(ExposureNumbering, AnExposureAheadOfTheNotedPulsesWaitsForItsPulse) {
  ExposureNumbering numbering(true, kTolerance);
  note_pulses(numbering, 101, 102);
  const int64_t stamp = 104 * 10 * kMs;
  EXPECT_EQ(numbering.number(1, stamp, stamp + kMs), ExposureNumbering::wait());
  note_pulses(numbering, 103, 103);
  EXPECT_EQ(numbering.number(1, stamp, stamp + kMs), ExposureNumbering::wait());
  note_pulses(numbering, 104, 104);
  EXPECT_EQ(numbering.number(1, stamp, stamp + kMs), ExposureNumbering::numbered(104));
}

// The camera's clock is the trigger's, but the pulse of its first exposure never reached the edge:
// that exposure cannot be numbered; the next one can.
TEST(ExposureNumbering, AnExposureWhosePulseWasNotNotedIsDropped) {
  ExposureNumbering numbering(true, kTolerance);
  note_pulses(numbering, 101, 104);
  note_pulses(numbering, 106, 107);  // 105's message lost
  EXPECT_EQ(numbering.number(6, 105 * 10 * kMs, 105 * 10 * kMs + kMs), ExposureNumbering::drop());
  EXPECT_EQ(numbering.number(7, 106 * 10 * kMs, 106 * 10 * kMs + kMs),
            ExposureNumbering::numbered(106));
}

TEST(ExposureNumbering, AnExposureBeforeEveryNotedPulseIsDropped) {
  ExposureNumbering numbering(true, kTolerance);
  note_pulses(numbering, 101, 103);
  EXPECT_EQ(numbering.number(1, 987'654'321'000, 100 * 10 * kMs + kMs), ExposureNumbering::drop());
}

// A camera clock that only seems to be the trigger's (its timestamps a fraction of a second before
// the arrivals) and matches no pulse: after three dropped exposures the arrival decides.
TEST(ExposureNumbering, AClockThatOnlySeemsSharedFallsBackToTheArrival) {
  ExposureNumbering numbering(true, kTolerance);
  note_pulses(numbering, 101, 120);
  const int64_t skew = 500 * kMs + 3 * kMs;
  for (uint16_t block = 1; block <= 3; ++block) {
    const int64_t arrival = (104 + block) * 10 * kMs + 2 * kMs;
    EXPECT_EQ(numbering.number(block, arrival - skew, arrival), ExposureNumbering::drop());
  }
  const int64_t arrival = 108 * 10 * kMs + 2 * kMs;
  EXPECT_EQ(numbering.number(4, arrival - skew, arrival), ExposureNumbering::numbered(108));
}

TEST(ExposureNumbering, NothingNotedNothingNumbered) {
  ExposureNumbering numbering(true, kTolerance);
  EXPECT_EQ(numbering.number(1, 5 * kMs, 6 * kMs), ExposureNumbering::wait());
}

}  // namespace
}  // namespace syncap::edge
