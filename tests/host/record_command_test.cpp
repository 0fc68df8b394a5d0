#include "record_command.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "io/lcm_log_reader.hpp"
#include "subcommand.hpp"

namespace syncap::tools {
namespace {

std::filesystem::path temp_log(const std::string& name) {
  return std::filesystem::temp_directory_path() /
         (name + "-" + std::to_string(::getpid()) + ".lcmlog");
}

std::vector<io::LogEvent> read_log(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  io::LcmLogReader reader(in);
  std::vector<io::LogEvent> events;
  while (auto event = reader.next()) events.push_back(*event);
  EXPECT_TRUE(reader.take_errors().empty());
  return events;
}

// Publishes `count` messages on memq (LCM's in-process provider) before any is handled. memq
// keeps every message whatever the queue capacity; the queue's own test is on real multicast
// (tests/hil/traffic_recorder_test.cpp).
void publish_burst(lcm::LCM& lcm, int count) {
  for (int i = 0; i < count; ++i) {
    const std::string channel =
        i % 3 == 0 ? "SYNCAP_TRIGGER" : "SYNCAP_BLOBS_0" + std::to_string(i % 3);
    const std::vector<std::uint8_t> data{static_cast<std::uint8_t>(i),
                                         static_cast<std::uint8_t>(i >> 8)};
    lcm.publish(channel, data.data(), static_cast<unsigned>(data.size()));
  }
}

void handle_all(lcm::LCM& lcm) {
  while (lcm.handleTimeout(0) > 0) {
  }
}

TEST(TrafficRecorder, EveryMessageIsRecordedInOrderWithItsChannel) {
  const std::filesystem::path path = temp_log("record-burst");
  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  constexpr int kBurst = 3000;
  {
    io::LcmLogWriter log(path.string());
    TrafficRecorder recorder(lcm, log);
    publish_burst(lcm, kBurst);
    handle_all(lcm);
    EXPECT_EQ(log.events(), kBurst);
    EXPECT_EQ(recorder.by_channel().at("SYNCAP_TRIGGER"), kBurst / 3);
    EXPECT_EQ(recorder.by_channel().at("SYNCAP_BLOBS_01"), kBurst / 3);
    EXPECT_EQ(recorder.by_channel().at("SYNCAP_BLOBS_02"), kBurst / 3);
    EXPECT_TRUE(recorder.write_error().empty());
    log.close();
  }
  const std::vector<io::LogEvent> events = read_log(path);
  ASSERT_EQ(events.size(), static_cast<std::size_t>(kBurst));
  for (int i = 0; i < kBurst; ++i) {
    ASSERT_EQ(events[i].event_number, i);
    ASSERT_EQ(events[i].data[0] | (events[i].data[1] << 8), i & 0xFFFF) << "out of order at " << i;
  }
  std::filesystem::remove(path);
}

TEST(TrafficRecorder, OnlyTheChannelsOfTheRegexAreRecorded) {
  const std::filesystem::path path = temp_log("record-regex");
  lcm::LCM lcm("memq://");
  io::LcmLogWriter log(path.string());
  TrafficRecorder recorder(lcm, log, "SYNCAP_BLOBS_.*");
  publish_burst(lcm, 30);
  handle_all(lcm);
  EXPECT_EQ(log.events(), 20);
  EXPECT_EQ(recorder.by_channel().count("SYNCAP_TRIGGER"), 0u);
  log.close();
  std::filesystem::remove(path);
}

TEST(TrafficRecorder, AWriteErrorStopsRecordingAndIsKept) {
  if (!std::filesystem::exists("/dev/full")) GTEST_SKIP() << "no /dev/full on this system";
  lcm::LCM lcm("memq://");
  io::LcmLogWriter log("/dev/full");
  TrafficRecorder recorder(lcm, log);
  // Records larger than stdio's buffer reach the disk within write().
  const std::vector<std::uint8_t> big(1 << 16, 7);
  for (int i = 0; i < 4; ++i) lcm.publish("BIG", big.data(), static_cast<unsigned>(big.size()));
  handle_all(lcm);
  EXPECT_NE(recorder.write_error().find("cannot write event"), std::string::npos)
      << recorder.write_error();
}

struct CommandRun {
  int status;
  std::string out, err;
};

CommandRun run(std::vector<std::string> args) {
  std::ostringstream out, err;
  const int status = record_command(args, out, err);
  return {status, out.str(), err.str()};
}

TEST(RecordCommand, RecordsForTheDurationAndSummarises) {
  const std::filesystem::path path = temp_log("record-command");
  const CommandRun r = run({"--out", path.string(), "--lcm-url", "memq://", "--duration-s", "0.2"});
  EXPECT_EQ(r.status, kExitOk) << r.err;
  EXPECT_NE(r.err.find("recording memq://"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("0 events on 0 channels in " + path.string()), std::string::npos) << r.out;
  EXPECT_TRUE(std::filesystem::exists(path));
  EXPECT_EQ(std::filesystem::file_size(path), 0u);
  std::filesystem::remove(path);
}

TEST(RecordCommand, AnUnwritableLogIsAUsageErrorNamingIt) {
  const CommandRun r =
      run({"--out", "/nonexistent-syncap-folder/t.lcmlog", "--lcm-url", "memq://"});
  EXPECT_EQ(r.status, kExitUsage);
  EXPECT_NE(r.err.find("/nonexistent-syncap-folder/t.lcmlog"), std::string::npos) << r.err;
}

TEST(RecordCommand, OutIsRequiredAndDurationMustNotBeNegative) {
  EXPECT_EQ(run({"--lcm-url", "memq://"}).status, kExitUsage);
  const CommandRun r = run({"--out", "x.lcmlog", "--duration-s", "-1"});
  EXPECT_EQ(r.status, kExitUsage);
  EXPECT_NE(r.err.find("--duration-s"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace syncap::tools
