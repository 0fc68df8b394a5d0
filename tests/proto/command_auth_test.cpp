#include "syncap/proto/command_auth.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>

#include "syncap/clip_polygon_t.hpp"
#include "syncap/edge_command_t.hpp"

namespace syncap::proto {
namespace {

constexpr int64_t kSecond = 1'000'000'000;
constexpr int64_t kNow = 1'800'000'000 * kSecond;  // a fixed "now" for the guard's clock

class CommandAuthTest : public ::testing::Test {
 protected:
  CommandAuthTest() : key_(CommandKey::generate()), guard_(key_, 5 * kSecond, kNow - kSecond) {}

  // A command signed now (by the sender's clock), as syncap ctl sends it.
  edge_command_t command(CommandSigner& signer, int8_t code = edge_command_t::STOP) {
    edge_command_t c{};
    c.camera_id = 3;
    c.command = code;
    signer.sign(c);
    return c;
  }
  // Re-signs `c` with the key, at sender time `sent_ns` (the signer always takes "now").
  void resign_at(edge_command_t& c, int64_t sent_ns) {
    c.sent_realtime_ns = sent_ns;
    const CommandMac mac = mac_of_encoding(encoding_without_mac(c), key_);
    std::memcpy(c.mac, mac.data(), mac.size());
  }

