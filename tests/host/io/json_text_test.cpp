// io::JsonText writes numbers and strings as nlohmann::json's dump() wrote them (the host's JSON
// lines keep their text; a number's digits only where Grisu2's were not the shortest or closest,
// for the same double), puts the commas, and keeps a line readable whatever a name holds.
#include "io/json_text.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <string_view>

namespace syncap::io {
namespace {

std::string number_text(double v) {
  std::string out;
  append_json_number(out, v);
  return out;
}

std::string string_text(std::string_view s) {
  std::string out;
  append_json_string(out, s);
  return out;
}

// Fixed notation and its ends (1e-4, 15 digits before the point), scientific notation beyond,
// the largest and smallest doubles, the ends of the shortcuts (thousandths, to_chars' layout).
constexpr std::string_view kEdges =
    "0 -0 1 -2.5 0.1 0.30000000000000004 1e-4 1.5e-4 1e14 999999999999999 123456789012345.6 "
    "412.3817138671875 9.99e-5 1e-5 123e-7 1e15 1e16 1.5e16 1e21 1e22 1e100 -1e-300 "
    "1.7976931348623157e308 -1.7976931348623157e308 5e-324 312.587 0.001 -0.001 0.05 0.12 38 "
    "-1022.1 999999999999.999 123456789012.345 1000000000000.5 900000000000000.5 0.0015 "
    "1234567890123456.5 0.00012345 -0.00012345678";

TEST(JsonText, NumbersAtTheEdgesOfTheLayoutsAreWrittenAsNlohmannJsonWroteThem) {
  const char* const end = kEdges.data() + kEdges.size();
  for (const char* at = kEdges.data(); at < end;) {
    double v = 0;
    at = std::from_chars(at, end, v).ptr + 1;  // past the space
    EXPECT_EQ(number_text(v), nlohmann::json(v).dump()) << v;
  }
  EXPECT_EQ(number_text(std::numeric_limits<double>::quiet_NaN()), "null");
  EXPECT_EQ(number_text(-std::numeric_limits<double>::infinity()), "null");
}

// nlohmann::json's Grisu2 digits round-trip but are not always the shortest (0.14 % of all
// doubles, 0.16 % of rotations rounded to 1e-9: "0.48891402900000003") nor the closest (a float
// widened ends on a tie in 12 %: "...813" for "...8125", where to_chars rounds to even "...812").
// Such a number is written with other digits, never more, for the same double.
void expect_same_double(double v) {
  const std::string ours = number_text(v), theirs = nlohmann::json(v).dump();
  if (ours == theirs) return;
  ASSERT_EQ(std::strtod(ours.c_str(), nullptr), v) << ours;
  ASSERT_EQ(std::strtod(theirs.c_str(), nullptr), v) << theirs;
  ASSERT_LE(ours.size(), theirs.size()) << ours << " " << theirs;
}

// Every bit pattern is a double: all magnitudes and digit counts; then the host's numbers.
TEST(JsonText, RandomNumbersReadBackAsTheSameDoubleAsNlohmannJsonsText) {
  std::mt19937_64 rng(7);
  for (int i = 0; i < 200'000; ++i) {
    const double v = std::bit_cast<double>(rng());
    if (std::isfinite(v)) expect_same_double(v);
  }
  std::uniform_real_distribution<double> mm(-3000, 3000), unit(-1, 1);
  for (int i = 0; i < 100'000; ++i) {
    expect_same_double(static_cast<float>(mm(rng)));        // a blob's coordinate
    expect_same_double(std::round(unit(rng) * 1e9) / 1e9);  // a rotation's element
  }
}

// A marker's coordinates and sigmas (rounded to 0.001 mm): the same text (none of 2*10^6
// differed).
TEST(JsonText, MillimetresRoundedToMicrometresAreTheSameText) {
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> mm(-3000, 3000);
  for (int i = 0; i < 100'000; ++i) {
    const double v = std::round(mm(rng) * 1000) / 1000;
    ASSERT_EQ(number_text(v), nlohmann::json(v).dump());
  }
}

TEST(JsonText, StringsAreEscapedAsNlohmannJsonEscapesThem) {
  for (int c = 0; c < 0x80; ++c) {
    const std::string s(1, static_cast<char>(c));
    EXPECT_EQ(string_text(s), nlohmann::json(s).dump()) << c;
  }
  const std::string utf8 = "caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x8e\xa5 \xef\xbf\xbf";
  EXPECT_EQ(string_text(utf8), nlohmann::json(utf8).dump());
}

// dump() throws on such a name; a reader would refuse the line with the bytes as they are.
TEST(JsonText, BytesThatAreNotUtf8AreWrittenAsTheReplacementCharacter) {
  const std::string replacement = "\xef\xbf\xbd";
  EXPECT_EQ(string_text("a\xff"
                        "b"),
            "\"a" + replacement + "b\"");
  EXPECT_EQ(string_text("\xc3"), "\"" + replacement + "\"");                    // cut short
  EXPECT_EQ(string_text("\xc0\xaf"), "\"" + replacement + replacement + "\"");  // overlong
  EXPECT_EQ(string_text("\xed\xa0\x80"), "\"" + replacement + replacement + replacement + "\"");
  EXPECT_EQ(string_text("\xf4\x90\x80\x80").size(), 2 + 4 * replacement.size());  // > U+10FFFF
  for (const char* bad : {"\xff", "\xe0\x80\x80", "\xf0\x80\x80\x80", "x\xc3(", "\xe2\x82"}) {
    const nlohmann::json read = nlohmann::json::parse(string_text(bad), nullptr, false);
    ASSERT_TRUE(read.is_string()) << bad;
  }
}

TEST(JsonText, CommasGoBetweenMembersAndElements) {
  std::string out;
  JsonText j(out);
  j.begin_object().key("a").integers({1, 2}).key("b").begin_array();
  j.begin_object().end_object().begin_array().end_array().number(0.5).flag(false).end_array();
  j.key("c").string("x").key("d").integer(-9'000'000'000).end_object();
  j.flush();
  EXPECT_EQ(out, R"({"a":[1,2],"b":[{},[],0.5,false],"c":"x","d":-9000000000})");
}

// The buffer fills and moves to `out` many times over, at every position of a token; a key
// longer than the buffer goes straight to `out`.
TEST(JsonText, TheTextIsWholeAcrossTheBuffersEnds) {
  std::string out, expected = "[";
  {
    JsonText j(out);
    j.begin_array();
    for (int i = 0; i < 3000; ++i) {
      j.number(i * 0.001).begin_object().key(std::string(i % 7, 'k')).flag(i % 2).end_object();
      expected += (i ? "," : "") + nlohmann::json(i * 0.001).dump() + ",{\"" +
                  std::string(i % 7, 'k') + "\":" + (i % 2 ? "true" : "false") + "}";
    }
    j.begin_object().key(std::string(3000, 'x')).integers({}).end_object().end_array();
  }
  expected += ",{\"" + std::string(3000, 'x') + "\":[]}]";
  ASSERT_EQ(out.size(), expected.size());
  EXPECT_TRUE(out == expected);  // not printed: 60 kB
}

}  // namespace
}  // namespace syncap::io
