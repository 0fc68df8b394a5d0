// syncap-hil-impair as a process inside hil/netns-run: what it forwards from one LCM URL to the
// other, what it counts, and its refusals of bad arguments.
#include <gtest/gtest.h>
#include <lcm/lcm-cpp.hpp>

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include <unistd.h>

#include "../fakecam/child_process.hpp"
#include "help_check.hpp"

namespace {

using syncap::test::ChildProcess;
using namespace std::chrono_literals;

constexpr const char* kBoardUrl = "udpm://239.255.76.67:7667?ttl=0";
constexpr const char* kHostUrl = "udpm://239.255.76.68:7668?ttl=0";
constexpr int kMessages = 200;

struct Received {
  std::map<std::string, std::vector<std::vector<uint8_t>>> by_channel;
  void on(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
    const auto* bytes = static_cast<const uint8_t*>(buffer->data);
    by_channel[channel].emplace_back(bytes, bytes + buffer->data_size);
  }
};

// The payload of message i: its index twice (so that no one flipped bit turns it into another
// message's payload), then a fixed pattern.
std::vector<uint8_t> payload(int i) {
  std::vector<uint8_t> bytes(40, 0x5a);
  bytes[0] = bytes[2] = static_cast<uint8_t>(i);
  bytes[1] = bytes[3] = static_cast<uint8_t>(i >> 8);
  return bytes;
}

class RelayTest : public ::testing::Test {
 protected:
  // Runs the relay with `options`, publishes kMessages on TEST_A and on TEST_B, collects what
  // arrives on the host's URL, stops the relay; its stats JSON in stats_.
  Received relay(const std::vector<std::string>& options) {
    // One file per test process: ctest runs the cases in parallel, all in the same /tmp.
    const std::string stats_path =
        ::testing::TempDir() + "impair-stats-" + std::to_string(getpid()) + ".json";
    std::vector<std::string> argv{SYNCAP_IMPAIR_EXE, "--in",    kBoardUrl, "--out",
                                  kHostUrl,          "--stats", stats_path};
    argv.insert(argv.end(), options.begin(), options.end());
    // The receiver asks for 4 MiB as the host does: 400 datagrams at once overflow the default.
    lcm::LCM board(kBoardUrl), host(std::string(kHostUrl) + "&recv_buf_size=4194304");
    Received received;
    host.subscribe(".*", &Received::on, &received);
    ChildProcess relay(argv);
    EXPECT_TRUE(relay.wait_for_output("relaying", 5s)) << relay.output();
    for (int i = 0; i < kMessages; ++i) {
      for (const char* channel : {"TEST_A", "TEST_B"}) {
        const auto bytes = payload(i);
        board.publish(channel, bytes.data(), static_cast<unsigned>(bytes.size()));
      }
      while (host.handleTimeout(1) > 0) {
      }
    }
    for (int idle = 0; idle < 5;) idle = host.handleTimeout(100) > 0 ? 0 : idle + 1;
    EXPECT_EQ(relay.stop(SIGINT), 0) << relay.output();
    for (int idle = 0; idle < 3;) idle = host.handleTimeout(100) > 0 ? 0 : idle + 1;
    std::ifstream file(stats_path);
    stats_ = nlohmann::json::parse(file, nullptr, false);
    output_ = relay.output();
    return received;
  }
  nlohmann::json stats_;
  std::string output_;
};

TEST_F(RelayTest, ForwardsEverythingUnchangedWithoutImpairment) {
  const Received got = relay({});
  for (const char* channel : {"TEST_A", "TEST_B"}) {
    const auto& messages = got.by_channel.at(channel);
    ASSERT_EQ(messages.size(), static_cast<std::size_t>(kMessages)) << channel;
    for (int i = 0; i < kMessages; ++i) EXPECT_EQ(messages[i], payload(i)) << channel << " " << i;
    EXPECT_EQ(stats_["channels"][channel]["forwarded"], kMessages);
  }
  EXPECT_EQ(stats_["total"]["dropped"], 0);
}

// Loss, duplication and corruption at 30 %: what arrives is what the relay says it did.
TEST_F(RelayTest, ArrivalsMatchTheCounts) {
  const Received got = relay({"--loss", "30%", "--duplicate", "30%", "--corrupt", "30%"});
  for (const char* channel : {"TEST_A", "TEST_B"}) {
    const auto& counts = stats_["channels"][channel];
    const auto& messages = got.by_channel.at(channel);
    EXPECT_EQ(counts["received"], kMessages);
    EXPECT_EQ(counts["forwarded"].get<int>(), static_cast<int>(messages.size()));
    EXPECT_EQ(counts["received"].get<int>() - counts["dropped"].get<int>() +
                  counts["duplicated"].get<int>(),
              counts["forwarded"].get<int>());
    EXPECT_NEAR(counts["dropped"].get<int>(), 0.3 * kMessages, 0.3 * kMessages * 0.5);
    // A corrupted message differs from every original in one bit; count those that arrived.
    int one_bit_off = 0;
    for (const auto& m : messages) {
      int best = 1000;
      for (int i = 0; i < kMessages; ++i) {
        const auto original = payload(i);
        int bits = 0;
        for (std::size_t k = 0; k < m.size(); ++k) bits += __builtin_popcount(m[k] ^ original[k]);
        best = std::min(best, bits);
      }
      ASSERT_LE(best, 1);
      one_bit_off += best == 1;
    }
    // Each corrupted message arrives once, or twice when also duplicated.
    EXPECT_GE(one_bit_off, counts["corrupted"].get<int>());
    EXPECT_LE(one_bit_off, 2 * counts["corrupted"].get<int>());
    EXPECT_GT(counts["corrupted"].get<int>(), 0);
  }
  EXPECT_NE(output_.find("syncap-hil-impair: received 400, forwarded"), std::string::npos)
      << output_;
}

TEST_F(RelayTest, ReorderedMessagesArriveLaterButAllArrive) {
  const Received got = relay({"--reorder", "50%", "--reorder-delay-ms", "20"});
  const auto& messages = got.by_channel.at("TEST_A");
  ASSERT_EQ(messages.size(), static_cast<std::size_t>(kMessages));
  int out_of_order = 0;
  for (std::size_t k = 1; k < messages.size(); ++k)
    out_of_order += messages[k][0] < messages[k - 1][0];
  EXPECT_GT(out_of_order, 0);
  EXPECT_GT(stats_["channels"]["TEST_A"]["reordered"].get<int>(), 0);
}

TEST(RelayProgram, RefusesBadArgumentsNamingThem) {
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases{
      {{"--in", kBoardUrl}, "--out is required"},
      {{"--in", kBoardUrl, "--out", kBoardUrl}, "the relay would loop"},
      {{"--in", kBoardUrl, "--out", kHostUrl, "--loss", "150%"}, "--loss: '150%'"},
      {{"--in", kBoardUrl, "--out", kHostUrl, "--loss", "nan"}, "--loss: 'nan'"},
      {{"--in", kBoardUrl, "--out", kHostUrl, "--seed", "-1"}, "--seed: '-1'"},
      {{"--in", kBoardUrl, "--out", kHostUrl, "--reorder-delay-ms", "0"},
       "--reorder-delay-ms: '0'"},
      {{"--in", kBoardUrl, "--out", kHostUrl, "--bogus"}, "unknown option '--bogus'"},
  };
  for (const auto& [arguments, message] : cases) {
    std::vector<std::string> argv{SYNCAP_IMPAIR_EXE};
    argv.insert(argv.end(), arguments.begin(), arguments.end());
    ChildProcess relay(argv);
    EXPECT_EQ(relay.wait(5s), 2) << message;
    EXPECT_NE(relay.output().find(message), std::string::npos) << relay.output();
  }
}

// --help: every option with its meaning and default, what it prints, the exit statuses.
TEST(RelayProgram, HelpIsComplete) {
  ChildProcess relay({SYNCAP_IMPAIR_EXE, "--help"});
  EXPECT_EQ(relay.wait(5s), 0);
  syncap::test::expect_help_mentions(
      relay.output(), {"--in URL", "--out URL", "--loss P", "0.05 or 5% (default 0)",
                       "--duplicate P", "--reorder P", "--reorder-delay-ms N", "(default 10)",
                       "--corrupt P", "--seed N", "(default 1)", "--stats FILE", "--quiet",
                       "syncap-hil-impair: relaying IN -> OUT", "2 for wrong arguments"});
}

}  // namespace