  CommandKey key_;
  CommandGuard guard_;
};

TEST_F(CommandAuthTest, ASignedCommandIsAcceptedOnceAndOnlyUnchanged) {
  CommandSigner signer(key_);
  edge_command_t c = command(signer);
  EXPECT_TRUE(mac_valid(c, key_));
  resign_at(c, kNow);
  EXPECT_EQ(guard_.check(c, kNow), CommandCheck::kAccepted);
  EXPECT_EQ(guard_.check(c, kNow + 1), CommandCheck::kReplayed);
  // Each field is covered: change any and the MAC fails.
  edge_command_t changed = c;
  changed.int_value = 1;
  EXPECT_EQ(guard_.check(changed, kNow), CommandCheck::kBadMac);
  changed = c;
  changed.camera_id = edge_command_t::ALL_CAMERAS;
  EXPECT_EQ(guard_.check(changed, kNow), CommandCheck::kBadMac);
  changed = c;
  changed.sequence += 1;  // a replay with a new sequence number
  EXPECT_EQ(guard_.check(changed, kNow), CommandCheck::kBadMac);
}

TEST_F(CommandAuthTest, AnotherKeyOrNoKeyIsRefused) {
  CommandSigner stranger(CommandKey::generate());
  edge_command_t c = command(stranger);
  EXPECT_EQ(guard_.check(c, c.sent_realtime_ns), CommandCheck::kBadMac);
  CommandGuard keyless(std::nullopt, 5 * kSecond, 0);
  CommandSigner signer(key_);
  const edge_command_t genuine = command(signer);
  EXPECT_EQ(keyless.check(genuine, genuine.sent_realtime_ns), CommandCheck::kNoKey);
  EXPECT_FALSE(keyless.has_key());
}

TEST_F(CommandAuthTest, TheTimeWindowAndTheStartBoundTheReplays) {
  CommandSigner signer(key_);
  edge_command_t c = command(signer);
  resign_at(c, kNow - 6 * kSecond);  // older than the window
  EXPECT_EQ(guard_.check(c, kNow), CommandCheck::kOutsideWindow);
  resign_at(c, kNow + 6 * kSecond);  // from the future
  EXPECT_EQ(guard_.check(c, kNow), CommandCheck::kOutsideWindow);
  resign_at(c, INT64_MIN);  // no overflow into the window
  EXPECT_EQ(guard_.check(c, kNow), CommandCheck::kOutsideWindow);
  resign_at(c, kNow - 2 * kSecond);  // in the window, but before the receiver started
  EXPECT_EQ(guard_.check(c, kNow), CommandCheck::kBeforeStart);
  resign_at(c, kNow);
  EXPECT_EQ(guard_.check(c, kNow), CommandCheck::kAccepted);
}

TEST_F(CommandAuthTest, SequencesCountPerSenderAndOldSendersAreForgotten) {
  CommandSigner host(key_);
  CommandSigner ctl(key_);
  ASSERT_NE(host.sender(), ctl.sender());
  edge_command_t a1 = command(host);
  edge_command_t a2 = command(host);
  edge_command_t b1 = command(ctl);
  resign_at(a2, kNow);
  resign_at(b1, kNow);
  resign_at(a1, kNow);
  EXPECT_EQ(guard_.check(a2, kNow), CommandCheck::kAccepted);
  EXPECT_EQ(guard_.check(b1, kNow), CommandCheck::kAccepted) << "another sender's sequence 1";
  EXPECT_EQ(guard_.check(a1, kNow), CommandCheck::kReplayed) << "below the sender's last";
  EXPECT_EQ(guard_.senders_remembered(), 2u);
  // Ten seconds later both are outside the window: forgotten, and their replays still refused.
  EXPECT_EQ(guard_.check(a2, kNow + 10 * kSecond), CommandCheck::kOutsideWindow);
  edge_command_t later = command(host);
  resign_at(later, kNow + 10 * kSecond);
  EXPECT_EQ(guard_.check(later, kNow + 10 * kSecond), CommandCheck::kAccepted);
  EXPECT_EQ(guard_.senders_remembered(), 1u);
}

TEST_F(CommandAuthTest, ClipPolygonsAreSignedTheSameWay) {
  CommandSigner signer(key_);
  clip_polygon_t clip{};
  clip.camera_id = 2;
  clip.image_width = 640;
  clip.image_height = 480;
  clip.num_points = 3;
  clip.x = {0, 100, 0};
  clip.y = {0, 0, 100};
  signer.sign(clip);
  EXPECT_TRUE(mac_valid(clip, key_));
  clip.x[1] = 600;  // the polygon moved by someone else
  EXPECT_FALSE(mac_valid(clip, key_));
}

class CommandKeyFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("syncap-key-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  static void expect_error(const std::string& file, const std::string& words) {
    try {
      CommandKey::load(file);
      FAIL() << file << " loaded";
    } catch (const CommandKeyError& e) {
      EXPECT_NE(std::string(e.what()).find(file), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  }
  std::filesystem::path dir_;
};

TEST_F(CommandKeyFileTest, SavedKeysLoadBackAndAreTheOwnersAlone) {
  const CommandKey key = CommandKey::generate();
  key.save(path("command.key"), /*replace=*/false);
  struct stat info {};
  ASSERT_EQ(::stat(path("command.key").c_str(), &info), 0);
  EXPECT_EQ(info.st_mode & 0777, 0600u);
  EXPECT_EQ(CommandKey::load(path("command.key")).bytes(), key.bytes());
  EXPECT_THROW(CommandKey::generate().save(path("command.key"), false), CommandKeyError)
      << "an installation's key was overwritten without --force";
  EXPECT_EQ(CommandKey::load(path("command.key")).bytes(), key.bytes());
  EXPECT_NE(CommandKey::generate().bytes(), key.bytes());
}

TEST_F(CommandKeyFileTest, BadKeyFilesAreNamedWithTheProblem) {
  expect_error(path("missing.key"), "No such file");
  CommandKey::generate().save(path("open.key"), false);
  ::chmod(path("open.key").c_str(), 0644);
  expect_error(path("open.key"), "readable by others (mode 644)");
  std::ofstream(path("short.key")) << "abcd\n";
  ::chmod(path("short.key").c_str(), 0600);
  expect_error(path("short.key"), "64 hexadecimal digits");
  std::ofstream(path("nothex.key")) << std::string(64, 'g') << "\n";
  ::chmod(path("nothex.key").c_str(), 0600);
  expect_error(path("nothex.key"), "64 hexadecimal digits");
}

}  // namespace
}  // namespace syncap::proto
