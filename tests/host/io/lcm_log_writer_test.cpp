#include "io/lcm_log_writer.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "io/export_error.hpp"
#include "io/lcm_log_reader.hpp"

namespace syncap::io {
namespace {

std::filesystem::path temp_log(const std::string& name) {
  return std::filesystem::temp_directory_path() /
         (name + "-" + std::to_string(::getpid()) + ".lcmlog");
}

TEST(LcmLogWriter, WrittenEventsReadBackInOrderWithTheirNumbersTimesAndBytes) {
  const std::filesystem::path path = temp_log("writer-roundtrip");
  const std::vector<std::uint8_t> first{1, 2, 3}, empty{}, third(70000, 0xAB);
  {
    LcmLogWriter log(path.string());
    log.write(1'700'000'000'000'001, "SYNCAP_TRIGGER", first);
    log.write(1'700'000'000'000'002, "SYNCAP_BLOBS_03", empty);
    log.write(-5, "X", third);
    EXPECT_EQ(log.events(), 3);
    log.close();
  }
  std::ifstream in(path, std::ios::binary);
  LcmLogReader reader(in);
  std::vector<LogEvent> events;
  while (auto event = reader.next()) events.push_back(*event);
  EXPECT_TRUE(reader.take_errors().empty());
  ASSERT_EQ(events.size(), 3u);
  EXPECT_EQ(events[0].event_number, 0);
  EXPECT_EQ(events[0].timestamp_us, 1'700'000'000'000'001);
  EXPECT_EQ(events[0].channel, "SYNCAP_TRIGGER");
  EXPECT_EQ(events[0].data, first);
  EXPECT_EQ(events[1].event_number, 1);
  EXPECT_EQ(events[1].channel, "SYNCAP_BLOBS_03");
  EXPECT_TRUE(events[1].data.empty());
  EXPECT_EQ(events[2].event_number, 2);
  EXPECT_EQ(events[2].timestamp_us, -5);
  EXPECT_EQ(events[2].data, third);
  std::filesystem::remove(path);
}

TEST(LcmLogWriter, FlushedEventsAreInTheFileBeforeClose) {
  const std::filesystem::path path = temp_log("writer-flush");
  LcmLogWriter log(path.string());
  log.write(7, "A", std::vector<std::uint8_t>{9});
  log.flush();
  EXPECT_EQ(std::filesystem::file_size(path), kLcmLogHeaderSize + 1 + 1);
  log.close();
  std::filesystem::remove(path);
}

TEST(LcmLogWriter, AFolderThatDoesNotExistIsNamedInTheError) {
  try {
    LcmLogWriter log("/nonexistent-syncap-folder/traffic.lcmlog");
    FAIL() << "opened a log in a folder that does not exist";
  } catch (const ExportError& e) {
    EXPECT_EQ(e.path(), "/nonexistent-syncap-folder/traffic.lcmlog");
    EXPECT_NE(std::string(e.what()).find("cannot create the log"), std::string::npos) << e.what();
  }
}

TEST(LcmLogWriter, AFullDiskIsAnErrorNamingTheFile) {
  if (!std::filesystem::exists("/dev/full")) GTEST_SKIP() << "no /dev/full on this system";
  LcmLogWriter log("/dev/full");
  // stdio buffers the record; the disk's answer comes with the flush.
  log.write(1, "SYNCAP_TRIGGER", std::vector<std::uint8_t>(100, 1));
  try {
    log.flush();
    FAIL() << "a flush to /dev/full succeeded";
  } catch (const ExportError& e) {
    EXPECT_EQ(e.path(), "/dev/full");
    EXPECT_NE(e.problem().find("cannot write the log"), std::string::npos) << e.what();
  }
}

TEST(LcmLogWriter, WritingAfterCloseIsAnError) {
  const std::filesystem::path path = temp_log("writer-closed");
  LcmLogWriter log(path.string());
  log.close();
  EXPECT_THROW(log.write(1, "A", std::vector<std::uint8_t>{}), ExportError);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace syncap::io
