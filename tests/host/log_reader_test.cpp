// The LCM log reader and `syncap log`: logs are built byte by byte here, so every kind of damage
// sits at a known offset.
#include <gtest/gtest.h>

#include <unistd.h>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <nlohmann/json.hpp>
#include <optional>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "help_check.hpp"
#include "lcm_log_reader.hpp"
#include "log_command.hpp"
#include "malformed_messages.hpp"
#include "message_json.hpp"
#include "subcommand.hpp"
#include "syncap/trigger_status_t.hpp"

namespace syncap::tools {
namespace {

using Bytes = std::vector<std::uint8_t>;

template <class Message>
Bytes encode(const Message& msg) {
  Bytes bytes(static_cast<std::size_t>(msg.getEncodedSize()));
  msg.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

void append(Bytes& log, const Bytes& more) { log.insert(log.end(), more.begin(), more.end()); }

Bytes record(std::int64_t event_number, const std::string& channel, const Bytes& data) {
  return encode_log_record(event_number, 1'700'000'000'000'000 + event_number, channel, data);
}

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
  const LogRun run = run_print_log(record(0, "SYNCAP_TEST", encode(msg)));
  EXPECT_EQ(run.status, kExitOk) << run.errors;
  EXPECT_EQ(run.lines.size(), 1u);
  if (run.lines.size() != 1) return nullptr;
  EXPECT_EQ(run.lines[0]["type"], std::string("syncap.") + Message::getTypeName());
  return run.lines[0]["fields"];
}

std::vector<LogEvent> read_all(const Bytes& log, std::vector<LogError>& errors) {
  std::istringstream in(std::string(log.begin(), log.end()));
  LcmLogReader reader(in);
  std::vector<LogEvent> events;
  while (auto event = reader.next()) events.push_back(std::move(*event));
  errors = reader.take_errors();
  return events;
}

trigger_t sample_trigger(std::int64_t frame_number) {
  trigger_t msg{};
  msg.frame_number = frame_number;
  msg.monotonic_ns = 1'234'567'890'123'456'789;
  msg.realtime_ns = -5;
  msg.rate_hz = 99.75;
  msg.pulse_width_us = 500;
  msg.trigger_id = 2;
  msg.flags = trigger_t::FLAG_LATE | trigger_t::FLAG_LAST;
  return msg;
}

blob_t sample_blob(float x) {
  blob_t blob{};
  blob.x = x;
  blob.y = -2.25f;
  blob.area = 17.5f;
  blob.peak = 4095;
  blob.bbox_x = 10;
  blob.bbox_y = 20;
  blob.bbox_w = 5;
  blob.bbox_h = 6;
  blob.flags = blob_t::FLAG_SATURATED;
  return blob;
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
  const Bytes payload = encode(sample_trigger(3));
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

TEST(LogJson, TriggerRoundTrips) {
  const nlohmann::json fields = fields_of(sample_trigger(42));
  EXPECT_EQ(fields["frame_number"], 42);
  EXPECT_EQ(fields["monotonic_ns"], 1'234'567'890'123'456'789);
  EXPECT_EQ(fields["realtime_ns"], -5);
  EXPECT_EQ(fields["rate_hz"], 99.75);
  EXPECT_EQ(fields["pulse_width_us"], 500);
  EXPECT_EQ(fields["trigger_id"], 2);
  EXPECT_EQ(fields["flags"], trigger_t::FLAG_LATE | trigger_t::FLAG_LAST);
}

TEST(LogJson, BlobRoundTrips) {
  const nlohmann::json fields = fields_of(sample_blob(1.5f));
  EXPECT_EQ(fields, nlohmann::json::parse(R"({"x":1.5,"y":-2.25,"area":17.5,"peak":4095,
      "bbox_x":10,"bbox_y":20,"bbox_w":5,"bbox_h":6,"flags":1})"));
}

TEST(LogJson, BlobFrameRoundTripsWithNestedBlobs) {
  blob_frame_t msg{};
  msg.camera_id = 3;
  msg.frame_number = 1'000'000'000'000;
  msg.monotonic_ns = 987'654'321;
  msg.exposure_us = 1200;
  msg.processing_us = 340;
  msg.image_width = 2048;
  msg.image_height = 1536;
  msg.part_index = 1;
  msg.part_count = 2;
  msg.total_blobs = 60;
  msg.blobs = {sample_blob(1.5f), sample_blob(-0.5f)};
  msg.num_blobs = static_cast<int16_t>(msg.blobs.size());

  const nlohmann::json fields = fields_of(msg);

  EXPECT_EQ(fields["camera_id"], 3);
  EXPECT_EQ(fields["frame_number"], 1'000'000'000'000);
  EXPECT_EQ(fields["monotonic_ns"], 987'654'321);
  EXPECT_EQ(fields["exposure_us"], 1200);
  EXPECT_EQ(fields["processing_us"], 340);
  EXPECT_EQ(fields["image_width"], 2048);
  EXPECT_EQ(fields["image_height"], 1536);
  EXPECT_EQ(fields["part_index"], 1);
  EXPECT_EQ(fields["part_count"], 2);
  EXPECT_EQ(fields["total_blobs"], 60);
  EXPECT_EQ(fields["num_blobs"], 2);
  ASSERT_EQ(fields["blobs"].size(), 2u);
  EXPECT_EQ(fields["blobs"][0]["x"], 1.5);
  EXPECT_EQ(fields["blobs"][1]["x"], -0.5);
  EXPECT_EQ(fields["blobs"][1]["peak"], 4095);
}

TEST(LogJson, SilhouettePartRoundTripsWithBase64Data) {
  silhouette_part_t msg{};
  msg.camera_id = 12;
  msg.frame_number = 77;
  msg.image_width = 640;
  msg.image_height = 480;
  msg.part_index = 0;
  msg.part_count = 1;
  msg.num_pieces = 1;
  msg.data = {0x00, 0xff, 0x10, 0x80};
  msg.data_size = static_cast<int16_t>(msg.data.size());

  const nlohmann::json fields = fields_of(msg);

  EXPECT_EQ(fields["camera_id"], 12);
  EXPECT_EQ(fields["frame_number"], 77);
  EXPECT_EQ(fields["image_width"], 640);
  EXPECT_EQ(fields["image_height"], 480);
  EXPECT_EQ(fields["part_index"], 0);
  EXPECT_EQ(fields["part_count"], 1);
  EXPECT_EQ(fields["num_pieces"], 1);
  EXPECT_EQ(fields["data_size"], 4);
  EXPECT_EQ(fields["data"], "AP8QgA==");
}

TEST(LogJson, CameraStatusRoundTrips) {
  camera_status_t msg{};
  msg.camera_id = 99;
  msg.state = camera_status_t::STATE_ERROR;
  msg.monotonic_ns = 11;
  msg.realtime_ns = 22;
  msg.last_frame_number = -1;
  msg.frames_received = 33;
  msg.frames_lost = 4;
  msg.frames_incomplete = 5;
  msg.frame_rate_hz = 59.5f;
  msg.processing_us_mean = 812.25f;
  msg.message = "buffer underrun \"x\"";

  const nlohmann::json fields = fields_of(msg);

  EXPECT_EQ(fields["camera_id"], 99);
  EXPECT_EQ(fields["state"], camera_status_t::STATE_ERROR);
  EXPECT_EQ(fields["monotonic_ns"], 11);
  EXPECT_EQ(fields["realtime_ns"], 22);
  EXPECT_EQ(fields["last_frame_number"], -1);
  EXPECT_EQ(fields["frames_received"], 33);
  EXPECT_EQ(fields["frames_lost"], 4);
  EXPECT_EQ(fields["frames_incomplete"], 5);
  EXPECT_EQ(fields["frame_rate_hz"], 59.5);
  EXPECT_EQ(fields["processing_us_mean"], 812.25);
  EXPECT_EQ(fields["message"], "buffer underrun \"x\"");
}

TEST(LogJson, TriggerStatusRoundTrips) {
  trigger_status_t msg{};
  msg.trigger_id = 3;
  msg.state = trigger_status_t::STATE_STOPPED;
  msg.monotonic_ns = 11;
  msg.realtime_ns = 22;
  msg.pulses = 1000;
  msg.late = 2;
  msg.missed = 1;
  msg.last_frame_number = 1000;
  msg.rate_hz = 99.75;
  msg.message = "exiting";

  const nlohmann::json fields = fields_of(msg);

  EXPECT_EQ(fields["trigger_id"], 3);
  EXPECT_EQ(fields["state"], trigger_status_t::STATE_STOPPED);
  EXPECT_EQ(fields["monotonic_ns"], 11);
  EXPECT_EQ(fields["realtime_ns"], 22);
  EXPECT_EQ(fields["pulses"], 1000);
  EXPECT_EQ(fields["late"], 2);
  EXPECT_EQ(fields["missed"], 1);
  EXPECT_EQ(fields["last_frame_number"], 1000);
  EXPECT_EQ(fields["rate_hz"], 99.75);
  EXPECT_EQ(fields["message"], "exiting");
}

TEST(LogJson, EdgeCommandRoundTrips) {
  edge_command_t msg{};
  msg.camera_id = edge_command_t::ALL_CAMERAS;
  msg.sender = -5;
  msg.sequence = 9'000'000'000;
  msg.sent_realtime_ns = 1'800'000'000'000'000'000;
  msg.command = edge_command_t::SET_ROI;
  msg.int_value = -7;
  msg.real_value = 0.125;
  msg.roi_x = 8;
  msg.roi_y = 16;
  msg.roi_width = 320;
  msg.roi_height = 240;
  msg.mac[0] = 0x0f;
  msg.mac[31] = -1;

  const nlohmann::json fields = fields_of(msg);

  EXPECT_EQ(fields, nlohmann::json::parse(R"({"camera_id":-1,"sender":-5,"sequence":9000000000,
      "sent_realtime_ns":1800000000000000000,"command":6,
      "int_value":-7,"real_value":0.125,"roi_x":8,"roi_y":16,"roi_width":320,"roi_height":240,
      "mac":"0f000000000000000000000000000000000000000000000000000000000000ff"})"));
}

TEST(LogJson, ClipPolygonRoundTrips) {
  clip_polygon_t msg{};
  msg.camera_id = 3;
  msg.sequence = 12;
  msg.image_width = 640;
  msg.image_height = 480;
  msg.num_points = 3;
  msg.x = {10, 600, 300};
  msg.y = {470, 470, 200};

  const nlohmann::json fields = fields_of(msg);

  EXPECT_EQ(fields, nlohmann::json::parse(R"({"camera_id":3,"sender":0,"sequence":12,
      "sent_realtime_ns":0,"image_width":640,"image_height":480,"num_points":3,
      "x":[10,600,300],"y":[470,470,200],"mac":"0000000000000000000000000000000000000000000000000000000000000000"})"));
}

TEST(LogJson, MarkerFrameRoundTripsWithItsMarkers) {
  marker_frame_t msg{};
  msg.frame_number = 7;
  msg.trigger_realtime_ns = 1'700'000'000'000'000'000;
  msg.host_us = 412;
  msg.flags = marker_frame_t::FLAG_COMPLETE;
  msg.cameras = 8;
  msg.part_count = 1;
  marker_t m{};
  m.id = 3;
  m.x = 12.5f;
  m.y = -1.25f;
  m.z = 1000.0f;
  m.sigma_x = m.sigma_y = m.sigma_z = 0.25f;
  m.residual_px = 0.125f;
  m.cameras = 5;
  m.flags = marker_t::FLAG_TWO_CAMERAS;
  msg.markers = {m};
  msg.num_markers = msg.total_markers = 1;

  const nlohmann::json fields = fields_of(msg);

  EXPECT_EQ(fields, nlohmann::json::parse(R"({"frame_number":7,"trigger_monotonic_ns":0,
      "trigger_realtime_ns":1700000000000000000,"host_us":412,"flags":1,"cameras":8,
      "part_index":0,"part_count":1,"total_markers":1,"num_markers":1,
      "markers":[{"id":3,"x":12.5,"y":-1.25,"z":1000.0,"sigma_x":0.25,"sigma_y":0.25,
      "sigma_z":0.25,"residual_px":0.125,"cameras":5,"flags":1}]})"));
}

TEST(LogJson, InvalidUtf8InStringsIsReplacedNotFatal) {
  camera_status_t msg{};
  msg.message = "bad \xff byte";

  const nlohmann::json fields = fields_of(msg);

  EXPECT_EQ(fields["message"], "bad \xef\xbf\xbd byte");  // U+FFFD
}

TEST(LogJson, LineCarriesEventHeaderInOrder) {
  const LogRun run = run_print_log(record(5, "SYNCAP_TRIGGER", encode(sample_trigger(1))));
  ASSERT_EQ(run.raw_lines.size(), 1u);
  EXPECT_TRUE(run.raw_lines[0].starts_with(
      R"({"event":5,"timestamp_us":1700000000000005,"channel":"SYNCAP_TRIGGER",)"
      R"("type":"syncap.trigger_t","fields":{"frame_number":1,)"))
      << run.raw_lines[0];
}

TEST(LogJson, UnknownFingerprintPrintsNullTypeAndReportsWhere) {
  const Bytes first = record(0, "SYNCAP_TRIGGER", encode(sample_trigger(0)));
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
  Bytes payload = encode(sample_trigger(0));
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
  Bytes payload = encode(sample_trigger(6));
  payload.push_back(0xaa);

  const LogRun run = run_print_log(record(0, "SYNCAP_TRIGGER", payload));

  EXPECT_EQ(run.status, kExitReportedErrors);
  ASSERT_EQ(run.lines.size(), 1u);
  EXPECT_EQ(run.lines[0]["fields"]["frame_number"], 6);
  EXPECT_NE(run.errors.find("trailing"), std::string::npos) << run.errors;
}

TEST(LcmLogReader, TruncatedFinalRecordReportsItsOffsetAndStops) {
  const Bytes first = record(0, "SYNCAP_TRIGGER", encode(sample_trigger(0)));
  Bytes log = first;
  append(log, record(1, "SYNCAP_TRIGGER", encode(sample_trigger(1))));
  log.resize(log.size() - 5);

  const LogRun run = run_print_log(log);

  EXPECT_EQ(run.status, kExitReportedErrors);
  EXPECT_EQ(run.lines.size(), 1u);
  EXPECT_NE(run.errors.find("truncated event at offset " + std::to_string(first.size()) + ": "),
            std::string::npos)
      << run.errors;
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
  const Bytes first = record(0, "SYNCAP_TRIGGER", encode(sample_trigger(0)));
  const Bytes garbage{0xde, 0xad, 0xbe, 0xef, 0xed, 0xa1, 0xda, 0x00, 0x42, 0x42, 0x42, 0x42, 0x01};
  Bytes log = first;
  append(log, garbage);
  append(log, record(1, "SYNCAP_TRIGGER", encode(sample_trigger(1))));

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

TEST(LogCommand, ChannelFilterMatchesWholeNames) {
  Bytes log = record(0, "SYNCAP_TRIGGER", encode(sample_trigger(0)));
  append(log, record(1, "SYNCAP_BLOBS_03", {9, 9, 9, 9, 9, 9, 9, 9}));  // unknown, but filtered
  append(log, record(2, "SYNCAP_TRIGGER_2", encode(sample_trigger(2))));

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

TEST(Base64, EncodesWithPadding) {
  EXPECT_EQ(base64_encode(Bytes{}), "");
  EXPECT_EQ(base64_encode(Bytes{'f'}), "Zg==");
  EXPECT_EQ(base64_encode(Bytes{'f', 'o'}), "Zm8=");
  EXPECT_EQ(base64_encode(Bytes{'f', 'o', 'o'}), "Zm9v");
  EXPECT_EQ(base64_encode(Bytes{'f', 'o', 'o', 'b', 'a', 'r'}), "Zm9vYmFy");
}

TEST(LogCommand, LcmSelfTestProbeIsShownAndNotAnError) {
  const std::string probe = "lcm self test";
  Bytes log = record(0, "LCM_SELF_TEST", Bytes(probe.begin(), probe.end()));
  append(log, record(1, "SYNCAP_TRIGGER", encode(sample_trigger(1))));

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
  Bytes log = record(0, "SYNCAP_TRIGGER", encode(sample_trigger(0)));
  const std::size_t bad_offset = log.size();
  append(log, record(1, "SYNCAP_BLOBS_02", test::blob_frame_with_negative_count(2, 0)));
  append(log, record(2, "SYNCAP_STATUS_02", test::camera_status_with_zero_string_length(2)));
  append(log, record(3, "SYNCAP_TRIGGER", encode(sample_trigger(1))));

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
