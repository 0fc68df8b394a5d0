// BVH parsing: the structure and values of a good file, and errors that name file, line and
// problem for broken ones.
#include <gtest/gtest.h>

#include <string>

#include "body/bvh.hpp"

namespace syncap::body {
namespace {

// Two joints and an end site; 9 channels; line numbers matter to the error tests below.
const char* const kGood =
    "HIERARCHY\n"                                                                 // 1
    "ROOT Hips\n"                                                                 // 2
    "{\n"                                                                         // 3
    "  OFFSET 0.0 0.0 0.0\n"                                                      // 4
    "  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n"  // 5
    "  JOINT Spine\n"                                                             // 6
    "  {\n"                                                                       // 7
    "    OFFSET 0 10 0\n"                                                         // 8
    "    CHANNELS 3 Xrotation Zrotation Yrotation\n"                              // 9
    "    End Site\n"                                                              // 10
    "    {\n"                                                                     // 11
    "      OFFSET 0 5 0\n"                                                        // 12
    "    }\n"                                                                     // 13
    "  }\n"                                                                       // 14
    "}\n"                                                                         // 15
    "MOTION\n"                                                                    // 16
    "Frames: 2\n"                                                                 // 17
    "Frame Time: 0.04\n"                                                          // 18
    "1 2 3 10 20 30 40 50 60\n"                                                   // 19
    "4 5 6 11 21 31 41 51 61\n";                                                  // 20

std::string replace_line(const std::string& text, int line, const std::string& with) {
  std::string out;
  int n = 1;
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t end = text.find('\n', start);
    out += (n == line ? with : text.substr(start, end - start)) + "\n";
    start = end + 1;
    ++n;
  }
  return out;
}

// Parses and returns the error; fails the test when there is none.
BvhError error_of(const std::string& text) {
  try {
    parse_bvh(text, "broken.bvh");
  } catch (const BvhError& e) {
    return e;
  }
  ADD_FAILURE() << "no error for:\n" << text;
  return BvhError("", 0, "");
}

void expect_error(const std::string& text, int line, const std::string& problem) {
  const BvhError e = error_of(text);
  EXPECT_EQ(e.file(), "broken.bvh");
  EXPECT_EQ(e.line(), line) << e.what();
  EXPECT_NE(e.problem().find(problem), std::string::npos) << e.what();
  EXPECT_EQ(std::string(e.what()).rfind("broken.bvh:" + std::to_string(line) + ": ", 0), 0u)
      << e.what();
}

TEST(BvhParser, ReadsHierarchyAndMotion) {
  const Bvh bvh = parse_bvh(kGood, "good.bvh");
  ASSERT_EQ(bvh.joints.size(), 3u);
  EXPECT_EQ(bvh.joints[0].name, "Hips");
  EXPECT_EQ(bvh.joints[1].name, "Spine");
  EXPECT_EQ(bvh.joints[1].parent, 0);
  EXPECT_EQ(bvh.joints[1].offset, Eigen::Vector3d(0, 10, 0));
  EXPECT_EQ(bvh.joints[1].first_channel, 6);
  EXPECT_EQ(bvh.joints[1].line, 6);
  EXPECT_TRUE(bvh.joints[2].end_site);
  EXPECT_EQ(bvh.joints[2].name, "Spine/End Site");
  EXPECT_EQ(bvh.joints[2].offset, Eigen::Vector3d(0, 5, 0));
  EXPECT_EQ(bvh.joints[0].channels,
            (std::vector<BvhChannel>{BvhChannel::kXposition, BvhChannel::kYposition,
                                     BvhChannel::kZposition, BvhChannel::kZrotation,
                                     BvhChannel::kXrotation, BvhChannel::kYrotation}));
  EXPECT_EQ(bvh.joints[1].channels,
            (std::vector<BvhChannel>{BvhChannel::kXrotation, BvhChannel::kZrotation,
                                     BvhChannel::kYrotation}));
  EXPECT_EQ(bvh.channel_count, 9);
  EXPECT_EQ(bvh.frame_count, 2);
  EXPECT_DOUBLE_EQ(bvh.frame_time_s, 0.04);
  EXPECT_DOUBLE_EQ(bvh.duration_s(), 0.04);
  EXPECT_EQ(bvh.frame(1)[0], 4);
  EXPECT_EQ(bvh.frame(1)[8], 61);
  EXPECT_EQ(bvh.find("Spine"), 1);
  EXPECT_EQ(bvh.find("Neck"), -1);
}

TEST(BvhParser, AcceptsCrLfTabsGluedBracesAndNamesWithSpaces) {
  std::string text = replace_line(kGood, 6, "\tJOINT Bip01 Spine{");
  text = replace_line(text, 7, "");
  for (std::size_t at = text.find('\n'); at != std::string::npos; at = text.find('\n', at + 2)) {
    text.insert(at, "\r");
  }
  const Bvh bvh = parse_bvh(text, "crlf.bvh");
  EXPECT_EQ(bvh.joints[1].name, "Bip01 Spine");
  EXPECT_EQ(bvh.frame_count, 2);
}

TEST(BvhParser, TooFewChannelValuesNameTheLine) {
  expect_error(replace_line(kGood, 20, "4 5 6 11 21 31 41 51"), 20,
               "expected 9 channel values, got 8");
}

TEST(BvhParser, ValueThatIsNotANumber) {
  expect_error(replace_line(kGood, 19, "1 2 3 10 20 x 40 50 60"), 19,
               "channel value 6 is not a number: 'x'");
}

TEST(BvhParser, UnknownKeyword) {
  expect_error(replace_line(kGood, 8, "    OFFSETS 0 10 0"), 8, "unknown keyword 'OFFSETS'");
}

TEST(BvhParser, UnknownChannel) {
  expect_error(replace_line(kGood, 9, "    CHANNELS 3 Xrotation Wrotation Yrotation"), 9,
               "got 'Wrotation'");
}

TEST(BvhParser, MissingClosingBrace) {
  expect_error(replace_line(kGood, 14, ""), 16, "unbalanced braces: joint 'Hips' (line 2)");
}

TEST(BvhParser, ExtraClosingBrace) {
  expect_error(replace_line(kGood, 15, "}\n}"), 16, "unbalanced braces: '}' closes no joint");
}

TEST(BvhParser, FewerFramesThanAnnounced) {
  expect_error(replace_line(kGood, 17, "Frames: 3"), 20,
               "frame count mismatch: 2 frame lines, 'Frames: 3' (line 17)");
}

TEST(BvhParser, MoreFramesThanAnnounced) {
  expect_error(replace_line(kGood, 17, "Frames: 1"), 20, "frame count mismatch: more frame lines");
}

TEST(BvhParser, BadFrameTime) {
  expect_error(replace_line(kGood, 18, "Frame Time: -1"), 18, "Frame Time");
  expect_error(replace_line(kGood, 18, "FrameTime 0.04"), 18, "expected 'Frame Time: <seconds>'");
}

TEST(BvhParser, OffsetWithTooFewValues) {
  expect_error(replace_line(kGood, 8, "    OFFSET 0 10"), 9,
               "expected an OFFSET value, got 'CHANNELS'");
}

TEST(BvhParser, NoMotionSection) {
  expect_error(std::string(kGood).substr(0, std::string(kGood).find("MOTION")), 15,
               "no MOTION section");
}

TEST(BvhParser, NotABvhFile) { expect_error("{ \"json\": true }\n", 1, "expected HIERARCHY"); }

TEST(BvhParser, MissingFileIsNamed) {
  try {
    load_bvh("/nonexistent/motion.bvh");
    FAIL() << "no error";
  } catch (const BvhError& e) {
    EXPECT_EQ(e.file(), "/nonexistent/motion.bvh");
    EXPECT_NE(std::string(e.what()).find("cannot open"), std::string::npos);
  }
}

}  // namespace
}  // namespace syncap::body
