#include "log_stats.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/lcm_log_reader.hpp"
#include "log_command.hpp"
#include "malformed_messages.hpp"
#include "subcommand.hpp"
#include "syncap/proto/blob_parts.hpp"
#include "syncap/proto/channels.hpp"
#include "syncap/proto/contour_codec.hpp"

namespace syncap::tools {
namespace {

template <class Msg>
std::vector<std::uint8_t> encoded(const Msg& msg) {
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(msg.getEncodedSize()));
  msg.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

class Log {
 public:
  template <class Msg>
  void add(const std::string& channel, const Msg& msg) {
    const auto record = io::encode_log_record(next_++, 0, channel, encoded(msg));
    bytes_.append(record.begin(), record.end());
  }
  std::istringstream stream() const { return std::istringstream(bytes_); }

 private:
  std::string bytes_;
  std::int64_t next_ = 0;
};

blob_frame_t frame(int camera, int64_t k, int blobs, int silhouette_parts) {
  blob_frame_t f{};
  f.camera_id = static_cast<int16_t>(camera);
  f.frame_number = k;
  f.image_width = 1280;
  f.image_height = 1024;
  f.part_count = 1;
  f.blobs.resize(static_cast<std::size_t>(blobs));
  f.num_blobs = f.total_blobs = static_cast<int16_t>(blobs);
  f.silhouette_parts = static_cast<int16_t>(silhouette_parts);
  return f;
}

TEST(LogStats, CountsDatagramBytesPerChannelAndPerFrame) {
  Log log;
  proto::Contour square{false, true, {{0, 0}, {100, 0}, {100, 100}, {0, 100}}};
  const auto sil = proto::encode_silhouette(2, 1, 1280, 1024, std::vector{square});
  ASSERT_EQ(sil.size(), 1u);
  log.add(proto::blob_channel(2), frame(2, 0, 16, 0));
  log.add(proto::blob_channel(2), frame(2, 1, 0, 1));
  log.add(proto::silhouette_channel(2), sil[0]);
  // 100 blobs: two parts, one frame.
  for (const auto& part : proto::split_blob_frame(frame(3, 0, 100, 0))) {
    log.add(proto::blob_channel(3), part);
  }
  std::istringstream in = log.stream();
  const TrafficStats stats = collect_traffic(in);

  EXPECT_EQ(stats.events, 5);
  const std::int64_t blob16 = datagram_bytes(proto::blob_channel(2), 48 + 16 * 23);
  const std::int64_t blob0 = datagram_bytes(proto::blob_channel(2), 48);
  EXPECT_EQ(stats.channels.at(proto::blob_channel(2)).datagram_bytes, blob16 + blob0);
  EXPECT_EQ(stats.channels.at(proto::blob_channel(2)).max_datagram_bytes, blob16);
  EXPECT_EQ(blob16, 8 + 16 + 48 + 16 * 23);  // "SYNCAP_BLOBS_02" is 15 characters

  const CameraTraffic& c2 = stats.cameras.at(2);
  EXPECT_EQ(c2.frames, 2);
  EXPECT_EQ(c2.silhouette_frames, 1);
  EXPECT_EQ(c2.silhouette_bytes,
            datagram_bytes(proto::silhouette_channel(2), encoded(sil[0]).size()));
  EXPECT_EQ(stats.cameras.at(3).frames, 1);
  EXPECT_EQ(stats.cameras.at(3).image_width, 1280);

  std::ostringstream text;
  print_traffic(stats, text);
  EXPECT_NE(text.str().find("SYNCAP_BLOBS_03"), std::string::npos) << text.str();
  EXPECT_NE(text.str().find("1310720"), std::string::npos) << text.str();  // raw 1280 x 1024
}

TEST(LogStats, UndecodableCameraMessagesAreCountedApart) {
  Log log;
  blob_frame_t broken = frame(1, 0, 1, 0);
  std::vector<std::uint8_t> bytes = encoded(broken);
  bytes.resize(bytes.size() - 5);
  const auto record = io::encode_log_record(0, 0, proto::blob_channel(1), bytes);
  std::istringstream in(std::string(record.begin(), record.end()));
  const TrafficStats stats = collect_traffic(in);
  EXPECT_EQ(stats.undecodable, 1);
  EXPECT_TRUE(stats.cameras.empty());
  EXPECT_EQ(stats.channels.at(proto::blob_channel(1)).messages, 1);
}

// Issue 15: the decoder threw std::length_error on a negative num_blobs and ended `syncap log`.
TEST(LogStats, NegativeArrayLengthIsCountedAndTheRestKept) {
  auto log = io::encode_log_record(0, 0, proto::blob_channel(1),
                                   test::blob_frame_with_negative_count(1, 0));
  const auto good = io::encode_log_record(1, 0, proto::blob_channel(1), encoded(frame(1, 1, 2, 0)));
  log.insert(log.end(), good.begin(), good.end());
  std::istringstream in(std::string(log.begin(), log.end()));
  const TrafficStats stats = collect_traffic(in);
  EXPECT_EQ(stats.events, 2);
  EXPECT_EQ(stats.undecodable, 1);
  EXPECT_EQ(stats.cameras.at(1).frames, 1);
}

// Issue 15: random bytes gave exit 0 and an empty table.
TEST(LogStats, FileWithoutAnyLogEventExitsTwoNamingFileAndOffset) {
  const std::string path =
      (std::filesystem::temp_directory_path() / ("syncap-random-" + std::to_string(getpid())))
          .string();
  {
    std::ofstream file(path, std::ios::binary);
    std::uint32_t x = 12345;
    for (int i = 0; i < 4096; ++i) {
      x = x * 1103515245u + 12345u;
      file.put(static_cast<char>(x >> 24));
    }
  }
  std::ostringstream out, err;
  const std::vector<std::string> args{"--stats", path};
  EXPECT_EQ(log_command(args, out, err), kExitUsage) << out.str();
  EXPECT_NE(err.str().find("syncap log: " + path +
                           ": no valid LCM log event found (damage from offset 0)"),
            std::string::npos)
      << err.str();
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace syncap::tools
