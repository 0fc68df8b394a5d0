// syncap-fakecam end to end, inside the private network namespace of hil/netns-run: the fake
// camera runs as a process on 127.0.0.x, an Aravis client opens it by address (never by
// discovery), and frames are triggered by syncap-trigger on a shared simulated GPIO chip, by the
// chip's C API, or by TriggerSoftware. The images encode their frame number, so each frame's
// number, trigger time and content are checked exactly; so is that nothing extra arrives.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "aravis_client.hpp"
#include "child_process.hpp"
#include "syncap/fakecam/frame_number.hpp"
#include "syncap/proto/channels.hpp"
#include "syncap/trigger/gpiosim.h"
#include "syncap/trigger_t.hpp"

#ifndef SYNCAP_FAKECAM_EXE
#error "SYNCAP_FAKECAM_EXE must be the path of syncap-fakecam"
#endif
#ifndef SYNCAP_TRIGGER_EXE
#error "SYNCAP_TRIGGER_EXE must be the path of syncap-trigger"
#endif

namespace syncap::test {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using fakecam::FrameNumberTracker;

constexpr int kWidth = 64;
constexpr int kHeight = 48;
constexpr int kFrameTimeoutMs = 3000;  // generous: frames normally follow their trigger in < 1 ms
constexpr int kQuietMs = 300;          // no frame this long after the last: nothing extra comes

// The pixels of image `frame`: its number in the first four pixels (little-endian), then a
// pattern that differs between neighbouring frames.
std::vector<std::uint8_t> image_pixels(std::uint64_t frame, int width, int height) {
  std::vector<std::uint8_t> pixels(static_cast<std::size_t>(width * height));
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      pixels[static_cast<std::size_t>(y * width + x)] =
          static_cast<std::uint8_t>(frame * 37 + x + 3 * y);
    }
  }
  for (int i = 0; i < 4; ++i)
    pixels[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(frame >> (8 * i));
  return pixels;
}

std::vector<std::uint8_t> crop(const std::vector<std::uint8_t>& pixels, int width,
                               const Region& r) {
  std::vector<std::uint8_t> out;
  for (int y = r.y; y < r.y + r.height; ++y) {
    const auto row = pixels.begin() + y * width;
    out.insert(out.end(), row + r.x, row + r.x + r.width);
  }
  return out;
}

// The rising edges a writer drives on a line, read back from the chip's history.
class ChipWatcher {
 public:
  ChipWatcher(const std::string& name, unsigned line) : line_(line) {
    chip_ = syncap_gpiosim_open(name.c_str(), true);
    syncap_gpiosim_line state{};
    if (chip_ != nullptr) syncap_gpiosim_read_line(chip_, line, &state);
    rise_ = {state.run, state.count, state.last_rise_ns};
  }
  ~ChipWatcher() { syncap_gpiosim_close(chip_); }
  ChipWatcher(const ChipWatcher&) = delete;
  ChipWatcher& operator=(const ChipWatcher&) = delete;

  bool ok() const { return chip_ != nullptr; }
  // The times of the edges since the watcher was made (or the last call), oldest first.
  std::vector<std::int64_t> edge_times() {
    std::vector<std::int64_t> times;
    while (syncap_gpiosim_wait_rising(chip_, line_, 0, &rise_) == 0) times.push_back(rise_.time_ns);
    return times;
  }

 private:
  syncap_gpiosim* chip_ = nullptr;
  unsigned line_;
  syncap_gpiosim_rise rise_{};
};

// Drives a line of the shared chip directly, as syncap-trigger would.
class ChipWriter {
 public:
  ChipWriter(const std::string& name, unsigned line) : line_(line) {
    chip_ = syncap_gpiosim_open(name.c_str(), true);
    if (chip_ != nullptr) syncap_gpiosim_claim_lines(chip_, &line_, 1);
  }
  ~ChipWriter() { syncap_gpiosim_close(chip_); }
  ChipWriter(const ChipWriter&) = delete;
  ChipWriter& operator=(const ChipWriter&) = delete;

