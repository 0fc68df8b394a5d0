// The image patch codec: tiles within the budget, exact grey values where the person is, a lost
// or corrupt part losing only its own rows.
#include "syncap/proto/image_patch.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "syncap/proto/channels.hpp"

namespace syncap::proto {
namespace {

// A textured grey image (noise does not compress: the hard case) with an elliptic person.
struct Scene {
  cv::Mat image, mask;
};

Scene scene(cv::Size size, cv::Point centre, cv::Size axes) {
  Scene s;
  s.image.create(size, CV_8UC1);
  cv::RNG rng(7);
  rng.fill(s.image, cv::RNG::UNIFORM, 0, 256);
  s.mask = cv::Mat::zeros(size, CV_8UC1);
  cv::ellipse(s.mask, centre, axes, 0, 0, 360, 255, cv::FILLED);
  return s;
}

TEST(ImagePatch, PartsFitTheBudgetAndCarryTheExactGreyValues) {
  const Scene s = scene({640, 480}, {300, 250}, {60, 150});
  const auto parts = encode_image_patch(4, 77, s.image, s.mask);
  ASSERT_GT(parts.size(), 10u);
  for (const image_patch_t& p : parts) {
    EXPECT_LE(p.data_size, image_patch_t::MAX_DATA);
    EXPECT_EQ(p.part_count, static_cast<int>(parts.size()));
    EXPECT_EQ(p.camera_id, 4);
    EXPECT_EQ(p.frame_number, 77);
  }
  const ImagePatch patch = decode_image_patch(parts);
  EXPECT_TRUE(patch.complete());
  ASSERT_EQ(patch.image.size(), s.image.size());
  // Every foreground pixel, and those within the margin, arrive exactly.
  cv::Mat sent;
  cv::dilate(s.mask, sent, cv::getStructuringElement(cv::MORPH_ELLIPSE, {9, 9}));
  EXPECT_EQ(cv::countNonZero((patch.image != s.image) & sent), 0);
  EXPECT_EQ(cv::countNonZero(sent & ~patch.known), 0);
  // Far from the person nothing is known.
  EXPECT_EQ(patch.known.at<uchar>(10, 10), 0);
  EXPECT_EQ(patch.image.at<uchar>(10, 10), 0);
}

TEST(ImagePatch, AWindowOfTheSensorLandsAtItsSensorPosition) {
  const Scene s = scene({200, 300}, {100, 150}, {40, 100});
  const auto parts = encode_image_patch(1, 5, s.image, s.mask, {500, 200}, {1280, 1024});
  const ImagePatch patch = decode_image_patch(parts);
  ASSERT_EQ(patch.image.size(), cv::Size(1280, 1024));
  EXPECT_EQ(patch.image.at<uchar>(200 + 150, 500 + 100), s.image.at<uchar>(150, 100));
  EXPECT_EQ(patch.known.at<uchar>(150, 100), 0);
}

TEST(ImagePatch, AWideBoxIsCutIntoColumnsThatEachFit) {
  const Scene s = scene({2400, 200}, {1200, 100}, {1150, 80});
  const auto parts = encode_image_patch(2, 9, s.image, s.mask);
  bool right_column = false;
  for (const image_patch_t& p : parts) {
    EXPECT_LE(p.data_size, image_patch_t::MAX_DATA);
    right_column = right_column || p.tile_x >= kMaxTileWidth;
  }
  EXPECT_TRUE(right_column);
  EXPECT_TRUE(decode_image_patch(parts).complete());
}

TEST(ImagePatch, ALostPartLosesOnlyItsOwnRows) {
  const Scene s = scene({640, 480}, {300, 250}, {60, 150});
  auto parts = encode_image_patch(4, 77, s.image, s.mask);
  const image_patch_t lost = parts[parts.size() / 2];
  parts.erase(parts.begin() + static_cast<long>(parts.size() / 2));
  const ImagePatch patch = decode_image_patch(parts);
  EXPECT_FALSE(patch.complete());
  EXPECT_EQ(patch.parts_received, patch.part_count - 1);
  EXPECT_EQ(patch.known.at<uchar>(lost.tile_y, 300), 0);
  EXPECT_EQ(patch.image.at<uchar>(250 - 140, 300), s.image.at<uchar>(250 - 140, 300));
}

TEST(ImagePatch, ACorruptPartIsNamedAndTheOthersKept) {
  const Scene s = scene({640, 480}, {300, 250}, {60, 150});
  auto parts = encode_image_patch(4, 77, s.image, s.mask);
  parts[2].data.assign(parts[2].data.size(), 0x55);
  parts[3].tile_y = 470;  // its rows would run past the image's end
  parts[4].encoding = 9;
  const ImagePatch patch = decode_image_patch(parts);
  ASSERT_EQ(patch.errors.size(), 3u);
  EXPECT_NE(patch.errors[0].find("camera 4 frame 77 part 2/"), std::string::npos);
  EXPECT_NE(patch.errors[0].find("not an 8-bit grey PNG"), std::string::npos);
  EXPECT_NE(patch.errors[1].find("outside the 640x480 image"), std::string::npos);
  EXPECT_NE(patch.errors[2].find("unknown encoding 9"), std::string::npos);
  EXPECT_EQ(patch.parts_received, patch.part_count - 3);
}

// A forged PNG header must not make the host allocate what it announces.
TEST(ImagePatch, AForgedPngSizeIsRefusedBeforeDecoding) {
  const Scene s = scene({640, 480}, {300, 250}, {60, 150});
  auto parts = encode_image_patch(4, 77, s.image, s.mask);
  auto& width = parts[0].data;  // IHDR: width at bytes 16..19, big-endian
  width[16] = 0, width[17] = 0x01, width[18] = 0, width[19] = 0;  // 65536 pixels wide
  const ImagePatch patch = decode_image_patch(parts);
  ASSERT_EQ(patch.errors.size(), 1u);
  EXPECT_NE(patch.errors[0].find("a 65536x"), std::string::npos) << patch.errors[0];
  EXPECT_NE(patch.errors[0].find("outside the 640x480 image"), std::string::npos);
}

TEST(ImagePatch, NoForegroundNoParts) {
  const Scene s = scene({64, 48}, {30, 25}, {6, 15});
  EXPECT_TRUE(encode_image_patch(0, 1, s.image, cv::Mat::zeros(s.image.size(), CV_8UC1)).empty());
  EXPECT_THROW(encode_image_patch(0, 1, s.image, cv::Mat()), std::invalid_argument);
  const ImagePatch none = decode_image_patch({});
  EXPECT_TRUE(none.image.empty());
}

TEST(ImagePatch, AnImpossibleSensorSizeIsRefused) {
  const Scene s = scene({64, 48}, {30, 25}, {6, 15});
  auto parts = encode_image_patch(0, 1, s.image, s.mask);
  for (auto& p : parts) p.image_width = -3;
  const ImagePatch patch = decode_image_patch(parts);
  ASSERT_EQ(patch.errors.size(), 1u);
  EXPECT_NE(patch.errors[0].find("sensor size -3x48"), std::string::npos);
}

}  // namespace
}  // namespace syncap::proto
