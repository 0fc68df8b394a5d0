#include "sensor/v4l2/v4l2_source.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <ctime>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "fake_v4l2_device.hpp"

namespace syncap::edge::v4l2 {
namespace {

using testing::FakeV4l2Device;
using testing::ScriptedFrame;

V4l2Options small_options() {
  V4l2Options options;
  options.device_path = "/dev/video2";
  options.width = 8;
  options.height = 4;
  options.frame_timeout_ms = 200;
  return options;
}

// The Y value of pixel (x, y) in the test pattern.
uint8_t pattern(int x, int y, int salt) { return static_cast<uint8_t>(x * 17 + y * 29 + salt); }

// A YUYV buffer of the pattern, with `padding` bytes after every line.
std::vector<uint8_t> yuyv_image(int width, int height, int salt, int padding = 0) {
  std::vector<uint8_t> data;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      data.push_back(pattern(x, y, salt));
      data.push_back(x % 2 == 0 ? 90 : 200);  // U, V: must not leak into the grey image
    }
    data.insert(data.end(), static_cast<std::size_t>(padding), 0xEE);
  }
  return data;
}

cv::Mat pattern_image(int width, int height, int salt) {
  cv::Mat image(height, width, CV_8UC1);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) image.at<uint8_t>(y, x) = pattern(x, y, salt);
  return image;
}

// A scripted YUYV frame with sequence number `sequence`; the pattern's salt is the sequence.
ScriptedFrame yuyv_frame(uint32_t sequence, bool error = false) {
  ScriptedFrame frame;
  frame.sequence = sequence;
  frame.data = yuyv_image(8, 4, static_cast<int>(sequence));
  frame.error = error;
  frame.timestamp_us = 1'000'000 + sequence * 33'333;
  return frame;
}

ScriptedFrame failing_dqbuf(int error) {
  ScriptedFrame frame;
  frame.dqbuf_errno = error;
  return frame;
}

void expect_error(const std::function<void()>& action, const std::string& message) {
  try {
    action();
    ADD_FAILURE() << "no FrameSourceError, expected: " << message;
  } catch (const FrameSourceError& error) {
    EXPECT_EQ(error.what(), message);
  }
}

bool same(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0;
}

// ---- format negotiation ----

TEST(V4l2Source, PrefersGreyWhenTheDeviceHasIt) {
  auto fake = std::make_shared<FakeV4l2Device>();
  fake->formats = {V4L2_PIX_FMT_MJPEG, V4L2_PIX_FMT_YUYV, V4L2_PIX_FMT_GREY};
  V4l2Source source(small_options(), 1, fake);
  EXPECT_EQ(source.format(), PixelFormat::grey);
  EXPECT_EQ(fake->count("VIDIOC_S_FMT"), 1);
}

TEST(V4l2Source, FallsBackToYuyvBeforeMjpeg) {
  auto fake = std::make_shared<FakeV4l2Device>();
  fake->formats = {V4L2_PIX_FMT_MJPEG, V4L2_PIX_FMT_YUYV};
  V4l2Source source(small_options(), 1, fake);
  EXPECT_EQ(source.format(), PixelFormat::yuyv);
  EXPECT_EQ(fake->count("VIDIOC_S_FMT GREY"), 1);
  EXPECT_EQ(fake->count("VIDIOC_S_FMT YUYV"), 1);
  EXPECT_EQ(fake->count("VIDIOC_S_FMT MJPG"), 0);
  EXPECT_EQ(fake->count("VIDIOC_G_FMT"), 1);
}

TEST(V4l2Source, TakesMjpegLast) {
  auto fake = std::make_shared<FakeV4l2Device>();
  fake->formats = {V4L2_PIX_FMT_MJPEG};
  V4l2Source source(small_options(), 1, fake);
  EXPECT_EQ(source.format(), PixelFormat::mjpeg);
  EXPECT_EQ(fake->count("VIDIOC_S_FMT"), 3);
}

TEST(V4l2Source, ReportsTheSizeTheDriverChose) {
  auto fake = std::make_shared<FakeV4l2Device>();
  fake->max_width = 640;
  fake->max_height = 360;
  V4l2Options options = small_options();
  options.width = 1920;
  options.height = 1080;
  V4l2Source source(options, 1, fake);
  EXPECT_EQ(source.width(), 640);
  EXPECT_EQ(source.height(), 360);
  EXPECT_NE(source.describe().find("/dev/video2"), std::string::npos);
  EXPECT_NE(source.describe().find("YUYV 640x360"), std::string::npos);
}

