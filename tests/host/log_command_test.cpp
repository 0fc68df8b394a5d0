// `syncap log`: each event as a JSON line, damage reported on stderr with its offset, the
// channel filter, usage. Logs are built byte by byte, so every kind of damage sits at a known
// offset (the reader's own tests: tests/host/io/lcm_log_reader_test.cpp; the messages' JSON
// views: tests/host/io/message_json_test.cpp).
#include <gtest/gtest.h>

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "help_check.hpp"
#include "lcm_log_samples.hpp"
#include "log_command.hpp"
#include "malformed_messages.hpp"
#include "subcommand.hpp"
#include "syncap/camera_status_t.hpp"

namespace syncap::tools {
namespace {

using test::append;
using test::Bytes;
using test::record;
using test::sample_trigger;

struct LogRun {
  int status = -1;
  std::vector<std::string> raw_lines;  // stdout
  std::vector<nlohmann::json> lines;   // stdout, one parsed JSON object per line
  std::string errors;                  // stderr
};

LogRun run_print_log(const Bytes& log, const std::optional<std::regex>& filter = std::nullopt) {
  std::istringstream in(std::string(log.begin(), log.end()));
  std::ostringstream out;
  std::ostringstream err;
  LogRun run;
  run.status = print_log(in, filter, out, err);
  std::istringstream printed(out.str());
  for (std::string line; std::getline(printed, line);) {
    run.raw_lines.push_back(line);
    run.lines.push_back(nlohmann::json::parse(line));
  }
  run.errors = err.str();
  return run;
}

// The fields of the single event a log holding only `msg` prints.
template <class Message>
nlohmann::json fields_of(const Message& msg) {
  const LogRun run = run_print_log(record(0, "SYNCAP_TEST", test::encoded(msg)));
  EXPECT_EQ(run.status, kExitOk) << run.errors;
  EXPECT_EQ(run.lines.size(), 1u);
  if (run.lines.size() != 1) return nullptr;
  EXPECT_EQ(run.lines[0]["type"], std::string("syncap.") + Message::getTypeName());
  return run.lines[0]["fields"];
}

TEST(LogJson, InvalidUtf8InStringsIsReplacedNotFatal) {
  camera_status_t msg{};
  msg.message = "bad \xff byte";

  const nlohmann::json fields = fields_of(msg);

  EXPECT_EQ(fields["message"], "bad \xef\xbf\xbd byte");  // U+FFFD
}

TEST(LogJson, LineCarriesEventHeaderInOrder) {
  const LogRun run = run_print_log(record(5, "SYNCAP_TRIGGER", test::encoded(sample_trigger(1))));
  ASSERT_EQ(run.raw_lines.size(), 1u);
  EXPECT_TRUE(run.raw_lines[0].starts_with(
      R"({"event":5,"timestamp_us":1700000000000005,"channel":"SYNCAP_TRIGGER",)"
      R"("type":"syncap.trigger_t","fields":{"frame_number":1,)"))
      << run.raw_lines[0];
}

TEST(LogJson, UnknownFingerprintPrintsNullTypeAndReportsWhere) {
  const Bytes first = record(0, "SYNCAP_TRIGGER", test::encoded(sample_trigger(0)));
  Bytes log = first;
  append(log, record(1, "MYSTERY", {1, 2, 3, 4, 5, 6, 7, 8, 9}));

  const LogRun run = run_print_log(log);

  EXPECT_EQ(run.status, kExitReportedErrors);
  ASSERT_EQ(run.lines.size(), 2u);
  EXPECT_TRUE(run.lines[1]["type"].is_null());
  EXPECT_FALSE(run.lines[1].contains("fields"));
  EXPECT_NE(run.errors.find("event 1 on channel MYSTERY at offset " + std::to_string(first.size()) +
                            ": unknown type fingerprint 0x0102030405060708"),
            std::string::npos)
      << run.errors;
}

TEST(LogJson, PayloadThatDoesNotDecodeIsReportedWithOffset) {
  Bytes payload = test::encoded(sample_trigger(0));
  payload.resize(payload.size() - 3);

  const LogRun run = run_print_log(record(4, "SYNCAP_TRIGGER", payload));

  EXPECT_EQ(run.status, kExitReportedErrors);
  ASSERT_EQ(run.lines.size(), 1u);
  EXPECT_EQ(run.lines[0]["type"], "syncap.trigger_t");
  EXPECT_FALSE(run.lines[0].contains("fields"));
  EXPECT_NE(run.errors.find("event 4 on channel SYNCAP_TRIGGER at offset 0: payload of"),
            std::string::npos)
      << run.errors;
}

TEST(LogJson, TrailingBytesAfterAnEncodingAreReported) {
  Bytes payload = test::encoded(sample_trigger(6));
  payload.push_back(0xaa);

  const LogRun run = run_print_log(record(0, "SYNCAP_TRIGGER", payload));

  EXPECT_EQ(run.status, kExitReportedErrors);
  ASSERT_EQ(run.lines.size(), 1u);
  EXPECT_EQ(run.lines[0]["fields"]["frame_number"], 6);
  EXPECT_NE(run.errors.find("trailing"), std::string::npos) << run.errors;
}

TEST(LcmLogReader, TruncatedFinalRecordReportsItsOffsetAndStops) {
  const Bytes first = record(0, "SYNCAP_TRIGGER", test::encoded(sample_trigger(0)));
  Bytes log = first;
  append(log, record(1, "SYNCAP_TRIGGER", test::encoded(sample_trigger(1))));
  log.resize(log.size() - 5);

  const LogRun run = run_print_log(log);

  EXPECT_EQ(run.status, kExitReportedErrors);
  EXPECT_EQ(run.lines.size(), 1u);
  EXPECT_NE(run.errors.find("truncated event at offset " + std::to_string(first.size()) + ": "),
            std::string::npos)
      << run.errors;
}

TEST(LogCommand, ChannelFilterMatchesWholeNames) {
  Bytes log = record(0, "SYNCAP_TRIGGER", test::encoded(sample_trigger(0)));
  append(log, record(1, "SYNCAP_BLOBS_03", {9, 9, 9, 9, 9, 9, 9, 9}));  // unknown, but filtered
  append(log, record(2, "SYNCAP_TRIGGER_2", test::encoded(sample_trigger(2))));

  const LogRun run = run_print_log(log, std::regex("SYNCAP_TRIGGER"));

  EXPECT_EQ(run.status, kExitOk) << run.errors;
  ASSERT_EQ(run.lines.size(), 1u);
  EXPECT_EQ(run.lines[0]["event"], 0);
}

TEST(LogCommand, UsageErrorsAndUnreadableFilesExitWithTwo) {
  std::ostringstream out;
  std::ostringstream err;
  const std::vector<std::string> no_file;
  EXPECT_EQ(log_command(no_file, out, err), kExitUsage);
  EXPECT_EQ(err.str().rfind("syncap log: FILE is required\n", 0), 0u) << err.str();

  const std::vector<std::string> missing{"/nonexistent/syncap.log"};
  EXPECT_EQ(log_command(missing, out, err), kExitUsage);
  EXPECT_NE(err.str().find("cannot open /nonexistent/syncap.log"), std::string::npos) << err.str();

  const std::vector<std::string> bad_regex{"x.log", "--channel", "("};
  err.str("");
  EXPECT_EQ(log_command(bad_regex, out, err), kExitUsage);
  EXPECT_NE(err.str().find("--channel: bad REGEX '('"), std::string::npos) << err.str();
  EXPECT_TRUE(out.str().empty());

  const std::vector<std::string> two_files{"a.log", "b.log"};
  err.str("");
  EXPECT_EQ(log_command(two_files, out, err), kExitUsage);
  EXPECT_NE(err.str().find("unexpected argument 'b.log'"), std::string::npos) << err.str();
}

// --help: both forms, every option with its meaning, the exit statuses.
TEST(LogCommand, HelpIsComplete) {
  std::ostringstream out, err;
  const std::vector<std::string> help{"--help"};
  EXPECT_EQ(log_command(help, out, err), kExitOk);
  syncap::test::expect_help_mentions(
      out.str(),
      {"usage: syncap log FILE [--channel REGEX]", "syncap log --stats FILE", "-c,--channel REGEX",
       "(ECMAScript)", "--stats", "per camera the bytes per", "Exit status: 0 all decoded"});
}

TEST(LogCommand, LcmSelfTestProbeIsShownAndNotAnError) {
  const std::string probe = "lcm self test";
  Bytes log = record(0, "LCM_SELF_TEST", Bytes(probe.begin(), probe.end()));
  append(log, record(1, "SYNCAP_TRIGGER", test::encoded(sample_trigger(1))));

  const LogRun run = run_print_log(log, std::nullopt);

  EXPECT_EQ(run.status, kExitOk) << run.errors;
  EXPECT_TRUE(run.errors.empty()) << run.errors;
  ASSERT_EQ(run.lines.size(), 2u);
  EXPECT_EQ(run.lines[0]["type"], "lcm.self_test");
  EXPECT_EQ(run.lines[0]["fields"]["text"], probe);
  EXPECT_EQ(run.lines[1]["type"], "syncap.trigger_t");
}

// Issue 15: a negative num_blobs made the decoder throw std::length_error out of `syncap log`.
TEST(LogJson, NegativeArrayLengthIsReportedWithEventAndOffsetAndTheLogGoesOn) {
  Bytes log = record(0, "SYNCAP_TRIGGER", test::encoded(sample_trigger(0)));
  const std::size_t bad_offset = log.size();
  append(log, record(1, "SYNCAP_BLOBS_02", test::blob_frame_with_negative_count(2, 0)));
  append(log, record(2, "SYNCAP_STATUS_02", test::camera_status_with_zero_string_length(2)));
  append(log, record(3, "SYNCAP_TRIGGER", test::encoded(sample_trigger(1))));

  const LogRun run = run_print_log(log);

  EXPECT_EQ(run.status, kExitReportedErrors);
  ASSERT_EQ(run.lines.size(), 4u);
  EXPECT_EQ(run.lines[1]["type"], "syncap.blob_frame_t");
  EXPECT_FALSE(run.lines[1].contains("fields"));
  EXPECT_TRUE(run.lines[3].contains("fields"));
  EXPECT_NE(run.errors.find("event 1 on channel SYNCAP_BLOBS_02 at offset " +
                            std::to_string(bad_offset) + ": payload of 48 bytes does not decode"),
            std::string::npos)
      << run.errors;
  EXPECT_NE(run.errors.find("event 2 on channel SYNCAP_STATUS_02"), std::string::npos)
      << run.errors;
}

}  // namespace
}  // namespace syncap::tools
