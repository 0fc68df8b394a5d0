// The offline replay's silhouette gap (syncap fit --leave-out-silhouettes): which events it
// leaves out, and its option's errors.
#include "log_feed.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "malformed_messages.hpp"
#include "syncap/silhouette_part_t.hpp"

namespace syncap::tools {
namespace {

io::LogEvent silhouette_event(const std::string& channel, int camera, std::int64_t frame) {
  silhouette_part_t part{};
  part.camera_id = static_cast<std::int16_t>(camera);
  part.frame_number = frame;
  part.part_count = 1;
  io::LogEvent e;
  e.channel = channel;
  e.data = test::encoded(part);
  return e;
}

TEST(SilhouetteGap, LeavesOutOnlyThatCamerasSilhouettesInTheRange) {
  const SilhouetteGap gap = SilhouetteGap::parse("2:100:129");
  EXPECT_EQ(gap.camera, 2);
  EXPECT_EQ(gap.first, 100);
  EXPECT_EQ(gap.last, 129);
  EXPECT_TRUE(gap.leaves_out(silhouette_event("SYNCAP_SIL_02", 2, 100)));
  EXPECT_TRUE(gap.leaves_out(silhouette_event("SYNCAP_SIL_02", 2, 129)));
  EXPECT_FALSE(gap.leaves_out(silhouette_event("SYNCAP_SIL_02", 2, 99)));
  EXPECT_FALSE(gap.leaves_out(silhouette_event("SYNCAP_SIL_02", 2, 130)));
  EXPECT_FALSE(gap.leaves_out(silhouette_event("SYNCAP_SIL_03", 3, 110))) << "another camera";
  io::LogEvent blobs = silhouette_event("SYNCAP_BLOBS_02", 2, 110);
  EXPECT_FALSE(gap.leaves_out(blobs)) << "the camera's blobs stay";
  io::LogEvent garbage = silhouette_event("SYNCAP_SIL_02", 2, 110);
  garbage.data.resize(3);
  EXPECT_FALSE(gap.leaves_out(garbage)) << "undecodable: fed, and counted as rejected there";
}

TEST(SilhouetteGap, ABadRangeIsNamed) {
  for (const char* text : {"2:130:100", "2:100", "x:1:2", "2:1:2:3", "100:1:2", "-1:1:2", ""}) {
    try {
      SilhouetteGap::parse(text);
      ADD_FAILURE() << "'" << text << "' was taken";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("CAMERA:FIRST:LAST"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace syncap::tools