TEST(V4l2Source, SetsTheFrameRateWhenTheDriverCan) {
  auto fake = std::make_shared<FakeV4l2Device>();
  V4l2Options options = small_options();
  options.fps = 60;
  V4l2Source source(options, 1, fake);
  EXPECT_EQ(fake->count("VIDIOC_S_PARM"), 1);
  EXPECT_DOUBLE_EQ(source.fps(), 60);
  EXPECT_NE(source.describe().find("@ 60 fps"), std::string::npos);
}

TEST(V4l2Source, RunsWithoutAFrameRateWhenTheDriverHasNone) {
  auto fake = std::make_shared<FakeV4l2Device>();
  fake->timeperframe = false;
  V4l2Options options = small_options();
  options.fps = 60;
  V4l2Source source(options, 1, fake);
  EXPECT_EQ(fake->count("VIDIOC_S_PARM"), 0);
  EXPECT_EQ(source.fps(), 0);
}

// ---- pixel conversion ----

TEST(V4l2ToGrey, TakesTheYOfYuyvSkippingLinePadding) {
  const std::vector<uint8_t> data = yuyv_image(6, 3, 5, 4);
  const cv::Mat grey = to_grey(PixelFormat::yuyv, data.data(), data.size(), 6, 3, 6 * 2 + 4);
  EXPECT_TRUE(same(grey, pattern_image(6, 3, 5)));
}

TEST(V4l2ToGrey, CopiesGreyRowsSkippingLinePadding) {
  std::vector<uint8_t> data;
  for (int y = 0; y < 3; ++y) {
    for (int x = 0; x < 5; ++x) data.push_back(pattern(x, y, 1));
    data.insert(data.end(), 3, 0xEE);
  }
  const cv::Mat grey = to_grey(PixelFormat::grey, data.data(), data.size(), 5, 3, 8);
  EXPECT_TRUE(same(grey, pattern_image(5, 3, 1)));
}

TEST(V4l2ToGrey, RefusesShortBuffers) {
  const std::vector<uint8_t> data = yuyv_image(6, 3, 5);
  EXPECT_TRUE(to_grey(PixelFormat::yuyv, data.data(), data.size() - 1, 6, 3, 12).empty());
  EXPECT_TRUE(to_grey(PixelFormat::grey, data.data(), 17, 6, 3, 6).empty());
}

TEST(V4l2Source, GrabsTheYPlaneOfYuyvWithPaddedLines) {
  auto fake = std::make_shared<FakeV4l2Device>();
  fake->line_padding = 8;
  ScriptedFrame frame = yuyv_frame(0);
  frame.data = yuyv_image(8, 4, 0, 8);
  fake->script.push_back(frame);
  V4l2Source source(small_options(), 1, fake);
  const auto grabbed = source.grab(0);
  ASSERT_TRUE(grabbed);
  EXPECT_TRUE(same(grabbed->image, pattern_image(8, 4, 0)));
}

TEST(V4l2Source, DecodesMjpegToGrey) {
  auto fake = std::make_shared<FakeV4l2Device>();
  fake->formats = {V4L2_PIX_FMT_MJPEG};
  V4l2Options options = small_options();
  options.width = 32;
  options.height = 16;
  cv::Mat image(16, 32, CV_8UC1);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 32; ++x) image.at<uint8_t>(y, x) = static_cast<uint8_t>(x * 4 + y * 2);
  ScriptedFrame frame;
  ASSERT_TRUE(cv::imencode(".jpg", image, frame.data, {cv::IMWRITE_JPEG_QUALITY, 100}));
  fake->script.push_back(frame);
  ScriptedFrame corrupt;
  corrupt.sequence = 1;
  corrupt.data = {0xFF, 0xD8, 0x00, 0x01, 0x02};
  fake->script.push_back(corrupt);
  V4l2Source source(options, 1, fake);
  const auto grabbed = source.grab(0);
  ASSERT_TRUE(grabbed);
  ASSERT_EQ(grabbed->image.size(), image.size());
  ASSERT_EQ(grabbed->image.type(), CV_8UC1);
  EXPECT_LE(cv::norm(grabbed->image, image, cv::NORM_INF), 4);  // JPEG is lossy
  EXPECT_FALSE(source.grab(1));  // a JPEG that does not decode counts incomplete
  EXPECT_EQ(source.frames_incomplete(), 1);
}

