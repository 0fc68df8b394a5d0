// The real lcm-logger records syncap messages published with lcm::LCM, and `syncap log` decodes
// its file. Runs inside the private network namespace of hil/netns-run, so the multicast stays
// on its loopback.
//
// No fixed sleeps: the test publishes probes until the logger has recorded one (it is then
// subscribed), and stops the logger only once the file holds every message.
#include <gtest/gtest.h>

#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "io/lcm_log_reader.hpp"
#include "syncap/blob_frame_t.hpp"
#include "syncap/camera_status_t.hpp"
#include "syncap/edge_command_t.hpp"
#include "syncap/proto/channels.hpp"
#include "syncap/silhouette_part_t.hpp"
#include "syncap/trigger_t.hpp"

extern char** environ;

namespace syncap {
namespace {

constexpr auto kWaitLimit = std::chrono::seconds(10);
constexpr auto kPollInterval = std::chrono::milliseconds(20);
constexpr const char* kProbeChannel = "SYNCAP_PROBE";
constexpr int kCamera = 3;

// Polls `done` until it holds or kWaitLimit has passed; `between` runs before every poll.
bool wait_until(const std::function<bool()>& done, const std::function<void()>& between = {}) {
  const auto deadline = std::chrono::steady_clock::now() + kWaitLimit;
  while (std::chrono::steady_clock::now() < deadline) {
    if (between) between();
    if (done()) return true;
    std::this_thread::sleep_for(kPollInterval);
  }
  return done();
}

// The lcm-logger process, recording the default syncap URL into `path`.
class LcmLogger {
 public:
  explicit LcmLogger(const std::filesystem::path& path) {
    std::vector<std::string> args{"lcm-logger",
                                  "--force",
                                  "--quiet",
                                  "--flush-interval=10",
                                  std::string("--lcm-url=") + proto::kDefaultLcmUrl,
                                  path.string()};
    std::vector<char*> argv;
    for (std::string& arg : args) argv.push_back(arg.data());
    argv.push_back(nullptr);
    if (posix_spawnp(&pid_, "lcm-logger", nullptr, nullptr, argv.data(), environ) != 0) pid_ = -1;
  }
  LcmLogger(const LcmLogger&) = delete;
  LcmLogger& operator=(const LcmLogger&) = delete;
  ~LcmLogger() {
    if (pid_ > 0) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
  }

  bool started() const { return pid_ > 0; }

  // Interrupts the logger as a user would; true when it ended within kWaitLimit.
  bool stop() {
    kill(pid_, SIGINT);
    const bool ended = wait_until([this] { return waitpid(pid_, nullptr, WNOHANG) == pid_; });
    if (ended) pid_ = -1;
    return ended;
  }

 private:
  pid_t pid_ = -1;
};

// The complete events in the log so far; a record the logger is still writing is left out.
std::vector<io::LogEvent> recorded_events(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  io::LcmLogReader reader(in);
  std::vector<io::LogEvent> events;
  while (auto event = reader.next()) events.push_back(std::move(*event));
  return events;
}

std::size_t count_recorded(const std::filesystem::path& path, bool probes) {
  std::size_t count = 0;
  for (const auto& event : recorded_events(path)) {
    if ((event.channel == kProbeChannel) == probes) ++count;
  }
  return count;
}

std::string recorded_channels(const std::filesystem::path& path) {
  std::string channels;
  for (const auto& event : recorded_events(path)) channels += event.channel + " ";
  return channels;
}

struct ToolRun {
  int status = -1;
  std::vector<nlohmann::json> lines;
};

// Runs the built `syncap log` on the file, leaving the probes out.
ToolRun run_syncap_log(const std::filesystem::path& path) {
  const std::string command =
      std::string(SYNCAP_TOOL_PATH) + " log " + path.string() + " --channel '(?!SYNCAP_PROBE).*'";
  ToolRun run;
  FILE* output = popen(command.c_str(), "r");
  if (output == nullptr) return run;
  std::string text;
  for (int c; (c = std::fgetc(output)) != EOF;) text += static_cast<char>(c);
  const int wait_status = pclose(output);
  run.status = WIFEXITED(wait_status) ? WEXITSTATUS(wait_status) : -1;
  std::size_t start = 0;
  for (std::size_t end; (end = text.find('\n', start)) != std::string::npos; start = end + 1) {
    run.lines.push_back(nlohmann::json::parse(text.substr(start, end - start)));
  }
  return run;
}

trigger_t make_trigger(std::int64_t frame_number) {
  trigger_t msg{};
  msg.frame_number = frame_number;
  msg.monotonic_ns = 5'000'000'000 + frame_number;
  msg.realtime_ns = 1'700'000'000'000'000'000;
  msg.rate_hz = 120.0;
  msg.pulse_width_us = 100;
  return msg;
}

blob_frame_t make_blob_frame() {
  blob_frame_t msg{};
  msg.camera_id = kCamera;
  msg.frame_number = 41;
  msg.image_width = 2048;
  msg.image_height = 1536;
  msg.part_count = 1;
  for (const float x : {100.5f, 200.25f}) {
    blob_t blob{};
    blob.x = x;
    blob.y = 50.0f;
    blob.area = 12.0f;
    msg.blobs.push_back(blob);
  }
  msg.num_blobs = static_cast<std::int16_t>(msg.blobs.size());
  msg.total_blobs = msg.num_blobs;
  return msg;
}

silhouette_part_t make_silhouette_part() {
  silhouette_part_t msg{};
  msg.camera_id = kCamera;
  msg.frame_number = 41;
  msg.part_count = 1;
  msg.num_pieces = 1;
  msg.data = {'f', 'o', 'o'};
  msg.data_size = static_cast<std::int16_t>(msg.data.size());
  return msg;
}

camera_status_t make_status() {
  camera_status_t msg{};
  msg.camera_id = kCamera;
  msg.state = camera_status_t::STATE_ACQUIRING;
  msg.last_frame_number = 41;
  msg.message = "all well";
  return msg;
}

edge_command_t make_command() {
  edge_command_t msg{};
  msg.camera_id = edge_command_t::ALL_CAMERAS;
  msg.sequence = 7;
  msg.command = edge_command_t::START;
  return msg;
}

class LcmLoggerRoundTrip : public ::testing::Test {
 protected:
  void TearDown() override { std::filesystem::remove(log_path_); }

