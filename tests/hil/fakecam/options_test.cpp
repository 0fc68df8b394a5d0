// The command line of syncap-fakecam: defaults, every option, and errors naming option and value.
#include "options.hpp"

#include "help_check.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace {

using syncap::fakecam::parse_options;
using syncap::fakecam::ParsedOptions;
using syncap::fakecam::TriggerSpec;

ParsedOptions parse(std::vector<const char*> arguments) { return parse_options(arguments); }

TEST(FakecamOptions, NeedsOnlyAddressAndImages) {
  const ParsedOptions parsed = parse({"--address", "127.0.0.7", "--images", "/data/cam07"});
  ASSERT_EQ(parsed.result, ParsedOptions::Result::run) << parsed.error;
  EXPECT_EQ(parsed.options.address, "127.0.0.7");
  EXPECT_EQ(parsed.options.images, "/data/cam07");
  EXPECT_EQ(parsed.options.serial, "SYNCAP-FAKE-7");
  EXPECT_EQ(parsed.options.trigger.kind, TriggerSpec::Kind::software);
  EXPECT_EQ(parsed.options.delay_ms, 0);
  EXPECT_EQ(parsed.options.start_frame, 0u);
  EXPECT_EQ(parsed.options.link_mbps, 1000u);
  EXPECT_FALSE(parsed.options.loop);
  EXPECT_FALSE(parsed.options.drop.drops(0));
}

TEST(FakecamOptions, ReadsEveryOption) {
  const ParsedOptions parsed = parse({"--address",  "127.0.0.2", "--images",      "d",
                                      "--serial",   "CAM-A",     "--trigger",     "gpiosim:rig.1:5",
                                      "--drop",     "4,9",       "--seed",        "3",
                                      "--delay-ms", "25",        "--start-frame", "100",
                                      "--cache-mb", "0",         "--link-mbps",   "0",
                                      "--loop",     "--quiet"});
  ASSERT_EQ(parsed.result, ParsedOptions::Result::run) << parsed.error;
  const auto& o = parsed.options;
  EXPECT_EQ(o.serial, "CAM-A");
  EXPECT_EQ(o.trigger.kind, TriggerSpec::Kind::gpiosim);
  EXPECT_EQ(o.trigger.chip, "rig.1");
  EXPECT_EQ(o.trigger.line, 5u);
  EXPECT_EQ(o.trigger.describe(), "gpiosim:rig.1:5");
  EXPECT_TRUE(o.drop.drops(9));
  EXPECT_FALSE(o.drop.drops(5));
  EXPECT_EQ(o.seed, 3u);
  EXPECT_EQ(o.delay_ms, 25);
  EXPECT_EQ(o.start_frame, 100u);
  EXPECT_EQ(o.cache_mb, 0u);
  EXPECT_EQ(o.link_mbps, 0u);
  EXPECT_TRUE(o.loop);
  EXPECT_TRUE(o.quiet);
}

TEST(FakecamOptions, HelpWins) {
  EXPECT_EQ(parse({"--address", "x", "--help"}).result, ParsedOptions::Result::help);
}

// The usage text: every option with its meaning and default, the exit statuses.
TEST(FakecamOptions, UsageIsComplete) {
  syncap::test::expect_help_mentions(syncap::fakecam::usage(),
                                     {"usage: syncap-fakecam --address 127.0.0.X --images DIR",
                                      "--address A",
                                      "--images DIR",
                                      "--serial NAME",
                                      "(default SYNCAP-FAKE-<octet>)",
                                      "--trigger SOURCE",
                                      "software (default)",
                                      "gpiosim:NAME:LINE",
                                      "--drop LIST|RATE",
                                      "--seed N",
                                      "(default 1)",
                                      "--delay-ms N",
                                      "(default 0)",
                                      "--start-frame K",
                                      "--cache-mb N",
                                      "(default 256)",
                                      "--link-mbps N",
                                      "(default 1000; 0: unpaced)",
                                      "--loop",
                                      "--quiet",
                                      "2 for wrong arguments"});
}

struct BadCase {
  std::vector<const char*> arguments;
  std::string error;
};

TEST(FakecamOptions, RejectsWrongValuesNamingOptionAndValue) {
  const std::vector<BadCase> cases = {
      {{"--images", "d"}, "missing --address (e.g. --address 127.0.0.2)"},
      {{"--address", "127.0.0.2"}, "missing --images DIR"},
      {{"--address", "192.168.1.2", "--images", "d"},
       "invalid --address '192.168.1.2': must be an IPv4 address on the loopback, 127.x.y.z"},
      {{"--address", "127.0.0.2", "--images", "d", "--trigger", "line1"},
       "invalid --trigger 'line1': use software or gpiosim:NAME:LINE"},
      {{"--address", "127.0.0.2", "--images", "d", "--trigger", "gpiosim:rig:64"},
       "invalid --trigger 'gpiosim:rig:64': LINE must be 0 to 63"},
      {{"--address", "127.0.0.2", "--images", "d", "--trigger", "gpiosim:a/b:0"},
       "invalid --trigger 'gpiosim:a/b:0': 'a/b' is not a valid chip name (A-Z a-z 0-9 . _ -)"},
      {{"--address", "127.0.0.2", "--images", "d", "--drop", "5-3"},
       "invalid --drop '5-3': range '5-3' runs backwards"},
      {{"--address", "127.0.0.2", "--images", "d", "--delay-ms", "-1"},
       "invalid --delay-ms '-1': must be 0 to 60000 milliseconds"},
      {{"--address", "127.0.0.2", "--images", "d", "--serial", "SIXTEEN-CHARS-XX"},
       "invalid --serial 'SIXTEEN-CHARS-XX': must be 1 to 15 characters"},
      {{"--address", "127.0.0.2", "--images", "d", "--frobnicate"},
       "unknown option '--frobnicate'"},
      {{"--address", "127.0.0.2", "--images"}, "--images: 1 required TEXT missing"},
      {{"--address", "127.0.0.2", "--images", "d", "--seed", "nan"},
       "invalid --seed 'nan': not a number"},
  };
  for (const BadCase& c : cases) {
    const ParsedOptions parsed = parse(c.arguments);
    EXPECT_EQ(parsed.result, ParsedOptions::Result::invalid);
    EXPECT_EQ(parsed.error, c.error);
  }
}

}  // namespace