  bool ok() const { return chip_ != nullptr; }
  // `count` pulses of 1 ms, one every period.
  void pulses(int count, std::chrono::milliseconds period) {
    for (int i = 0; i < count; ++i) {
      syncap_gpiosim_set_lines(chip_, &line_, 1, 1, nullptr);
      std::this_thread::sleep_for(1ms);
      syncap_gpiosim_set_lines(chip_, &line_, 1, 0, nullptr);
      std::this_thread::sleep_for(period - 1ms);
    }
  }

 private:
  syncap_gpiosim* chip_ = nullptr;
  unsigned line_;
};

// Collects syncap-trigger's messages on a thread of its own, so that none is lost while the test
// is busy with frames.
class TriggerLog {
 public:
  // A receive buffer of its own: on a loaded machine the default one overflowed before this
  // process read the burst of 100 trigger messages (58 arrived once in a full ctest -j2 run).
  TriggerLog() : lcm_(std::string(proto::kDefaultLcmUrl) + "&recv_buf_size=4194304") {
    lcm_.subscribe(proto::kTriggerChannel, &TriggerLog::on_trigger, this);
    thread_ = std::jthread([this](std::stop_token stop) {
      while (!stop.stop_requested()) lcm_.handleTimeout(20);
    });
  }
  bool good() { return lcm_.good(); }
  // The messages, once `count` arrived or the time ran out.
  std::vector<syncap::trigger_t> messages(std::size_t count, std::chrono::milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (size() < count && std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(10ms);
    }
    thread_.request_stop();
    thread_.join();
    return messages_;
  }

 private:
  void on_trigger(const lcm::ReceiveBuffer*, const std::string&, const syncap::trigger_t* message) {
    std::lock_guard lock(mutex_);
    messages_.push_back(*message);
  }
  std::size_t size() {
    std::lock_guard lock(mutex_);
    return messages_.size();
  }

  lcm::LCM lcm_;
  std::mutex mutex_;
  std::vector<syncap::trigger_t> messages_;
  std::jthread thread_;
};

class FakecamTest : public ::testing::Test {
 protected:
  void SetUp() override {
    static int serial = 0;
    const std::string tag = std::to_string(getpid()) + "-" + std::to_string(serial++);
    chip_ = "fakecam-test-" + tag;
    images_ = fs::temp_directory_path() / ("syncap-fakecam-test-" + tag);
    fs::remove_all(images_);
    fs::create_directories(images_);
    syncap_gpiosim_unlink(chip_.c_str());
  }
  void TearDown() override {
    fs::remove_all(images_);
    syncap_gpiosim_unlink(chip_.c_str());
  }

  void write_images(std::uint64_t first, std::uint64_t count, int width = kWidth,
                    int height = kHeight) {
    for (std::uint64_t frame = first; frame < first + count; ++frame) {
      std::vector<std::uint8_t> pixels = image_pixels(frame, width, height);
      const cv::Mat image(height, width, CV_8UC1, pixels.data());
      char name[32];
      std::snprintf(name, sizeof name, "frame_%06llu.pgm", static_cast<unsigned long long>(frame));
      ASSERT_TRUE(cv::imwrite((images_ / name).string(), image));
    }
  }

  // Starts syncap-fakecam and waits until it serves.
  std::unique_ptr<ChildProcess> start_fakecam(const std::string& address,
                                              std::vector<std::string> extra = {}) {
    std::vector<std::string> argv = {SYNCAP_FAKECAM_EXE, "--address", address, "--images",
                                     images_.string()};
    argv.insert(argv.end(), extra.begin(), extra.end());
    auto child = std::make_unique<ChildProcess>(argv);
    EXPECT_TRUE(child->wait_for_output("syncap-fakecam: serving", 10s)) << child->output();
    return child;
  }

  std::string gpiosim_trigger(unsigned line = 0) const {
    return "gpiosim:" + chip_ + ":" + std::to_string(line);
  }

  // Frames until `count` arrived or none came for kFrameTimeoutMs; then checks that no more come.
  static std::vector<ReceivedFrame> receive_frames(AravisClient& client, std::size_t count) {
    std::vector<ReceivedFrame> frames;
    while (frames.size() < count) {
      auto frame = client.receive(kFrameTimeoutMs);
      if (!frame) break;
      frames.push_back(std::move(*frame));
    }
    EXPECT_FALSE(client.receive(kQuietMs).has_value()) << "a frame more than the " << count;
    return frames;
  }

