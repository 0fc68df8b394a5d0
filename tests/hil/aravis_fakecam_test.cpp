// Aravis against its own GigE Vision fake camera, in one process, inside the private network
// namespace of hil/netns-run. The camera serves on 127.0.0.2 and is opened by address: no
// discovery, so nothing is ever broadcast.
//
// Frames are software-triggered one at a time and each is awaited before the next trigger, so no
// frame can be dropped for want of a buffer however slowly the test runs.
#include <gtest/gtest.h>

#include <arv.h>

#include <chrono>
#include <cstdint>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace {

constexpr const char* kCameraAddress = "127.0.0.2";
constexpr const char* kClientAddress = "127.0.0.1";
constexpr const char* kSilentAddress = "127.0.0.9";  // on lo in the namespace, nothing listens
constexpr int kFrames = 20;
constexpr int kBufferPool = 4;
// Generous: a frame normally arrives within one fake-camera period (tens of ms).
constexpr std::uint64_t kFrameTimeoutUs = 5'000'000;

template <class T>
struct GObjectUnref {
  void operator()(T* object) const { g_object_unref(object); }
};
template <class T>
using GPtr = std::unique_ptr<T, GObjectUnref<T>>;

// Owns a GError*; tests read message() only after a call has failed.
class Error {
 public:
  Error() = default;
  Error(const Error&) = delete;
  Error& operator=(const Error&) = delete;
  ~Error() { g_clear_error(&error_); }
  GError** out() {
    g_clear_error(&error_);
    return &error_;
  }
  explicit operator bool() const { return error_ != nullptr; }
  std::string message() const { return error_ ? error_->message : "no error"; }

 private:
  GError* error_ = nullptr;
};

GPtr<GInetAddress> inet_address(const char* text) {
  return GPtr<GInetAddress>(g_inet_address_new_from_string(text));
}

// Opens the GigE Vision device at `device_address` directly, without discovery.
GPtr<ArvDevice> open_gv_device(const char* device_address, Error& error) {
  const auto client = inet_address(kClientAddress);
  const auto device = inet_address(device_address);
  return GPtr<ArvDevice>(arv_gv_device_new(client.get(), device.get(), error.out()));
}

// GigE Vision block ids are 16-bit and skip 0 on wrapping; the fake camera starts near the wrap.
std::uint64_t next_frame_id(std::uint64_t id) { return id >= 0xffff ? 1 : id + 1; }

struct Region {
  int x = 0;
  int y = 0;
  int width = 0;
  int height = 0;
};

struct Frame {
  ArvBufferStatus status = ARV_BUFFER_STATUS_UNKNOWN;
  std::uint64_t frame_id = 0;
  Region region;
  std::size_t image_size = 0;
  ArvPixelFormat pixel_format = 0;
};

class FakeCameraTest : public ::testing::Test {
 protected:
  void SetUp() override {
    fake_.reset(arv_gv_fake_camera_new(kCameraAddress, "SYNCAP-FAKE-01"));
    ASSERT_TRUE(arv_gv_fake_camera_is_running(fake_.get())) << "fake camera on " << kCameraAddress;
    Error error;
    device_ = open_gv_device(kCameraAddress, error);
    ASSERT_TRUE(device_) << error.message();
    // Packet sockets see loopback traffic in both directions; plain UDP sockets are enough here.
    arv_gv_device_set_stream_options(ARV_GV_DEVICE(device_.get()),
                                     ARV_GV_STREAM_OPTION_PACKET_SOCKET_DISABLED);
    camera_.reset(arv_camera_new_with_device(device_.get(), error.out()));
    ASSERT_TRUE(camera_) << error.message();
  }

  void TearDown() override {
    if (stream_) {
      Error error;
      arv_camera_stop_acquisition(camera_.get(), error.out());
      EXPECT_FALSE(error) << "stopping acquisition: " << error.message();
    }
    stream_.reset();
    camera_.reset();
    device_.reset();
    fake_.reset();
  }

  // Mono8, the given region, software trigger; then a stream with a buffer pool, started.
  void start_acquisition(const Region& region) {
    Error error;
    arv_camera_set_pixel_format(camera_.get(), ARV_PIXEL_FORMAT_MONO_8, error.out());
    ASSERT_FALSE(error) << "pixel format: " << error.message();
    arv_camera_set_region(camera_.get(), region.x, region.y, region.width, region.height,
                          error.out());
    ASSERT_FALSE(error) << "region: " << error.message();
    arv_camera_set_acquisition_mode(camera_.get(), ARV_ACQUISITION_MODE_CONTINUOUS, error.out());
    ASSERT_FALSE(error) << "acquisition mode: " << error.message();
    arv_camera_set_trigger(camera_.get(), "Software", error.out());
    ASSERT_FALSE(error) << "software trigger: " << error.message();
    const guint payload = arv_camera_get_payload(camera_.get(), error.out());
    ASSERT_FALSE(error) << "payload: " << error.message();
    stream_.reset(arv_camera_create_stream(camera_.get(), nullptr, nullptr, error.out()));
    ASSERT_TRUE(stream_) << "stream: " << error.message();
    for (int i = 0; i < kBufferPool; ++i) {
      arv_stream_push_buffer(stream_.get(), arv_buffer_new_allocate(payload));
    }
    arv_camera_start_acquisition(camera_.get(), error.out());
    ASSERT_FALSE(error) << "start: " << error.message();
  }

