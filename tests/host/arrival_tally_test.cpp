#include "aggregator/arrival_tally.hpp"

#include <gtest/gtest.h>

namespace syncap::host {
namespace {

blob_frame_t record(int camera, int64_t frame, int16_t part_index = 0) {
  blob_frame_t f{};
  f.camera_id = static_cast<int16_t>(camera);
  f.frame_number = frame;
  f.part_index = part_index;
  f.part_count = 2;
  return f;
}

camera_status_t status(int camera, int8_t state, int64_t received, int64_t lost = 0) {
  camera_status_t s{};
  s.camera_id = static_cast<int16_t>(camera);
  s.state = state;
  s.frames_received = received;
  s.frames_lost = lost;
  return s;
}

TEST(ArrivalTally, CountsOneRecordPerFrameNotPerPart) {
  ArrivalTally tally;
  tally.add_record(record(5, 0, 0));
  tally.add_record(record(5, 0, 1));
  tally.add_record(record(5, 1, 0));
  tally.add_record(record(2, 1, 1));  // a part 1 whose part 0 was lost: no record
  EXPECT_EQ(tally.records_here(5), 2);
  EXPECT_EQ(tally.records_here(2), 0);
  EXPECT_EQ(tally.records_here(7), 0);
}

TEST(ArrivalTally, FinalStatusNamesTheRecordsLostOnTheWay) {
  ArrivalTally tally;
  for (int k = 0; k < 89; ++k) tally.add_record(record(5, k));
  tally.add_status(status(5, camera_status_t::STATE_STOPPED, 90));
  EXPECT_EQ(tally.lost_in_transit(5), 1);
  EXPECT_EQ(tally.summary(),
            "  camera 5 status: stopped, 90 frames received, 0 lost, 89 here "
            "(1 lost between edge and host)\n");
}

TEST(ArrivalTally, HeartbeatProvesNothingAndNothingLostIsNotSaid) {
  ArrivalTally tally;
  for (int k = 0; k < 3; ++k) tally.add_record(record(0, k));
  // A heartbeat sent before the records that followed: no loss can be told from it.
  tally.add_status(status(0, camera_status_t::STATE_ACQUIRING, 10));
  EXPECT_EQ(tally.lost_in_transit(0), std::nullopt);
  auto last = status(1, camera_status_t::STATE_STOPPED, 0, 4);
  last.message = "no exposure for frame 3";
  tally.add_status(last);
  EXPECT_EQ(tally.lost_in_transit(1), 0);
  EXPECT_EQ(tally.summary(),
            "  camera 0 status: acquiring, 10 frames received, 0 lost, 3 here\n"
            "  camera 1 status: stopped, 0 frames received, 4 lost, 0 here, "
            "note: no exposure for frame 3\n");
}

}  // namespace
}  // namespace syncap::host
