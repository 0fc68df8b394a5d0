// syncap/cli/options.hpp: the exit rule of every program's option parsing and the number checks
// CLI11 lacks.
#include "syncap/cli/options.hpp"
#include "help_check.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

namespace syncap::cli {
namespace {

struct Parsed {
  std::optional<int> status;
  std::string out, err;
};

Parsed parse_with(CLI::App& app, const std::vector<std::string>& args) {
  std::ostringstream out, err;
  Parsed p;
  p.status = parse(app, args, out, err);
  p.out = out.str();
  p.err = err.str();
  return p;
}

TEST(CliOptions, WholeNumbersAreDecimalAndInRange) {
  long long n = 0;
  App app("prog", "about", "exit statuses");
  add_checked(app, "--n", n, "N", whole_in(1, 100), "a number");
  EXPECT_FALSE(parse_with(app, {"--n", "010"}).status);
  EXPECT_EQ(n, 10);  // not octal 8
  for (const std::string bad : {"0x10", "0", "101", "2xyz", "1.5", "nan", ""}) {
    const Parsed p = parse_with(app, {"--n", bad});
    EXPECT_EQ(p.status, kExitUsage) << bad;
    EXPECT_EQ(p.err.rfind("prog: --n: '" + bad + "' is not a whole number in [1, 100]\n", 0), 0u)
        << p.err;
  }
}

TEST(CliOptions, UnsignedWholeNumbersRefuseNegatives) {
  std::uint64_t seed = 0;
  App app("prog", "about", "exit statuses");
  add_checked(app, "--seed", seed, "N", whole_in<std::uint64_t>(0, UINT64_MAX), "a seed");
  EXPECT_FALSE(parse_with(app, {"--seed", "18446744073709551615"}).status);
  EXPECT_EQ(seed, UINT64_MAX);
  EXPECT_EQ(parse_with(app, {"--seed", "-1"}).status, kExitUsage);  // strtoull would wrap it
}

TEST(CliOptions, NumbersAreFinite) {
  double x = 0;
  App app("prog", "about", "exit statuses");
  add_checked(app, "--x", x, "X", number_in(0, 0.5), "a share");
  EXPECT_FALSE(parse_with(app, {"--x", "0.25"}).status);
  EXPECT_EQ(x, 0.25);
  for (const std::string bad : {"nan", "inf", "0.7", "-0.1", "0.1x", " 0.1"}) {
    const Parsed p = parse_with(app, {"--x", bad});
    EXPECT_EQ(p.status, kExitUsage) << bad;
    EXPECT_NE(p.err.find("--x: '" + bad + "' is not a number in [0, 0.5]"), std::string::npos)
        << p.err;
  }
  double y = 0;
  App any("prog", "about", "exit statuses");
  add_checked(any, "--y", y, "Y", finite(), "any number");
  EXPECT_EQ(parse_with(any, {"--y", "-nan"}).status, kExitUsage);
  EXPECT_FALSE(parse_with(any, {"--y", "-1e3"}).status);
  EXPECT_EQ(y, -1000);
}

TEST(CliOptions, WordsOneOf) {
  std::string mode;
  App app("prog", "about", "exit statuses");
  app.add_option("--mode", mode, "auto or all")->check(one_of({"auto", "all"}));
  EXPECT_FALSE(parse_with(app, {"--mode", "all"}).status);
  const Parsed p = parse_with(app, {"--mode", "some"});
  EXPECT_EQ(p.status, kExitUsage);
  EXPECT_NE(p.err.find("--mode: 'some' is not one of auto, all"), std::string::npos) << p.err;
}

TEST(CliOptions, HelpExitsZeroAndUsageErrorsTwoWithTheHelp) {
  int n = 3;
  App app("prog", "above the options", "below the options");
  add_checked(app, "--n", n, "N", whole_in(1, 9), "how many (default 3)");
  const Parsed help = parse_with(app, {"--help"});
  EXPECT_EQ(help.status, kExitOk);
  EXPECT_EQ(help.err, "");
  syncap::test::expect_help_mentions(
      help.out, {"above the options", "--n N", "how many (default 3)", "below the options"});
  const Parsed unknown = parse_with(app, {"--x", "1", "--n", "2"});
  EXPECT_EQ(unknown.status, kExitUsage);
  EXPECT_EQ(unknown.err.rfind("prog: unknown option '--x'\n", 0), 0u) << unknown.err;
  EXPECT_NE(unknown.err.find("below the options"), std::string::npos);
  const Parsed extra = parse_with(app, {"file"});
  EXPECT_EQ(extra.err.rfind("prog: unexpected argument 'file'\n", 0), 0u) << extra.err;
  // An option given twice takes the last value, as the argv loops did.
  EXPECT_FALSE(parse_with(app, {"--n", "2", "--n", "5"}).status);
  EXPECT_EQ(n, 5);
}

TEST(CliOptions, ChecksAfterParsingAreUsageErrors) {
  App app("prog", "about", "exit statuses");
  std::ostringstream out, err;
  const std::vector<std::string> none;
  EXPECT_EQ(
      parse(app, none, out, err, [] { throw CLI::ValidationError("give either --a or --b"); }),
      kExitUsage);
  EXPECT_EQ(err.str().rfind("prog: give either --a or --b\n", 0), 0u) << err.str();
}

}  // namespace
}  // namespace syncap::cli
