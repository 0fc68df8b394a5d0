#include "grouping/arrival_tally.hpp"

#include <gtest/gtest.h>

namespace syncap::grouping {
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
  tally.add_status(status(5, camera_status_t::STATE_ACQUIRING, 0));  // the edge's first status
  for (int k = 0; k < 90; ++k) {
    if (k != 17) tally.add_record(record(5, k));
  }
  EXPECT_EQ(tally.lost_in_transit(5), std::nullopt);  // a heartbeat proves nothing
  tally.add_status(status(5, camera_status_t::STATE_ACQUIRING, 60));
  EXPECT_EQ(tally.lost_in_transit(5), std::nullopt);
  tally.add_status(status(5, camera_status_t::STATE_STOPPED, 90));
  EXPECT_EQ(tally.lost_in_transit(5), 1);
  EXPECT_EQ(tally.summary(),
            "  camera 5 status: stopped, 90 frames received, 0 lost, 89 here "
            "(1 lost between edge and host)\n");
}

TEST(ArrivalTally, AHostStartedLateCountsFromTheFirstStatusItSaw) {
  ArrivalTally tally;
  // The edge ran long before: records of frames it processed then arrive first (or never).
  tally.add_record(record(2, 4000));
  tally.add_status(status(2, camera_status_t::STATE_ACQUIRING, 4001));
  for (int k = 4001; k < 4100; ++k) tally.add_record(record(2, k));
  tally.add_status(status(2, camera_status_t::STATE_STOPPED, 4100));
  EXPECT_EQ(tally.lost_in_transit(2), 0);
  EXPECT_EQ(tally.summary(),
            "  camera 2 status: stopped, 4100 frames received, 0 lost, 100 here\n");
}

TEST(ArrivalTally, AnEdgeThatRestartedStartsANewBaseline) {
  ArrivalTally tally;
  tally.add_status(status(1, camera_status_t::STATE_ACQUIRING, 0));
  for (int k = 0; k < 50; ++k) tally.add_record(record(1, k));
  tally.add_status(status(1, camera_status_t::STATE_ACQUIRING, 50));
  // Restarted: its count starts again at 0; the records of the run before count for nothing.
  tally.add_status(status(1, camera_status_t::STATE_ACQUIRING, 0));
  for (int k = 60; k < 80; k += 2) tally.add_record(record(1, k));
  tally.add_status(status(1, camera_status_t::STATE_STOPPED, 20));
  EXPECT_EQ(tally.lost_in_transit(1), 10);
}

TEST(ArrivalTally, NothingLostIsNotSaid) {
  ArrivalTally tally;
  for (int k = 0; k < 3; ++k) tally.add_record(record(0, k));
  tally.add_status(status(0, camera_status_t::STATE_ACQUIRING, 10));
  EXPECT_EQ(tally.lost_in_transit(0), std::nullopt);
  auto last = status(1, camera_status_t::STATE_STOPPED, 0, 4);
  last.message = "no exposure for frame 3";
  tally.add_status(last);
  EXPECT_EQ(tally.lost_in_transit(1), 0);
  tally.add_record(record(7, 0));  // a camera that never sent a status has no line
  EXPECT_EQ(tally.summary(),
            "  camera 0 status: acquiring, 10 frames received, 0 lost, 3 here\n"
            "  camera 1 status: stopped, 0 frames received, 4 lost, 0 here, "
            "note: no exposure for frame 3\n");
}

}  // namespace
}  // namespace syncap::grouping