  // Checks one frame: complete, Mono8, the region, the frame number and the image content.
  static void expect_frame(const ReceivedFrame& frame, std::uint64_t frame_number,
                           FrameNumberTracker& tracker, const Region& region,
                           int image_width = kWidth, int image_height = kHeight) {
    SCOPED_TRACE("frame " + std::to_string(frame_number));
    EXPECT_EQ(frame.status, ARV_BUFFER_STATUS_SUCCESS);
    EXPECT_EQ(frame.pixel_format, ARV_PIXEL_FORMAT_MONO_8);
    EXPECT_EQ(tracker.next(frame.block_id), frame_number);
    EXPECT_EQ(frame.region.x, region.x);
    EXPECT_EQ(frame.region.y, region.y);
    EXPECT_EQ(frame.region.width, region.width);
    EXPECT_EQ(frame.region.height, region.height);
    EXPECT_EQ(frame.pixels,
              crop(image_pixels(frame_number, image_width, image_height), image_width, region));
  }

  std::string chip_;
  fs::path images_;
};

const Region kFull{0, 0, kWidth, kHeight};

// The key run: syncap-trigger fires 100 periods at 200 Hz on the shared chip; the fake camera
// sends exactly one frame per pulse, numbered like its trigger count, stamped with the pulse's
// edge time (the very time syncap-trigger publishes), showing the image of that number.
// syncap-trigger keeps its time grid: a period its thread wakes for too late is skipped, not
// driven late (its next message carries FLAG_MISSED and the period's number is never sent). On
// this 2-core machine in a full ctest that happens to 1-2 of 100 periods, so the pulses driven
// are the trigger's messages, and the test checks that skipped periods are few and flagged.
TEST_F(FakecamTest, TriggerRunDeliversEveryFrameOnceWithItsNumberTimeAndImage) {
  constexpr int kPeriods = 100;
  constexpr std::size_t kMinPulses = 90;
  write_images(0, kPeriods);
  auto fakecam = start_fakecam("127.0.0.2", {"--trigger", gpiosim_trigger()});
  ChipWatcher watcher(chip_, 0);
  ASSERT_TRUE(watcher.ok());
  auto client = std::make_unique<AravisClient>("127.0.0.2");
  client->start("Line0");
  EXPECT_EQ(client->string_feature("TriggerSource"), "Line0");
  TriggerLog log;
  ASSERT_TRUE(log.good());

  ChildProcess trigger({SYNCAP_TRIGGER_EXE, "--chip", "sim:" + chip_, "--count",
                        std::to_string(kPeriods), "--rate-hz", "200", "--lines", "0",
                        "--start-delay-ms", "100", "--lcm-url", proto::kDefaultLcmUrl});
  // Received while the trigger runs: the client has fewer buffers than the run has frames. With a
  // skipped period this waits one frame timeout for the frame that never comes.
  const std::vector<ReceivedFrame> frames = receive_frames(*client, kPeriods);
  EXPECT_EQ(trigger.wait(5s), 0) << trigger.output();
  const std::vector<syncap::trigger_t> messages = log.messages(kPeriods, 1s);

  const std::vector<std::int64_t> edges = watcher.edge_times();
  ASSERT_GE(messages.size(), kMinPulses) << trigger.output();
  ASSERT_EQ(edges.size(), messages.size());
  ASSERT_EQ(frames.size(), messages.size());
  EXPECT_EQ(messages.back().frame_number, kPeriods - 1);
  EXPECT_TRUE(messages.back().flags & syncap::trigger_t::FLAG_LAST);
  const std::string missed = std::to_string(kPeriods - messages.size());
  EXPECT_NE(trigger.output().find("pulses=" + std::to_string(messages.size()) + " "),
            std::string::npos)
      << trigger.output();
  EXPECT_NE(trigger.output().find("missed=" + missed), std::string::npos) << trigger.output();
  FrameNumberTracker tracker;
  std::int64_t previous_number = -1;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    expect_frame(frames[i], i, tracker, kFull);
    EXPECT_EQ(frames[i].timestamp_ns, static_cast<std::uint64_t>(edges[i])) << "frame " << i;
    EXPECT_EQ(messages[i].monotonic_ns, edges[i]) << "frame " << i;
    const bool skipped = messages[i].frame_number > previous_number + 1;
    EXPECT_GT(messages[i].frame_number, previous_number) << "pulse " << i;
    EXPECT_EQ(skipped, (messages[i].flags & syncap::trigger_t::FLAG_MISSED) != 0) << "pulse " << i;
    previous_number = messages[i].frame_number;
  }
  EXPECT_EQ(client->missing_frames(), 0u);
  client.reset();  // first: it releases the camera while the camera still answers
  EXPECT_EQ(fakecam->stop(SIGTERM), 0);
  const std::string sent = std::to_string(messages.size());
  EXPECT_NE(fakecam->output().find("triggers=" + sent + " sent=" + sent +
                                   " dropped=0 idle=0 no_image=0 missed=0 errors=0"),
            std::string::npos)
      << fakecam->output();
}

