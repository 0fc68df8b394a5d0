#include "ctl_command.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <sstream>
#include <vector>

#include "subcommand.hpp"
#include "syncap/proto/command_auth.hpp"

namespace syncap::tools {
namespace {

struct CommandRun {
  int status;
  std::string out, err;
};

CommandRun run(int (*command)(std::span<const std::string>, std::ostream&, std::ostream&),
               std::vector<std::string> args) {
  std::ostringstream out, err;
  const int status = command(args, out, err);
  return {status, out.str(), err.str()};
}

std::vector<std::string> values(std::initializer_list<std::string> v) { return v; }

TEST(CtlActions, EachActionMakesItsCommand) {
  EXPECT_EQ(command_of_action("stop", {}).command, edge_command_t::STOP);
  EXPECT_EQ(command_of_action("start", {}).command, edge_command_t::START);
  EXPECT_EQ(command_of_action("shutdown", {}).command, edge_command_t::SHUTDOWN);
  const auto train = values({"40"});
  EXPECT_EQ(command_of_action("train-background", train).int_value, 40);
  const auto threshold = values({"0"});
  const edge_command_t t = command_of_action("threshold", threshold);
  EXPECT_EQ(t.command, edge_command_t::SET_THRESHOLD);
  EXPECT_EQ(t.int_value, 0) << "0: the threshold from the histogram";
  const auto every = values({"30"});
  const edge_command_t p = command_of_action("patches", every);
  EXPECT_EQ(p.command, edge_command_t::SET_PATCH_EVERY);
  EXPECT_EQ(p.int_value, 30);
  const auto too_many = values({"100001"});
  EXPECT_THROW(command_of_action("patches", too_many), std::invalid_argument);
  const auto roi = values({"8,16,320,240"});
  const edge_command_t r = command_of_action("roi", roi);
  EXPECT_EQ(r.command, edge_command_t::SET_ROI);
  EXPECT_EQ(r.roi_x, 8);
  EXPECT_EQ(r.roi_y, 16);
  EXPECT_EQ(r.roi_width, 320);
  EXPECT_EQ(r.roi_height, 240);
  const auto full = values({"full"});
  EXPECT_EQ(command_of_action("roi", full).roi_width, 0) << "full: the whole sensor";
  const auto exposure = values({"2500.5"});
  EXPECT_DOUBLE_EQ(command_of_action("exposure", exposure).real_value, 2500.5);
}

TEST(CtlActions, BadActionsAndValuesAreNamed) {
  const auto expect_invalid = [](const std::string& action, std::vector<std::string> v,
                                 const std::string& words) {
    try {
      command_of_action(action, v);
      FAIL() << action << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  expect_invalid("reboot", {}, "unknown action 'reboot'");
  expect_invalid("stop", {"1"}, "stop takes 0 value(s)");
  expect_invalid("threshold", {}, "threshold takes 1 value(s)");
  expect_invalid("threshold", {"256"}, "threshold DN '256'");
  expect_invalid("threshold", {"4x"}, "threshold DN '4x'");
  expect_invalid("exposure", {"nan"}, "exposure US 'nan'");
  expect_invalid("roi", {"1,2,3"}, "roi '1,2,3'");
  expect_invalid("roi", {"1,2,3,4,5"}, "roi '1,2,3,4,5'");
  expect_invalid("roi", {"1,2,-3,4"}, "roi X,Y,W,H '-3'");
}

TEST(CtlAcknowledgements, OnlyTheHeartbeatsNamingTheCommandAnswer) {
  Acknowledgements acks(/*sender=*/77, /*sequence=*/3);
  camera_status_t s{};
  s.camera_id = 1;
  s.last_command_sender = 77;
  s.last_command_sequence = 2;  // an earlier command of the same sender
  s.last_command_result = camera_status_t::COMMAND_ACCEPTED;
  EXPECT_FALSE(acks.take(s));
  EXPECT_FALSE(acks.answer(1).has_value());
  s.last_command_sequence = 3;
  s.last_command_result = camera_status_t::COMMAND_BAD_MAC;
  EXPECT_TRUE(acks.take(s));
  EXPECT_EQ(acks.answer(1), camera_status_t::COMMAND_BAD_MAC);
  s.camera_id = 2;
  s.last_command_sender = 78;  // another sender's command
  EXPECT_FALSE(acks.take(s));
  EXPECT_EQ(acks.heard().size(), 2u);
}

TEST(CtlCommand, UsageErrorsExitTwoAndHelpIsComplete) {
  const CommandRun help = run(ctl_command, {"--help"});
  EXPECT_EQ(help.status, kExitOk);
  for (const char* word : {"--command-key", "--camera", "--lcm-url", "--wait-s", "train-background",
                           "threshold", "roi X,Y,W,H", "exposure", "gain", "status"})
    EXPECT_NE(help.out.find(word), std::string::npos) << word << " missing from:\n" << help.out;
  EXPECT_EQ(run(ctl_command, {}).status, kExitUsage);
  const CommandRun no_key = run(ctl_command, {"stop"});
  EXPECT_EQ(no_key.status, kExitUsage);
  EXPECT_NE(no_key.err.find("--command-key FILE is required"), std::string::npos) << no_key.err;
  const CommandRun bad_camera = run(ctl_command, {"stop", "--camera", "100", "--key", "k"});
  EXPECT_EQ(bad_camera.status, kExitUsage);
  EXPECT_NE(bad_camera.err.find("--camera '100'"), std::string::npos) << bad_camera.err;
  const CommandRun unknown = run(ctl_command, {"stop", "--colour", "red"});
  EXPECT_EQ(unknown.status, kExitUsage);
  EXPECT_NE(unknown.err.find("--colour"), std::string::npos) << unknown.err;
  const CommandRun missing_key =
      run(ctl_command, {"stop", "--key", "/nonexistent/command.key", "--lcm-url", "memq://"});
  EXPECT_EQ(missing_key.status, kExitUsage);
  EXPECT_NE(missing_key.err.find("/nonexistent/command.key"), std::string::npos) << missing_key.err;
}

TEST(KeygenCommand, WritesAKeyOnlyItsOwnerReadsAndNeverOverwritesSilently) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("syncap-keygen-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string key = (dir / "command.key").string();
  const CommandRun first = run(keygen_command, {"--out", key});
  ASSERT_EQ(first.status, kExitOk) << first.err;
  const auto bytes = proto::CommandKey::load(key).bytes();
  struct stat info {};
  ASSERT_EQ(::stat(key.c_str(), &info), 0);
  EXPECT_EQ(info.st_mode & 0777, 0600u);
  const CommandRun again = run(keygen_command, {"--out", key});
  EXPECT_EQ(again.status, kExitUsage);
  EXPECT_NE(again.err.find("--force"), std::string::npos) << again.err;
  EXPECT_EQ(proto::CommandKey::load(key).bytes(), bytes) << "the key changed without --force";
  EXPECT_EQ(run(keygen_command, {"--out", key, "--force"}).status, kExitOk);
  EXPECT_NE(proto::CommandKey::load(key).bytes(), bytes);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace syncap::tools
