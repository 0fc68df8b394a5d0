// The LCM log reader (io::LcmLogReader): events with their offsets, and damage reported by
// offset (what `syncap log` prints of it: tests/host/log_command_test.cpp).
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "io/lcm_log_reader.hpp"
#include "lcm_log_samples.hpp"

namespace syncap::io {
namespace {

using test::append;
using test::Bytes;
using test::record;
using test::sample_trigger;

std::vector<LogEvent> read_all(const Bytes& log, std::vector<LogError>& errors) {
  std::istringstream in(std::string(log.begin(), log.end()));
  LcmLogReader reader(in);
  std::vector<LogEvent> events;
  while (auto event = reader.next()) events.push_back(std::move(*event));
  errors = reader.take_errors();
  return events;
}

TEST(LcmLogReader, ReadsEventsWithTheirOffsets) {
  const Bytes first = record(7, "A", {1, 2, 3});
  const Bytes second = record(8, "CHANNEL_B", {});
  Bytes log = first;
  append(log, second);

  std::vector<LogError> errors;
  const auto events = read_all(log, errors);

  EXPECT_TRUE(errors.empty());
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[0].offset, 0u);
  EXPECT_EQ(events[0].event_number, 7);
  EXPECT_EQ(events[0].timestamp_us, 1'700'000'000'000'007);
  EXPECT_EQ(events[0].channel, "A");
  EXPECT_EQ(events[0].data, (Bytes{1, 2, 3}));
  EXPECT_EQ(events[1].offset, first.size());
  EXPECT_EQ(events[1].channel, "CHANNEL_B");
  EXPECT_TRUE(events[1].data.empty());
}

TEST(LcmLogReader, ReadsWhatLcmsOwnLogWriterWrites) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() /
                                     ("syncap_log_reader_test_" + std::to_string(getpid()));
  const Bytes payload = test::encoded(sample_trigger(3));
  {
    lcm::LogFile writer(path.string(), "w");
    ASSERT_TRUE(writer.good());
    lcm::LogEvent event{};
    event.eventnum = 0;  // lcm numbers the events itself
    event.timestamp = 1'650'000'000'123'456;
    event.channel = "SYNCAP_TRIGGER";
    event.datalen = static_cast<int32_t>(payload.size());
    event.data = const_cast<std::uint8_t*>(payload.data());
    ASSERT_EQ(writer.writeEvent(&event), 0);
  }
  std::ifstream in(path, std::ios::binary);
  LcmLogReader reader(in);
  const auto event = reader.next();
  std::filesystem::remove(path);

  ASSERT_TRUE(event.has_value());
  EXPECT_EQ(event->timestamp_us, 1'650'000'000'123'456);
  EXPECT_EQ(event->channel, "SYNCAP_TRIGGER");
  EXPECT_EQ(event->data, payload);
  EXPECT_FALSE(reader.next().has_value());
  EXPECT_TRUE(reader.take_errors().empty());
}

TEST(LcmLogReader, TruncatedHeaderReportsItsOffset) {
  const Bytes first = record(0, "C", {});
  Bytes log = first;
  append(log, Bytes{0xed, 0xa1, 0xda, 0x01, 0, 0});

  std::vector<LogError> errors;
  const auto events = read_all(log, errors);

  EXPECT_EQ(events.size(), 1u);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].offset, first.size());
  EXPECT_EQ(errors[0].message, "truncated event at offset " + std::to_string(first.size()) +
                                   ": header needs 28 bytes, 6 left in the file");
}

TEST(LcmLogReader, GarbageBetweenRecordsIsSkippedWithItsOffset) {
  const Bytes first = record(0, "SYNCAP_TRIGGER", test::encoded(sample_trigger(0)));
  const Bytes garbage{0xde, 0xad, 0xbe, 0xef, 0xed, 0xa1, 0xda, 0x00, 0x42, 0x42, 0x42, 0x42, 0x01};
  Bytes log = first;
  append(log, garbage);
  append(log, record(1, "SYNCAP_TRIGGER", test::encoded(sample_trigger(1))));

  std::vector<LogError> errors;
  const auto events = read_all(log, errors);

  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[1].event_number, 1);
  EXPECT_EQ(events[1].offset, first.size() + garbage.size());
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].offset, first.size());
  EXPECT_EQ(errors[0].message,
            "bad sync word 0xdeadbeef at offset " + std::to_string(first.size()) + ": skipped " +
                std::to_string(garbage.size()) + " bytes to the next sync word at offset " +
                std::to_string(first.size() + garbage.size()));
}

TEST(LcmLogReader, GarbageAtTheEndIsSkippedToTheEnd) {
  Bytes log = record(0, "C", {});
  const std::size_t garbage_offset = log.size();
  append(log, Bytes(40, 0x55));

  std::vector<LogError> errors;
  const auto events = read_all(log, errors);

  EXPECT_EQ(events.size(), 1u);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].offset, garbage_offset);
  EXPECT_NE(errors[0].message.find("skipped 40 bytes to the end of the file"), std::string::npos)
      << errors[0].message;
}

TEST(LcmLogReader, GarbageBeforeATruncatedTailIsReportedFirst) {
  const Bytes first = record(0, "C", {});
  const Bytes last = record(1, "C", {});
  Bytes log = first;
  append(log, Bytes{'x', 'y', 'z'});
  log.insert(log.end(), last.begin(), last.begin() + 20);

  std::vector<LogError> errors;
  const auto events = read_all(log, errors);

  EXPECT_EQ(events.size(), 1u);
  ASSERT_EQ(errors.size(), 2u);
  EXPECT_EQ(errors[0].offset, first.size());
  EXPECT_NE(errors[0].message.find("bad sync word 0x78797aed"), std::string::npos)
      << errors[0].message;
  EXPECT_EQ(errors[1].message, "truncated event at offset " + std::to_string(first.size() + 3) +
                                   ": header needs 28 bytes, 20 left in the file");
}

TEST(LcmLogReader, ImplausibleLengthsAreTreatedAsDamage) {
  Bytes bad = record(0, "C", {});
  bad[20] = 0x7f;  // channel length far beyond any channel name
  Bytes log = bad;
  append(log, record(1, "D", {}));

  std::vector<LogError> errors;
  const auto events = read_all(log, errors);

  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].channel, "D");
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].offset, 0u);
  EXPECT_NE(errors[0].message.find("bad event header (channel length"), std::string::npos)
      << errors[0].message;
}

}  // namespace
}  // namespace syncap::io