// Software trigger: one frame per TriggerSoftware, numbered from --start-frame.
TEST_F(FakecamTest, SoftwareTriggerDeliversOneFramePerTrigger) {
  constexpr int kTriggers = 20;
  write_images(10, kTriggers);
  auto fakecam = start_fakecam("127.0.0.2", {"--start-frame", "10"});
  auto client = std::make_unique<AravisClient>("127.0.0.2");
  client->start("Software");
  EXPECT_EQ(client->string_feature("TriggerSource"), "Software");
  FrameNumberTracker tracker(10);
  for (int i = 0; i < kTriggers; ++i) {
    const std::int64_t before_ns = monotonic_ns();
    client->software_trigger();
    const auto frame = client->receive(kFrameTimeoutMs);
    ASSERT_TRUE(frame) << "no frame for trigger " << i;
    expect_frame(*frame, 10 + static_cast<std::uint64_t>(i), tracker, kFull);
    EXPECT_GE(frame->timestamp_ns, static_cast<std::uint64_t>(before_ns));
    EXPECT_LE(frame->timestamp_ns, static_cast<std::uint64_t>(frame->arrival_ns));
  }
  EXPECT_FALSE(client->receive(kQuietMs).has_value()) << "a frame without a trigger";
  client.reset();  // first: it releases the camera while the camera still answers
  EXPECT_EQ(fakecam->stop(SIGINT), 0);
  EXPECT_NE(fakecam->output().find("triggers=20 sent=20 dropped=0"), std::string::npos)
      << fakecam->output();
}

// --loop: frames past the last image show the images again from the first, keeping their numbers.
TEST_F(FakecamTest, LoopServesTheImagesAgainPastTheLast) {
  write_images(10, 4);  // frames 10..13
  auto fakecam = start_fakecam("127.0.0.2", {"--start-frame", "10", "--loop"});
  AravisClient client("127.0.0.2");
  client.start("Software");
  FrameNumberTracker tracker(10);
  for (std::uint64_t f = 10; f < 20; ++f) {
    client.software_trigger();
    const auto frame = client.receive(kFrameTimeoutMs);
    ASSERT_TRUE(frame) << "no frame " << f;
    SCOPED_TRACE("frame " + std::to_string(f));
    EXPECT_EQ(tracker.next(frame->block_id), f);
    EXPECT_EQ(frame->pixels, image_pixels(10 + (f - 10) % 4, kWidth, kHeight));
  }
}

TEST_F(FakecamTest, RegionOfInterestIsACropOfTheImage) {
  write_images(0, 3);
  auto fakecam = start_fakecam("127.0.0.2");
  AravisClient client("127.0.0.2");
  const Region roi{8, 4, 32, 20};
  client.start("Software", roi);
  FrameNumberTracker tracker;
  for (std::uint64_t i = 0; i < 3; ++i) {
    client.software_trigger();
    const auto frame = client.receive(kFrameTimeoutMs);
    ASSERT_TRUE(frame);
    expect_frame(*frame, i, tracker, roi);
  }
}