  // Triggers one frame and waits for its buffer; nothing when none arrives in time.
  std::optional<Frame> trigger_and_receive() {
    Error error;
    arv_camera_software_trigger(camera_.get(), error.out());
    if (error) {
      ADD_FAILURE() << "software trigger: " << error.message();
      return std::nullopt;
    }
    ArvBuffer* buffer = arv_stream_timeout_pop_buffer(stream_.get(), kFrameTimeoutUs);
    if (buffer == nullptr) return std::nullopt;
    Frame frame{.status = arv_buffer_get_status(buffer),
                .frame_id = arv_buffer_get_frame_id(buffer),
                .region = {arv_buffer_get_image_x(buffer), arv_buffer_get_image_y(buffer),
                           arv_buffer_get_image_width(buffer), arv_buffer_get_image_height(buffer)},
                .image_size = 0,
                .pixel_format = arv_buffer_get_image_pixel_format(buffer)};
    arv_buffer_get_image_data(buffer, &frame.image_size);
    arv_stream_push_buffer(stream_.get(), buffer);
    return frame;
  }

  std::vector<Frame> receive_frames(int count) {
    std::vector<Frame> frames;
    for (int i = 0; i < count; ++i) {
      auto frame = trigger_and_receive();
      if (!frame) {
        ADD_FAILURE() << "no buffer within " << kFrameTimeoutUs / 1000 << " ms for frame " << i;
        break;
      }
      frames.push_back(*frame);
    }
    return frames;
  }

  GPtr<ArvGvFakeCamera> fake_;
  GPtr<ArvDevice> device_;
  GPtr<ArvCamera> camera_;
  GPtr<ArvStream> stream_;
};

TEST_F(FakeCameraTest, DeliversCompleteMono8FramesWithConsecutiveIds) {
  const Region full{0, 0, 320, 240};
  ASSERT_NO_FATAL_FAILURE(start_acquisition(full));

  const std::vector<Frame> frames = receive_frames(kFrames);

  ASSERT_EQ(frames.size(), static_cast<std::size_t>(kFrames));
  for (std::size_t i = 0; i < frames.size(); ++i) {
    SCOPED_TRACE("frame " + std::to_string(i));
    EXPECT_EQ(frames[i].status, ARV_BUFFER_STATUS_SUCCESS);
    EXPECT_EQ(frames[i].pixel_format, ARV_PIXEL_FORMAT_MONO_8);
    EXPECT_EQ(frames[i].region.width, full.width);
    EXPECT_EQ(frames[i].region.height, full.height);
    EXPECT_EQ(frames[i].image_size, static_cast<std::size_t>(full.width * full.height));
    if (i > 0) {
      EXPECT_EQ(frames[i].frame_id, next_frame_id(frames[i - 1].frame_id));
    }
  }
}

TEST_F(FakeCameraTest, HonoursTheRegionOfInterest) {
  const Region roi{32, 16, 128, 96};
  ASSERT_NO_FATAL_FAILURE(start_acquisition(roi));

  const std::vector<Frame> frames = receive_frames(3);

  ASSERT_EQ(frames.size(), 3u);
  for (const Frame& frame : frames) {
    EXPECT_EQ(frame.status, ARV_BUFFER_STATUS_SUCCESS);
    EXPECT_EQ(frame.region.x, roi.x);
    EXPECT_EQ(frame.region.y, roi.y);
    EXPECT_EQ(frame.region.width, roi.width);
    EXPECT_EQ(frame.region.height, roi.height);
    EXPECT_EQ(frame.image_size, static_cast<std::size_t>(roi.width * roi.height));
  }
}

struct OpenOutcome {
  bool opened = false;
  std::string error;
};

TEST(AravisOpenByAddress, FailsWithAClearErrorWhereNoCameraListens) {
  // Run on a detached thread so that a hang fails this test instead of blocking it.
  std::packaged_task<OpenOutcome()> open([] {
    Error error;
    const auto device = open_gv_device(kSilentAddress, error);
    return OpenOutcome{device != nullptr, error.message()};
  });
  auto outcome = open.get_future();
  const auto start = std::chrono::steady_clock::now();
  std::thread(std::move(open)).detach();

  // Aravis gives up after its GVCP retries (about 2.5 s in 0.8.26).
  ASSERT_EQ(outcome.wait_for(std::chrono::seconds(15)), std::future_status::ready)
      << "opening " << kSilentAddress << " hangs";
  const auto elapsed = std::chrono::steady_clock::now() - start;
  const OpenOutcome result = outcome.get();
  EXPECT_FALSE(result.opened);
  EXPECT_NE(result.error.find("timeout"), std::string::npos) << result.error;
  EXPECT_LT(elapsed, std::chrono::seconds(10));
}

}  // namespace
