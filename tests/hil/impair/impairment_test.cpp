#include "impairment.hpp"

#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <string>

namespace syncap::hil {
namespace {

struct Tally {
  int drops = 0, duplicates = 0, reorders = 0, corruptions = 0;
};

Tally run(const Impairment& impairment, const std::string& channel, int messages) {
  Tally t;
  for (int i = 0; i < messages; ++i) {
    const auto d = impairment.decide(channel, static_cast<uint64_t>(i), 100);
    t.drops += d.drop;
    t.duplicates += d.duplicate;
    t.reorders += d.reorder;
    t.corruptions += d.flipped_bit.has_value();
  }
  return t;
}

TEST(Impairment, NoRatesChangeNothing) {
  const Tally t = run(Impairment({}, 7), "SYNCAP_BLOBS_00", 10000);
  EXPECT_EQ(t.drops + t.duplicates + t.reorders + t.corruptions, 0);
}

TEST(Impairment, RatesAreMetWithinSamplingError) {
  // 100000 draws: one standard deviation of a 5 % share is 0.07 %; allow 5 of them.
  const Impairment impairment({.loss = 0.05, .duplicate = 0.02, .reorder = 0.1, .corrupt = 0.01},
                              42);
  const Tally t = run(impairment, "SYNCAP_TRIGGER", 100000);
  EXPECT_NEAR(t.drops, 5000, 350);
  // Duplication, reordering and corruption apply to the 95 % that are not dropped.
  EXPECT_NEAR(t.duplicates, 0.02 * 95000, 5 * 43);
  EXPECT_NEAR(t.reorders, 0.1 * 95000, 5 * 92);
  EXPECT_NEAR(t.corruptions, 0.01 * 95000, 5 * 31);
}

TEST(Impairment, AllOrNothingRates) {
  const Tally all = run(Impairment({.loss = 1}, 3), "C", 1000);
  EXPECT_EQ(all.drops, 1000);
  EXPECT_EQ(all.duplicates + all.reorders + all.corruptions, 0);  // dropped: nothing else
  const Tally every = run(Impairment({.duplicate = 1, .reorder = 1, .corrupt = 1}, 3), "C", 1000);
  EXPECT_EQ(every.drops, 0);
  EXPECT_EQ(every.duplicates, 1000);
  EXPECT_EQ(every.reorders, 1000);
  EXPECT_EQ(every.corruptions, 1000);
}

TEST(Impairment, DecisionsDependOnSeedChannelAndIndexOnly) {
  const ImpairmentRates rates{.loss = 0.3, .duplicate = 0.3, .reorder = 0.3, .corrupt = 0.3};
  const Impairment a(rates, 11), b(rates, 11), other_seed(rates, 12);
  int differ_by_seed = 0, differ_by_channel = 0;
  for (uint64_t i = 0; i < 200; ++i) {
    const auto da = a.decide("SYNCAP_BLOBS_01", i, 64);
    const auto db = b.decide("SYNCAP_BLOBS_01", i, 64);
    EXPECT_EQ(da.drop, db.drop);
    EXPECT_EQ(da.duplicate, db.duplicate);
    EXPECT_EQ(da.reorder, db.reorder);
    EXPECT_EQ(da.flipped_bit, db.flipped_bit);
    differ_by_seed += da.drop != other_seed.decide("SYNCAP_BLOBS_01", i, 64).drop;
    differ_by_channel += da.drop != a.decide("SYNCAP_BLOBS_02", i, 64).drop;
  }
  EXPECT_GT(differ_by_seed, 40);  // independent draws at 30 % differ 42 % of the time
  EXPECT_GT(differ_by_channel, 40);
}

TEST(Impairment, FlippedBitIsInsideTheMessageAndSpreadOverIt) {
  const Impairment impairment({.corrupt = 1}, 5);
  std::array<int, 3> bytes_hit{};  // a 3-byte message: every byte gets hit
  for (uint64_t i = 0; i < 3000; ++i) {
    const auto d = impairment.decide("C", i, 3);
    ASSERT_TRUE(d.flipped_bit.has_value());
    ASSERT_LT(*d.flipped_bit, 24u);
    ++bytes_hit[*d.flipped_bit / 8];
  }
  for (const int hits : bytes_hit) EXPECT_GT(hits, 800);
  EXPECT_FALSE(impairment.decide("C", 0, 0).flipped_bit.has_value());  // empty: nothing to flip
}

TEST(FlipBit, ChangesExactlyThatBit) {
  std::array<uint8_t, 4> data{0x00, 0xff, 0x0f, 0xf0};
  const auto before = data;
  flip_bit(data.data(), 9);  // byte 1, bit 1
  EXPECT_EQ(data[1], 0xfd);
  int changed = 0;
  for (std::size_t i = 0; i < data.size(); ++i)
    changed += std::popcount(static_cast<unsigned>(data[i] ^ before[i]));
  EXPECT_EQ(changed, 1);
}

}  // namespace
}  // namespace syncap::hil