// --drop 3,7: those frames are not sent, the others keep their numbers, Aravis sees the two gaps
// and the fake camera counts them.
TEST_F(FakecamTest, DroppedFramesAreMissingAndCounted) {
  write_images(0, 10);
  auto fakecam = start_fakecam("127.0.0.2", {"--trigger", gpiosim_trigger(), "--drop", "3,7"});
  auto client = std::make_unique<AravisClient>("127.0.0.2");
  client->start("Line0");
  ChipWriter writer(chip_, 0);
  ASSERT_TRUE(writer.ok());
  writer.pulses(10, 5ms);
  const std::vector<ReceivedFrame> frames = receive_frames(*client, 8);
  const std::vector<std::uint64_t> expected = {0, 1, 2, 4, 5, 6, 8, 9};
  ASSERT_EQ(frames.size(), expected.size());
  FrameNumberTracker tracker;
  for (std::size_t i = 0; i < frames.size(); ++i)
    expect_frame(frames[i], expected[i], tracker, kFull);
  EXPECT_EQ(client->missing_frames(), 2u);
  client.reset();  // first: it releases the camera while the camera still answers
  EXPECT_EQ(fakecam->stop(), 0);
  EXPECT_NE(fakecam->output().find("triggers=10 sent=8 dropped=2 idle=0"), std::string::npos)
      << fakecam->output();
}

// --delay-ms: frames arrive that much after their trigger and still carry the trigger's time.
TEST_F(FakecamTest, DelayedFramesKeepTheirTriggerTime) {
  write_images(0, 5);
  auto fakecam = start_fakecam("127.0.0.2", {"--trigger", gpiosim_trigger(), "--delay-ms", "40"});
  AravisClient client("127.0.0.2");
  client.start("Line0");
  ChipWatcher watcher(chip_, 0);
  ChipWriter writer(chip_, 0);
  writer.pulses(5, 10ms);
  const std::vector<ReceivedFrame> frames = receive_frames(client, 5);
  const std::vector<std::int64_t> edges = watcher.edge_times();
  ASSERT_EQ(frames.size(), 5u);
  ASSERT_EQ(edges.size(), 5u);
  FrameNumberTracker tracker;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    expect_frame(frames[i], i, tracker, kFull);
    EXPECT_EQ(frames[i].timestamp_ns, static_cast<std::uint64_t>(edges[i]));
    EXPECT_GE(frames[i].arrival_ns - edges[i], 40'000'000) << "frame " << i;
  }
}

// Pulses while the client does not acquire give no frame (idle); frame numbers beyond the images
// give none either (no_image); both are counted, and the numbering stays tied to the pulses.
TEST_F(FakecamTest, TriggersWithoutAcquisitionOrImageSendNothingAndAreCounted) {
  write_images(0, 5);
  auto fakecam = start_fakecam("127.0.0.2", {"--trigger", gpiosim_trigger()});
  auto client = std::make_unique<AravisClient>("127.0.0.2");
  ChipWriter writer(chip_, 0);
  writer.pulses(2, 5ms);
  client->start("Line0");
  writer.pulses(5, 5ms);
  const std::vector<ReceivedFrame> frames = receive_frames(*client, 3);
  ASSERT_EQ(frames.size(), 3u);
  FrameNumberTracker tracker(2);
  for (std::size_t i = 0; i < frames.size(); ++i) expect_frame(frames[i], 2 + i, tracker, kFull);
  client.reset();  // first: it releases the camera while the camera still answers
  EXPECT_EQ(fakecam->stop(), 0);
  EXPECT_NE(fakecam->output().find("triggers=7 sent=3 dropped=0 idle=2 no_image=2"),
            std::string::npos)
      << fakecam->output();
}

