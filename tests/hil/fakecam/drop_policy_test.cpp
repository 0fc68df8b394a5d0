// --drop of syncap-fakecam: lists, ranges, rates, and their errors.
#include "drop_policy.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace {

using syncap::fakecam::DropPolicy;

TEST(DropPolicy, DropsNothingByDefault) {
  const DropPolicy policy;
  for (std::uint64_t f = 0; f < 1000; ++f) EXPECT_FALSE(policy.drops(f));
  EXPECT_EQ(policy.describe(), "nothing");
}

TEST(DropPolicy, DropsExactlyTheListedFramesAndRanges) {
  const DropPolicy policy = DropPolicy::parse("3,17,40-42", 1);
  for (std::uint64_t f = 0; f < 100; ++f) {
    const bool listed = f == 3 || f == 17 || (f >= 40 && f <= 42);
    EXPECT_EQ(policy.drops(f), listed) << f;
  }
  EXPECT_EQ(policy.describe(), "frames 3,17,40-42");
}

TEST(DropPolicy, DropsAboutTheRateReproduciblyPerSeed) {
  const DropPolicy a = DropPolicy::parse("0.1", 7);
  const DropPolicy b = DropPolicy::parse("10%", 7);
  const DropPolicy other_seed = DropPolicy::parse("0.1", 8);
  int dropped = 0;
  int differ = 0;
  for (std::uint64_t f = 0; f < 100'000; ++f) {
    EXPECT_EQ(a.drops(f), b.drops(f));
    dropped += a.drops(f);
    differ += a.drops(f) != other_seed.drops(f);
  }
  EXPECT_NEAR(dropped, 10'000, 400);
  EXPECT_GT(differ, 1000);
  EXPECT_EQ(a.describe(), "0.1 of frames (seed 7)");
}

TEST(DropPolicy, RatesZeroAndOneDropNothingAndEverything) {
  const DropPolicy none = DropPolicy::parse("0.0", 1);
  const DropPolicy all = DropPolicy::parse("100%", 1);
  for (std::uint64_t f = 0; f < 1000; ++f) {
    EXPECT_FALSE(none.drops(f));
    EXPECT_TRUE(all.drops(f));
  }
}

TEST(DropPolicy, RejectsMalformedText) {
  for (const char* text :
       {"", "x", "3,", ",3", "3,,4", "5-3", "1-", "-2", "1.5", "-0.1", "200%", "nan%", "3 4"}) {
    EXPECT_THROW((void)DropPolicy::parse(text, 1), std::invalid_argument) << "'" << text << "'";
  }
}

}  // namespace