// ---- frame numbers ----

TEST(V4l2SequenceMapper, NumbersFromTheFirstSequenceAndCountsGaps) {
  SequenceMapper mapper(1000);
  EXPECT_EQ(mapper.next(57), 1000);
  EXPECT_EQ(mapper.next(58), 1001);
  EXPECT_EQ(mapper.next(61), 1004);
  EXPECT_EQ(mapper.lost(), 2);
}

TEST(V4l2SequenceMapper, UnwrapsThe32BitSequence) {
  SequenceMapper mapper;
  EXPECT_EQ(mapper.next(0xFFFFFFFEu), 0);
  EXPECT_EQ(mapper.next(0xFFFFFFFFu), 1);
  EXPECT_EQ(mapper.next(0), 2);
  EXPECT_EQ(mapper.next(2), 4);
  EXPECT_EQ(mapper.lost(), 1);
}

TEST(V4l2SequenceMapper, NeverReusesANumberWhenTheDriverRepeats) {
  SequenceMapper mapper;
  EXPECT_EQ(mapper.next(5), 0);
  EXPECT_EQ(mapper.next(5), 1);
  EXPECT_EQ(mapper.lost(), 0);
}

TEST(V4l2Source, MapsSequenceNumbersWithGapsToFrameNumbers) {
  auto fake = std::make_shared<FakeV4l2Device>();
  for (uint32_t sequence : {7u, 8u, 10u, 11u}) fake->script.push_back(yuyv_frame(sequence));
  V4l2Options options = small_options();
  options.first_frame_number = 1000;
  options.exposure_us = 5000;
  V4l2Source source(options, 3, fake);
  auto frame = source.grab(1000);
  ASSERT_TRUE(frame);
  EXPECT_EQ(frame->frame_number, 1000);
  EXPECT_EQ(frame->camera_id, 3);
  EXPECT_EQ(frame->exposure_us, 5000);
  EXPECT_TRUE(same(frame->image, pattern_image(8, 4, 7)));
  frame = source.grab(1001);
  ASSERT_TRUE(frame);
  EXPECT_TRUE(same(frame->image, pattern_image(8, 4, 8)));
  EXPECT_FALSE(source.grab(1002));  // sequence 9 never came: 10 is kept for the next call
  EXPECT_EQ(source.frames_lost(), 1);
  frame = source.grab(1003);
  ASSERT_TRUE(frame);
  EXPECT_TRUE(same(frame->image, pattern_image(8, 4, 10)));
  frame = source.grab(1004);
  ASSERT_TRUE(frame);
  EXPECT_EQ(frame->frame_number, 1004);
  EXPECT_EQ(source.frames_stale(), 0);
}