  void publish_all() {
    EXPECT_EQ(lcm_.publish(proto::kTriggerChannel, &trigger_), 0);
    EXPECT_EQ(lcm_.publish(proto::blob_channel(kCamera), &blob_frame_), 0);
    EXPECT_EQ(lcm_.publish(proto::silhouette_channel(kCamera), &silhouette_), 0);
    EXPECT_EQ(lcm_.publish(proto::status_channel(kCamera), &status_), 0);
    EXPECT_EQ(lcm_.publish(proto::kEdgeCommandChannel, &command_), 0);
  }

  static constexpr std::size_t kPublished = 5;
  const std::filesystem::path log_path_ =
      std::filesystem::temp_directory_path() /
      ("syncap_lcm_logger_roundtrip_" + std::to_string(getpid()) + ".log");
  lcm::LCM lcm_{proto::kDefaultLcmUrl};
  const trigger_t trigger_ = make_trigger(41);
  const blob_frame_t blob_frame_ = make_blob_frame();
  const silhouette_part_t silhouette_ = make_silhouette_part();
  const camera_status_t status_ = make_status();
  const edge_command_t command_ = make_command();
};

TEST_F(LcmLoggerRoundTrip, SyncapLogDecodesWhatLcmLoggerRecorded) {
  ASSERT_TRUE(lcm_.good());
  LcmLogger logger(log_path_);
  ASSERT_TRUE(logger.started()) << "cannot run lcm-logger from PATH";
  const trigger_t probe = make_trigger(0);
  ASSERT_TRUE(wait_until([&] { return count_recorded(log_path_, true) > 0; },
                         [&] { lcm_.publish(kProbeChannel, &probe); }))
      << "lcm-logger recorded no probe";

  publish_all();
  // lcm-logger (1.4) flushes its file only when a later event arrives: the probes keep coming.
  ASSERT_TRUE(wait_until([&] { return count_recorded(log_path_, false) == kPublished; },
                         [&] { lcm_.publish(kProbeChannel, &probe); }))
      << "lcm-logger recorded " << count_recorded(log_path_, false) << " of " << kPublished
      << " messages: " << recorded_channels(log_path_);
  ASSERT_TRUE(logger.stop()) << "lcm-logger ignored SIGINT";

  const ToolRun run = run_syncap_log(log_path_);

  EXPECT_EQ(run.status, 0);
  ASSERT_EQ(run.lines.size(), kPublished);
  std::map<std::string, nlohmann::json> by_channel;
  for (std::size_t i = 0; i < run.lines.size(); ++i) {
    by_channel[run.lines[i]["channel"].get<std::string>()] = run.lines[i];
    if (i > 0) {
      EXPECT_GT(run.lines[i]["event"], run.lines[i - 1]["event"]);
      EXPECT_GE(run.lines[i]["timestamp_us"], run.lines[i - 1]["timestamp_us"]);
    }
  }
  const auto& trigger = by_channel[proto::kTriggerChannel];
  EXPECT_EQ(trigger["type"], "syncap.trigger_t");
  EXPECT_EQ(trigger["fields"]["frame_number"], 41);
  EXPECT_EQ(trigger["fields"]["realtime_ns"], 1'700'000'000'000'000'000);
  const auto& blobs = by_channel[proto::blob_channel(kCamera)];
  EXPECT_EQ(blobs["type"], "syncap.blob_frame_t");
  EXPECT_EQ(blobs["fields"]["num_blobs"], 2);
  EXPECT_EQ(blobs["fields"]["blobs"][1]["x"], 200.25);
  const auto& silhouette = by_channel[proto::silhouette_channel(kCamera)];
  EXPECT_EQ(silhouette["type"], "syncap.silhouette_part_t");
  EXPECT_EQ(silhouette["fields"]["data"], "Zm9v");
  const auto& status = by_channel[proto::status_channel(kCamera)];
  EXPECT_EQ(status["type"], "syncap.camera_status_t");
  EXPECT_EQ(status["fields"]["message"], "all well");
  const auto& command = by_channel[proto::kEdgeCommandChannel];
  EXPECT_EQ(command["type"], "syncap.edge_command_t");
  EXPECT_EQ(command["fields"]["command"], edge_command_t::START);
  EXPECT_EQ(command["fields"]["camera_id"], edge_command_t::ALL_CAMERAS);
}

}  // namespace
}  // namespace syncap