// Two cameras on one trigger line: both deliver every frame with the same number and time.
TEST_F(FakecamTest, TwoCamerasOnOneLineDeliverTheSameFrames) {
  write_images(0, 20);
  auto camera_a = start_fakecam("127.0.0.3", {"--trigger", gpiosim_trigger(2)});
  auto camera_b = start_fakecam("127.0.0.4", {"--trigger", gpiosim_trigger(2)});
  AravisClient client_a("127.0.0.3");
  AravisClient client_b("127.0.0.4");
  client_a.start("Line0");
  client_b.start("Line0");
  ChipWriter writer(chip_, 2);
  writer.pulses(20, 5ms);
  const auto frames_a = receive_frames(client_a, 20);
  const auto frames_b = receive_frames(client_b, 20);
  ASSERT_EQ(frames_a.size(), 20u);
  ASSERT_EQ(frames_b.size(), 20u);
  FrameNumberTracker tracker_a;
  FrameNumberTracker tracker_b;
  for (std::size_t i = 0; i < 20; ++i) {
    expect_frame(frames_a[i], i, tracker_a, kFull);
    expect_frame(frames_b[i], i, tracker_b, kFull);
    EXPECT_EQ(frames_a[i].timestamp_ns, frames_b[i].timestamp_ns);
  }
}

// VGA frames (228 packets each at the default packet size) at 100 Hz arrive complete: the
// camera paces them to its 1 Gbit/s link.
TEST_F(FakecamTest, LargeFramesArriveComplete) {
  constexpr int kFrames = 50;
  write_images(0, kFrames + 1, 640, 480);
  auto fakecam = start_fakecam("127.0.0.2", {"--trigger", gpiosim_trigger()});
  AravisClient client("127.0.0.2");
  client.start("Line0");
  ChipWriter writer(chip_, 0);
  // Aravis sets the stream's socket buffer (4 MiB) only when it reads the first frame's first
  // packet; until then the kernel's default (208 KiB, a third of this frame) holds the burst, and
  // a receiving thread that wakes a few ms late loses part of frame 0 (3 runs in 15 with three
  // busy loops on the two cores; none in 20 idle or beside one). That is the client's start, not
  // the camera: frame 0 is taken as it comes, and the frames under test follow it.
  writer.pulses(1, 10ms);
  ASSERT_TRUE(client.receive(kFrameTimeoutMs).has_value()) << "no frame 0";
  const std::uint64_t missing_at_start = client.missing_packets();
  // More frames than the client has buffers: they are taken while the pulses go on.
  std::jthread pulses([&writer] { writer.pulses(kFrames, 10ms); });
  const std::vector<ReceivedFrame> frames = receive_frames(client, kFrames);
  ASSERT_EQ(frames.size(), static_cast<std::size_t>(kFrames));
  FrameNumberTracker tracker(1);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    expect_frame(frames[i], i + 1, tracker, Region{0, 0, 640, 480}, 640, 480);
  }
  EXPECT_EQ(client.missing_packets(), missing_at_start);
}

// Bad input stops the camera before it serves, with exit status 1 and a message naming it.
TEST_F(FakecamTest, BadImageDirectoriesStopTheCameraNamingTheInput) {
  const auto run = [&](const std::string& expected) {
    ChildProcess fakecam(
        {SYNCAP_FAKECAM_EXE, "--address", "127.0.0.5", "--images", images_.string()});
    EXPECT_EQ(fakecam.wait(10s), 1) << fakecam.output();
    EXPECT_NE(fakecam.output().find(expected), std::string::npos)
        << "expected '" << expected << "' in:\n"
        << fakecam.output();
    EXPECT_EQ(fakecam.output().find("serving"), std::string::npos);
  };
  run("no images in " + images_.string());
  write_images(0, 2);
  std::ofstream(images_ / "frame_000002.pgm", std::ios::binary) << "P5\n64 48\n255\ntruncated";
  run("cannot decode " + (images_ / "frame_000002.pgm").string() +
      " (frame 2): unreadable or corrupt image");
  fs::remove(images_ / "frame_000002.pgm");
  write_images(2, 1, 32, 48);
  run((images_ / "frame_000002.pgm").string() + " (frame 2) is 32x48 but " +
      (images_ / "frame_000000.pgm").string() + " (frame 0) is 64x48");
  fs::remove_all(images_);
  run("image directory " + images_.string() + " does not exist");
}

}  // namespace
}  // namespace syncap::test
