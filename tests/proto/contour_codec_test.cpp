#include "syncap/proto/contour_codec.hpp"

#include <gtest/gtest.h>

#include <random>

#include "syncap/proto/channels.hpp"

namespace syncap::proto {
namespace {

Contour square(int x0, int y0, int side, bool hole = false) {
  Contour c;
  c.hole = hole;
  for (int i = 0; i < side; ++i) c.points.push_back({x0 + i, y0});
  for (int i = 0; i < side; ++i) c.points.push_back({x0 + side, y0 + i});
  for (int i = 0; i < side; ++i) c.points.push_back({x0 + side - i, y0 + side});
  for (int i = 0; i < side; ++i) c.points.push_back({x0, y0 + side - i});
  return c;
}

// A closed-ish random walk with 8-neighbour steps: what a traced silhouette boundary looks like.
Contour random_walk(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> step(-1, 1);
  Contour c;
  ContourPoint p{640, 512};
  for (int i = 0; i < n; ++i) {
    c.points.push_back(p);
    p = {p.x + step(rng), p.y + step(rng)};
  }
  return c;
}

TEST(ContourCodec, SmallSilhouetteRoundTripsInOnePart) {
  const std::vector<Contour> contours{square(10, 20, 30), square(15, 25, 5, true)};
  const auto parts = encode_silhouette(4, 1234, 640, 480, contours);
  ASSERT_EQ(parts.size(), 1u);
  EXPECT_EQ(parts[0].num_pieces, 2);
  // 120 unit steps cost 2 bytes each: the codec is compact for traced outlines.
  EXPECT_LT(parts[0].data_size, 2 * 140 + 20);
  const Silhouette s = decode_silhouette(parts);
  EXPECT_EQ(s.camera_id, 4);
  EXPECT_EQ(s.frame_number, 1234);
  EXPECT_EQ(s.image_width, 640);
  EXPECT_EQ(s.contours, contours);
}

TEST(ContourCodec, EmptyFrameIsOneEmptyPart) {
  const auto parts = encode_silhouette(1, 2, 640, 480, {});
  ASSERT_EQ(parts.size(), 1u);
  EXPECT_EQ(parts[0].data_size, 0);
  EXPECT_TRUE(decode_silhouette(parts).contours.empty());
}

TEST(ContourCodec, LongContourSpansPartsThatEachFitTheBudget) {
  const std::vector<Contour> contours{random_walk(5000, 1), square(0, 0, 3, true),
                                      random_walk(2000, 2)};
  const auto parts = encode_silhouette(7, 99, 1280, 1024, contours);
  ASSERT_GE(parts.size(), 6u);
  for (const auto& part : parts) {
    EXPECT_LE(part.data_size, silhouette_part_t::MAX_DATA);
    EXPECT_LE(static_cast<std::size_t>(part.getEncodedSize()), kMaxEncodedSize);
    EXPECT_EQ(part.part_count, static_cast<int16_t>(parts.size()));
  }
  const Silhouette s = decode_silhouette(parts);
  EXPECT_EQ(s.contours, contours);
  EXPECT_EQ(s.parts_received, s.part_count);
}

TEST(ContourCodec, FarJumpsAndNegativeCoordinatesRoundTrip) {
  Contour c;
  c.points = {{-32768, 32767}, {32767, -32768}, {0, 0}, {-1, -1}, {1000, -2000}};
  const auto parts = encode_silhouette(0, 0, 100, 100, std::vector<Contour>{c});
  EXPECT_EQ(decode_silhouette(parts).contours.at(0), c);
}

TEST(ContourCodec, CoordinateOutsideInt16IsRejected) {
  Contour c;
  c.points = {{0, 0}, {40000, 0}};
  EXPECT_THROW(encode_silhouette(0, 0, 100, 100, std::vector<Contour>{c}), std::invalid_argument);
}

TEST(ContourCodec, LostMiddlePartKeepsEverythingElse) {
  const std::vector<Contour> contours{square(5, 5, 10), random_walk(3000, 3), square(1, 1, 4)};
  auto parts = encode_silhouette(2, 5, 640, 480, contours);
  ASSERT_GE(parts.size(), 3u);
  std::vector<silhouette_part_t> received(parts.begin(), parts.end());
  received.erase(received.begin() + 1);
  const Silhouette s = decode_silhouette(received);
  EXPECT_EQ(s.parts_received, static_cast<int>(parts.size()) - 1);
  ASSERT_GE(s.contours.size(), 3u);
  EXPECT_EQ(s.contours.front(), contours.front());
  EXPECT_FALSE(s.contours[1].complete);  // the walk lost its middle
  EXPECT_FALSE(s.contours[2].complete);  // its continuation after the gap
  EXPECT_EQ(s.contours.back(), contours.back());
}

TEST(ContourCodec, CorruptDataNamesCameraFramePartAndByte) {
  auto parts = encode_silhouette(3, 77, 640, 480, std::vector<Contour>{square(0, 0, 20)});
  parts[0].data.resize(parts[0].data.size() - 3);
  parts[0].data.back() = 0xff;  // a varint that never ends
  parts[0].data_size = static_cast<int16_t>(parts[0].data.size());
  try {
    decode_silhouette(parts);
    FAIL() << "corrupt data decoded";
  } catch (const ContourDecodeError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("camera 3 frame 77 part 0/1 byte"), std::string::npos) << what;
  }
}

TEST(ContourCodec, DataSizeMismatchIsAnError) {
  auto parts = encode_silhouette(3, 77, 640, 480, std::vector<Contour>{square(0, 0, 20)});
  parts[0].data_size = static_cast<int16_t>(parts[0].data_size + 1);
  EXPECT_THROW(decode_silhouette(parts), ContourDecodeError);
}

silhouette_part_t part_with_data(std::vector<uint8_t> data, int pieces) {
  silhouette_part_t part{};
  part.part_count = 1;
  part.num_pieces = static_cast<int16_t>(pieces);
  part.data_size = static_cast<int16_t>(data.size());
  part.data = std::move(data);
  return part;
}

// Found by the contour codec fuzz target (issue 15): the decoder added steps without a bound, so
// a step past INT32_MAX overflowed (undefined behaviour), and points outside the encoder's int16
// range decoded as if they were pixels.
TEST(ContourCodec, DecodedPointOutsideInt16IsAnError) {
  // One piece of two points: (32767, 0), then a step of (+1, 0) to 32768.
  const std::vector<uint8_t> past_int16{0x08, 0xfe, 0xff, 0x03, 0x00, 0x02, 0x00};
  EXPECT_THROW(decode_silhouette(std::vector{part_with_data(past_int16, 1)}), ContourDecodeError);
  // (INT32_MAX, 0), then (+1, 0): the sum overflowed int.
  const std::vector<uint8_t> past_int32{0x08, 0xfe, 0xff, 0xff, 0xff, 0x0f, 0x00, 0x02, 0x00};
  EXPECT_THROW(decode_silhouette(std::vector{part_with_data(past_int32, 1)}), ContourDecodeError);
  const std::vector<uint8_t> at_the_edge{0x08, 0xfd, 0xff, 0x03, 0x00, 0x01, 0x00};
  const auto decoded = decode_silhouette(std::vector{part_with_data(at_the_edge, 1)});
  EXPECT_EQ(decoded.contours.at(0).points.at(1), (ContourPoint{-32768, 0}));
}

}  // namespace
}  // namespace syncap::proto
