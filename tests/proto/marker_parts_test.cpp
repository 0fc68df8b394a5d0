#include "syncap/proto/marker_parts.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include "syncap/proto/channels.hpp"

namespace syncap::proto {
namespace {

marker_frame_t frame_with(int markers) {
  marker_frame_t f{};
  f.frame_number = 77;
  f.cameras = 8;
  for (int i = 0; i < markers; ++i) {
    marker_t m{};
    m.id = i;
    m.x = static_cast<float>(i);
    f.markers.push_back(m);
  }
  return f;
}

TEST(MarkerParts, EveryPartFitsOneDatagramAndCarriesTheHeader) {
  const auto parts = split_marker_frame(frame_with(100));
  ASSERT_EQ(parts.size(), 3u);  // 38 + 38 + 24
  for (std::size_t i = 0; i < parts.size(); ++i) {
    EXPECT_EQ(parts[i].part_index, static_cast<int16_t>(i));
    EXPECT_EQ(parts[i].part_count, 3);
    EXPECT_EQ(parts[i].total_markers, 100);
    EXPECT_EQ(parts[i].frame_number, 77);
    EXPECT_LE(static_cast<std::size_t>(parts[i].getEncodedSize()) + 8, kMaxEncodedSize);
  }
  EXPECT_EQ(parts[2].num_markers, 24);
}

TEST(MarkerParts, NoMarkersIsOnePartAndPartsJoinInOrderWhateverTheirArrival) {
  EXPECT_EQ(split_marker_frame(frame_with(0)).size(), 1u);
  auto parts = split_marker_frame(frame_with(70));  // 38 + 32
  std::reverse(parts.begin(), parts.end());
  const marker_frame_t whole = join_marker_parts(parts);
  ASSERT_EQ(whole.num_markers, 70);
  for (int i = 0; i < 70; ++i) EXPECT_EQ(whole.markers[static_cast<std::size_t>(i)].id, i);
  EXPECT_EQ(whole.part_count, 1);
  // A lost part loses its markers only; total_markers shows the loss.
  parts.erase(parts.begin());  // the second part, 32 markers
  EXPECT_EQ(join_marker_parts(parts).num_markers, 38);
  EXPECT_EQ(join_marker_parts(parts).total_markers, 70);
}

}  // namespace
}  // namespace syncap::proto