TEST(V4l2Source, StampsFramesWithTheBuffersMonotonicTimestamp) {
  auto fake = std::make_shared<FakeV4l2Device>();
  fake->script.push_back(yuyv_frame(0));
  ScriptedFrame unknown_clock = yuyv_frame(1);
  unknown_clock.monotonic = false;
  fake->script.push_back(unknown_clock);
  V4l2Source source(small_options(), 1, fake);
  const auto frame = source.grab(0);
  ASSERT_TRUE(frame);
  EXPECT_EQ(frame->monotonic_ns, 1'000'000'000);
  timespec before{};
  clock_gettime(CLOCK_MONOTONIC, &before);
  const auto arrived = source.grab(1);  // no monotonic timestamp: the dequeue time
  ASSERT_TRUE(arrived);
  EXPECT_GE(arrived->monotonic_ns, before.tv_sec * 1'000'000'000LL + before.tv_nsec);
}

// ---- grab(k): stale, pending, incomplete ----

TEST(V4l2Source, DropsQueuedFramesBeforeTheOneAskedFor) {
  auto fake = std::make_shared<FakeV4l2Device>();
  for (uint32_t sequence : {0u, 1u, 2u}) fake->script.push_back(yuyv_frame(sequence));
  V4l2Source source(small_options(), 1, fake);
  const auto frame = source.grab(2);
  ASSERT_TRUE(frame);
  EXPECT_EQ(frame->frame_number, 2);
  EXPECT_EQ(source.frames_stale(), 2);
  EXPECT_EQ(fake->count("VIDIOC_QBUF"), 4 + 3);  // every buffer goes back to the driver
}

TEST(V4l2Source, KeepsALaterFrameForTheNextCall) {
  auto fake = std::make_shared<FakeV4l2Device>();
  fake->script.push_back(yuyv_frame(0));
  fake->script.push_back(yuyv_frame(3));
  V4l2Source source(small_options(), 1, fake);
  ASSERT_TRUE(source.grab(0));
  EXPECT_FALSE(source.grab(1));  // 3 came: 1 was lost
  EXPECT_FALSE(source.grab(2));  // still pending, 2 lost too
  const auto frame = source.grab(3);
  ASSERT_TRUE(frame);
  EXPECT_EQ(frame->frame_number, 3);
  EXPECT_EQ(source.frames_stale(), 0);
  EXPECT_EQ(source.frames_lost(), 2);
}

TEST(V4l2Source, APendingFrameOlderThanTheOneAskedForIsStale) {
  auto fake = std::make_shared<FakeV4l2Device>();
  fake->script.push_back(yuyv_frame(0));
  fake->script.push_back(yuyv_frame(2));
  fake->script.push_back(yuyv_frame(5));
  V4l2Source source(small_options(), 1, fake);
  ASSERT_TRUE(source.grab(0));
  EXPECT_FALSE(source.grab(1));  // 2 pending
  const auto frame = source.grab(5);
  ASSERT_TRUE(frame);
  EXPECT_EQ(frame->frame_number, 5);
  EXPECT_EQ(source.frames_stale(), 1);
}

TEST(V4l2Source, CountsErrorFlaggedBuffersIncompleteAndNeverReturnsThem) {
  auto fake = std::make_shared<FakeV4l2Device>();
  fake->script.push_back(yuyv_frame(0, true));  // before the one asked for: skipped
  fake->script.push_back(yuyv_frame(1, true));  // the one asked for: lost
  fake->script.push_back(yuyv_frame(2));
  V4l2Source source(small_options(), 1, fake);
  EXPECT_FALSE(source.grab(1));
  EXPECT_EQ(source.frames_incomplete(), 2);
  ASSERT_TRUE(source.grab(2));
  EXPECT_EQ(source.frames_stale(), 0);
}

TEST(V4l2Source, ReturnsNothingWhenNoFrameComesInTime) {
  auto fake = std::make_shared<FakeV4l2Device>();
  V4l2Source source(small_options(), 1, fake);
  EXPECT_FALSE(source.grab(0));
  EXPECT_GE(fake->count("poll"), 1);
}

// ---- errors name the device and the step ----

TEST(V4l2SourceErrors, DeviceBusyOnOpen) {
  auto fake = std::make_shared<FakeV4l2Device>();
  fake->open_errno = EBUSY;
  expect_error([&] { V4l2Source source(small_options(), 1, fake); },
               "/dev/video2: open: Device or resource busy");
}

TEST(V4l2SourceErrors, NotAV4l2Device) {
  auto fake = std::make_shared<FakeV4l2Device>();
  fake->fail_ioctl["VIDIOC_QUERYCAP"] = ENOTTY;
  expect_error([&] { V4l2Source source(small_options(), 1, fake); },
               "/dev/video2: VIDIOC_QUERYCAP: not a V4L2 device");
  EXPECT_EQ(fake->open_fds, 0);
}

TEST(V4l2SourceErrors, NoStreamingCapability) {
  auto fake = std::make_shared<FakeV4l2Device>();
  fake->capabilities = V4L2_CAP_VIDEO_CAPTURE | V4L2_CAP_READWRITE;
  expect_error([&] { V4l2Source source(small_options(), 1, fake); },
               "/dev/video2: VIDIOC_QUERYCAP: no streaming I/O (Fake Camera, driver fakevideo)");
  EXPECT_EQ(fake->open_fds, 0);
}

TEST(V4l2SourceErrors, NotACaptureDevice) {
  auto fake = std::make_shared<FakeV4l2Device>();
  fake->capabilities = V4L2_CAP_VIDEO_OUTPUT | V4L2_CAP_STREAMING;
  expect_error(
      [&] { V4l2Source source(small_options(), 1, fake); },
      "/dev/video2: VIDIOC_QUERYCAP: not a video capture device (Fake Camera, driver fakevideo)");
}

TEST(V4l2SourceErrors, NoFormatItCanUse) {
  auto fake = std::make_shared<FakeV4l2Device>();
  fake->formats = {V4L2_PIX_FMT_RGB24};
  expect_error([&] { V4l2Source source(small_options(), 1, fake); },
               "/dev/video2: VIDIOC_S_FMT: device supports none of GREY, YUYV, MJPG");
  EXPECT_EQ(fake->count("VIDIOC_S_FMT"), 3);
  EXPECT_EQ(fake->open_fds, 0);
}

TEST(V4l2SourceErrors, FormatBusy) {
  auto fake = std::make_shared<FakeV4l2Device>();
  fake->fail_ioctl["VIDIOC_S_FMT"] = EBUSY;
  expect_error([&] { V4l2Source source(small_options(), 1, fake); },
               "/dev/video2: VIDIOC_S_FMT: Device or resource busy");
}

TEST(V4l2SourceErrors, StreamOnFailsUnmapsAndCloses) {
  auto fake = std::make_shared<FakeV4l2Device>();
  fake->fail_ioctl["VIDIOC_STREAMON"] = ENOSPC;
  expect_error([&] { V4l2Source source(small_options(), 1, fake); },
               "/dev/video2: VIDIOC_STREAMON: No space left on device");
  EXPECT_EQ(fake->mapped, 0);
  EXPECT_EQ(fake->open_fds, 0);
  EXPECT_EQ(fake->count("VIDIOC_STREAMOFF"), 0);
}

TEST(V4l2SourceErrors, InputOutputErrorOnDequeue) {
  auto fake = std::make_shared<FakeV4l2Device>();
  fake->script.push_back(failing_dqbuf(EIO));
  V4l2Source source(small_options(), 1, fake);
  expect_error([&] { source.grab(0); }, "/dev/video2: VIDIOC_DQBUF: Input/output error");
}

TEST(V4l2SourceErrors, DeviceDisappears) {
  auto fake = std::make_shared<FakeV4l2Device>();
  fake->script.push_back(yuyv_frame(0));
  fake->script.push_back(failing_dqbuf(ENODEV));
  V4l2Source source(small_options(), 1, fake);
  ASSERT_TRUE(source.grab(0));
  expect_error([&] { source.grab(1); },
               "/dev/video2: VIDIOC_DQBUF: No such device (device disconnected)");
}

// ---- teardown ----

TEST(V4l2Source, DestructionStopsStreamingUnmapsAndCloses) {
  auto fake = std::make_shared<FakeV4l2Device>();
  V4l2Options options = small_options();
  options.buffers = 3;
  {
    V4l2Source source(options, 1, fake);
    EXPECT_TRUE(fake->streaming);
    EXPECT_EQ(fake->mapped, 3);
    fake->calls.clear();
  }
  const std::vector<std::string> expected = {"VIDIOC_STREAMOFF", "munmap 0",         "munmap 1",
                                             "munmap 2",         "VIDIOC_REQBUFS 0", "close"};
  EXPECT_EQ(fake->calls, expected);
  EXPECT_FALSE(fake->streaming);
  EXPECT_EQ(fake->mapped, 0);
  EXPECT_EQ(fake->open_fds, 0);
}

TEST(V4l2Source, StartsStreamingWithEveryBufferMappedAndQueued) {
  auto fake = std::make_shared<FakeV4l2Device>();
  fake->max_buffers = 2;
  V4l2Options options = small_options();
  options.buffers = 6;
  V4l2Source source(options, 1, fake);
  EXPECT_EQ(fake->count("VIDIOC_REQBUFS 6"), 1);
  EXPECT_EQ(fake->count("VIDIOC_QUERYBUF"), 2);
  EXPECT_EQ(fake->count("mmap"), 2);
  EXPECT_EQ(fake->count("VIDIOC_QBUF"), 2);
  EXPECT_EQ(fake->calls.back(), "VIDIOC_STREAMON");
}

}  // namespace
}  // namespace syncap::edge::v4l2
