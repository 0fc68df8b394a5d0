// Inside the private namespace: two processes exchange every syncap message type over LCM's
// default multicast URL, and each type at its maximum content travels as one UDP datagram.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>
#include <lcm/lcm-cpp.hpp>

#include <chrono>
#include <cstring>
#include <thread>
#include <vector>

#include "../proto/max_messages.hpp"
#include "syncap/proto/channels.hpp"
#include "syncap/proto/subscriber.hpp"

namespace syncap {
namespace {

constexpr const char* kGroup = "239.255.76.67";
constexpr uint16_t kPort = 7667;
// syncap-trigger's heartbeat channel (firmware/src/trigger_main.c, docs/design/architecture.md).
constexpr const char* kTriggerStatusChannel = "SYNCAP_TRIGGER_STATUS";

// Publishes one of each message type at maximum content, `rounds` times, from a child process.
pid_t spawn_publisher(int rounds) {
  const pid_t pid = fork();
  if (pid != 0) return pid;
  lcm::LCM lcm(proto::kDefaultLcmUrl);
  if (!lcm.good()) _exit(3);
  for (int i = 0; i < rounds; ++i) {
    const trigger_t trigger = test::max_trigger();
    lcm.publish(proto::kTriggerChannel, &trigger);
    const blob_frame_t blobs = test::max_blob_frame();
    lcm.publish(proto::blob_channel(99), &blobs);
    const silhouette_part_t part = test::max_silhouette_part();
    lcm.publish(proto::silhouette_channel(99), &part);
    const image_patch_t patch = test::max_image_patch();
    lcm.publish(proto::patch_channel(99), &patch);
    const camera_status_t status = test::max_camera_status();
    lcm.publish(proto::status_channel(99), &status);
    const edge_command_t command = test::max_edge_command();
    lcm.publish(proto::kEdgeCommandChannel, &command);
    const clip_polygon_t clip = test::max_clip_polygon();
    lcm.publish(proto::kEdgeClipChannel, &clip);
    const trigger_status_t trigger_status = test::max_trigger_status();
    lcm.publish(kTriggerStatusChannel, &trigger_status);
    const marker_frame_t markers = test::max_marker_frame();
    lcm.publish(proto::kMarkersChannel, &markers);
    const hull_frame_t hull = test::max_hull_frame();
    lcm.publish(proto::kHullChannel, &hull);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  _exit(0);
}

int wait_for_exit(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(LcmExchange, TwoProcessesExchangeEveryMessageType) {
  lcm::LCM lcm(proto::kDefaultLcmUrl);
  ASSERT_TRUE(lcm.good()) << "LCM multicast unavailable: is this inside hil/netns-run?";
  std::map<std::string, int> received;
  std::vector<blob_frame_t> frames;
  std::vector<camera_status_t> statuses;
  proto::Subscriber sub(lcm, [](const std::string& e) { ADD_FAILURE() << e; });
  auto count = [&](const std::string& channel) { ++received[channel]; };
  sub.subscribe<trigger_t>(proto::kTriggerChannel,
                           [&](const trigger_t&, const std::string& c) { count(c); });
  sub.subscribe<blob_frame_t>(
      "SYNCAP_BLOBS_.*", [&](const blob_frame_t& f, const std::string&) { frames.push_back(f); });
  sub.subscribe<camera_status_t>(
      "SYNCAP_STATUS_.*",
      [&](const camera_status_t& s, const std::string&) { statuses.push_back(s); });
  std::vector<marker_frame_t> markers;
  sub.subscribe<marker_frame_t>(
      proto::kMarkersChannel,
      [&](const marker_frame_t& m, const std::string&) { markers.push_back(m); });
  std::vector<hull_frame_t> hulls;
  sub.subscribe<hull_frame_t>(
      proto::kHullChannel, [&](const hull_frame_t& h, const std::string&) { hulls.push_back(h); });
  const pid_t child = spawn_publisher(3);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (std::chrono::steady_clock::now() < deadline &&
         (frames.size() < 3 || statuses.size() < 3 || markers.size() < 3 || hulls.size() < 3)) {
    lcm.handleTimeout(50);
  }
  ASSERT_EQ(wait_for_exit(child), 0);
  EXPECT_EQ(received[proto::kTriggerChannel], 3);
  ASSERT_EQ(frames.size(), 3u);
  ASSERT_EQ(statuses.size(), 3u);
  const blob_frame_t expected = test::max_blob_frame();
  EXPECT_EQ(frames[0].blobs.size(), expected.blobs.size());
  EXPECT_FLOAT_EQ(frames[2].blobs.back().y, expected.blobs.back().y);
  EXPECT_EQ(statuses[1].message, test::max_camera_status().message);
  ASSERT_EQ(markers.size(), 3u);
  EXPECT_EQ(markers[2].markers.size(), static_cast<std::size_t>(marker_frame_t::MAX_MARKERS));
  ASSERT_EQ(hulls.size(), 3u);
  EXPECT_DOUBLE_EQ(hulls[1].volume_mm3, test::max_hull_frame().volume_mm3);
  EXPECT_EQ(sub.malformed(), 0);
}

TEST(LcmExchange, MalformedMessageIsNamedAndLaterOnesStillArrive) {
  lcm::LCM lcm(proto::kDefaultLcmUrl);
  ASSERT_TRUE(lcm.good());
  std::vector<std::string> errors;
  std::vector<blob_frame_t> frames;
  proto::Subscriber sub(lcm, [&](const std::string& e) { errors.push_back(e); });
  sub.subscribe<blob_frame_t>(
      "SYNCAP_BLOBS_.*", [&](const blob_frame_t& f, const std::string&) { frames.push_back(f); });
  const std::vector<uint8_t> garbage(40, 0xab);
  lcm.publish(proto::blob_channel(5), garbage.data(), static_cast<unsigned>(garbage.size()));
  const blob_frame_t good = test::blob_frame_with(2);
  lcm.publish(proto::blob_channel(5), &good);
  for (int i = 0; i < 40 && frames.empty(); ++i) lcm.handleTimeout(50);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_NE(errors[0].find("malformed blob_frame_t on channel SYNCAP_BLOBS_05 (40 bytes)"),
            std::string::npos)
      << errors[0];
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].blobs.size(), 2u);
}

// A receiver that stalls (a host descheduled for a few hundred ms, a page-cache flush) keeps
// what arrived meanwhile: LCM's own limit, 30 waiting messages a subscription, dropped the 31st
// of 6 cameras' blob messages without a word (likely what failed CI's
// hil.run.RingSixCameraPersonShort once).
TEST(LcmExchange, StalledReceiverKeepsEveryMessageThatArrived) {
  lcm::LCM lcm(proto::kDefaultLcmUrl);
  ASSERT_TRUE(lcm.good());
  std::vector<blob_frame_t> frames;
  proto::Subscriber sub(lcm, [](const std::string& e) { ADD_FAILURE() << e; });
  sub.subscribe<blob_frame_t>(
      "SYNCAP_BLOBS_.*", [&](const blob_frame_t& f, const std::string&) { frames.push_back(f); });
  constexpr int kCameras = 6, kFrames = 50;
  const pid_t pid = fork();
  if (pid == 0) {
    lcm::LCM publisher(proto::kDefaultLcmUrl);
    if (!publisher.good()) _exit(3);
    for (int frame = 0; frame < kFrames; ++frame) {
      for (int camera = 0; camera < kCameras; ++camera) {
        blob_frame_t m = test::blob_frame_with(3);
        m.camera_id = static_cast<int16_t>(camera);
        m.frame_number = frame;
        publisher.publish(proto::blob_channel(camera), &m);
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    _exit(0);
  }
  ASSERT_EQ(wait_for_exit(pid), 0);  // the stall: everything is sent before anything is handled
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (std::chrono::steady_clock::now() < deadline && frames.size() < kCameras * kFrames) {
    lcm.handleTimeout(50);
  }
  ASSERT_EQ(frames.size(), static_cast<std::size_t>(kCameras * kFrames));
  EXPECT_EQ(frames.back().frame_number, kFrames - 1);
  EXPECT_EQ(frames.back().camera_id, kCameras - 1);
}

// A raw socket on the multicast group sees LCM's datagrams as they are on the wire.
int open_group_socket() {
  const int fd = socket(AF_INET, SOCK_DGRAM, 0);
  const int one = 1;
  setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(kPort);
  addr.sin_addr.s_addr = htonl(INADDR_ANY);
  if (bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) return -1;
  ip_mreq mreq{};
  inet_pton(AF_INET, kGroup, &mreq.imr_multiaddr);
  mreq.imr_interface.s_addr = htonl(INADDR_ANY);
  if (setsockopt(fd, IPPROTO_IP, IP_ADD_MEMBERSHIP, &mreq, sizeof mreq) != 0) return -1;
  timeval timeout{2, 0};
  setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
  return fd;
}

TEST(LcmExchange, EveryMaximalMessageIsOneDatagram) {
  // The SIL/PATCH/CMD channels are not in the Subscriber test above; here every channel counts.
  const int fd = open_group_socket();
  ASSERT_GE(fd, 0) << "cannot join " << kGroup << ": " << std::strerror(errno);
  const pid_t child = spawn_publisher(1);
  std::map<std::string, int> short_messages;
  int fragments = 0;
  std::vector<uint8_t> buf(65536);
  for (int i = 0; i < 8; ++i) {
    const ssize_t n = recv(fd, buf.data(), buf.size(), 0);
    ASSERT_GT(n, 8) << "datagram " << i << " missing";
    if (std::memcmp(buf.data(), "LC02", 4) == 0) {
      ++short_messages[reinterpret_cast<const char*>(buf.data() + 8)];
    } else {
      ++fragments;
    }
  }
  close(fd);
  ASSERT_EQ(wait_for_exit(child), 0);
  EXPECT_EQ(fragments, 0) << "a message was fragmented (LC03)";
  EXPECT_EQ(short_messages.size(), 8u);
  EXPECT_EQ(short_messages[proto::silhouette_channel(99)], 1);
  EXPECT_EQ(short_messages[proto::patch_channel(99)], 1);
  EXPECT_EQ(short_messages[proto::blob_channel(99)], 1);
  EXPECT_EQ(short_messages[kTriggerStatusChannel], 1);
  EXPECT_EQ(short_messages[proto::kEdgeClipChannel], 1);
}

}  // namespace
}  // namespace syncap
