// The host's JSON lines: what append_frame_line writes is the text nlohmann::json wrote before it
// and reads back (parse_frame_line, read_frame_lines) to the same content, short hand-written
// lines take defaults, and a malformed line is named by file, line and field.
#include "io/frame_json.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "frame_json_reference.hpp"
#include "outputs/json_lines_stage.hpp"
#include "sample_groups.hpp"

namespace syncap::io {
namespace {

blob_frame_t blob_frame(std::vector<float> xs) {
  blob_frame_t f{};
  f.processing_us = 210;
  for (const float x : xs) {
    blob_t b{};
    b.x = x;
    b.y = 2.5f;
    b.area = 30;
    f.blobs.push_back(b);
  }
  f.num_blobs = static_cast<int16_t>(f.blobs.size());
  return f;
}

proto::Silhouette silhouette() {
  proto::Silhouette s;
  s.image_width = 640;
  s.image_height = 480;
  s.parts_received = 1;
  s.part_count = 2;
  s.contours = {{false, true, {{1, 2}, {3, 4}, {5, 2}}}, {true, false, {{2, 2}, {3, 3}}}};
  return s;
}

pipeline::FrameWork sample_work() {
  pipeline::FrameWork w;
  w.group.frame_number = 41;
  w.group.trigger = trigger_t{};
  w.group.trigger->monotonic_ns = 123'456'789'012;
  w.group.blobs = {{0, blob_frame({1.5f, -0.25f})}, {1, blob_frame({})}};
  w.group.silhouettes = {{1, silhouette()}, {3, silhouette()}};  // camera 3: only a silhouette
  w.group.missing_cameras = {3};
  w.group.incomplete_silhouettes = {1};
  pipeline::Marker3d m;
  m.id = 7;
  m.position = {312.5, -401.25, 1234.0};
  m.covariance.diagonal() << 0.25, 0.0625, 1.0;
  m.residual_px = 0.125;
  m.camera_ids = {0, 1};
  w.markers = {m, m};
  w.markers[1].predicted = true;
  pipeline::RigidBody found{"tool", true, Eigen::Matrix3d::Identity(), {1, 2, 3}, 0.5, true, {7}};
  pipeline::RigidBody lost;
  lost.name = "wand";
  w.rigid_bodies = {found, lost};
  return w;
}

void expect_silhouette(const proto::Silhouette& read, int camera_id) {
  const proto::Silhouette written = silhouette();
  EXPECT_EQ(read.camera_id, camera_id);
  EXPECT_EQ(read.frame_number, 41);
  EXPECT_EQ(read.image_width, written.image_width);
  EXPECT_EQ(read.image_height, written.image_height);
  EXPECT_EQ(read.parts_received, written.parts_received);
  EXPECT_EQ(read.part_count, written.part_count);
  EXPECT_EQ(read.contours, written.contours);
}

void expect_markers(const std::vector<pipeline::Marker3d>& read,
                    const std::vector<pipeline::Marker3d>& written) {
  ASSERT_EQ(read.size(), written.size());
  for (std::size_t i = 0; i < read.size(); ++i) {
    EXPECT_EQ(read[i].id, written[i].id);
    EXPECT_EQ(read[i].position, written[i].position);
    EXPECT_EQ(read[i].covariance, written[i].covariance);  // diagonal: all the line holds
    EXPECT_EQ(read[i].residual_px, written[i].residual_px);
    EXPECT_EQ(read[i].camera_ids, written[i].camera_ids);
    EXPECT_EQ(read[i].predicted, written[i].predicted);
  }
}

TEST(FrameJson, WhatTheHostWritesReadsBack) {
  const pipeline::FrameWork w = sample_work();
  const FrameRecord r = parse_frame_line(frame_line(w, true), "groups.jsonl:1");
  EXPECT_EQ(r.frame, 41);
  EXPECT_FALSE(r.complete);
  EXPECT_EQ(r.missing_cameras, std::vector<int>{3});
  EXPECT_EQ(r.trigger_monotonic_ns, 123'456'789'012);
  EXPECT_EQ(r.incomplete_silhouettes, std::vector<int>{1});
  ASSERT_EQ(r.cameras.size(), 3u);
  ASSERT_TRUE(r.cameras.at(0).blobs);
  ASSERT_EQ(r.cameras.at(0).blobs->size(), 2u);
  EXPECT_EQ((*r.cameras.at(0).blobs)[1].x, -0.25);
  EXPECT_EQ((*r.cameras.at(0).blobs)[1].y, 2.5);
  EXPECT_EQ((*r.cameras.at(0).blobs)[1].area, 30);
  EXPECT_EQ(r.cameras.at(0).processing_us, 210);
  EXPECT_FALSE(r.cameras.at(0).silhouette);
  ASSERT_TRUE(r.cameras.at(1).blobs && r.cameras.at(1).silhouette);
  EXPECT_TRUE(r.cameras.at(1).blobs->empty());
  expect_silhouette(*r.cameras.at(1).silhouette, 1);
  EXPECT_FALSE(r.cameras.at(3).blobs);  // only its silhouette arrived
  expect_silhouette(*r.cameras.at(3).silhouette, 3);
  ASSERT_TRUE(r.markers);
  expect_markers(*r.markers, w.markers);
  ASSERT_EQ(r.rigid_bodies.size(), 2u);
  EXPECT_EQ(r.rigid_bodies[0].name, "tool");
  EXPECT_TRUE(r.rigid_bodies[0].found && r.rigid_bodies[0].collinear);
  EXPECT_EQ(r.rigid_bodies[0].rotation, Eigen::Matrix3d::Identity());
  EXPECT_EQ(r.rigid_bodies[0].translation_mm, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(r.rigid_bodies[0].rms_mm, 0.5);
  EXPECT_EQ(r.rigid_bodies[0].marker_ids, std::vector<int>{7});
  EXPECT_FALSE(r.rigid_bodies[1].found);
}

// A JSON text cut into tokens: a string whole (escapes kept), a number or a literal whole, any
// other character alone.
std::vector<std::string> tokens(std::string_view text) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < text.size();) {
    std::size_t end = i + 1;
    if (text[i] == '"') {
      while (text[end] != '"') end += text[end] == '\\' ? 2 : 1;
      ++end;
    } else if (std::string_view("-0123456789tfn").find(text[i]) != std::string_view::npos) {
      end = text.find_first_of(",]}", i);
    }
    out.emplace_back(text.substr(i, end - i));
    i = end;
  }
  return out;
}

// The text nlohmann::json wrote, but for numbers whose Grisu2 digits were not the shortest or
// closest (json_text_test.cpp): those the same double, in no more digits.
void expect_same_line(const std::string& ours, const std::string& reference) {
  const std::vector<std::string> a = tokens(ours), b = tokens(reference);
  EXPECT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
    if (a[i] == b[i]) continue;
    EXPECT_EQ(std::strtod(a[i].c_str(), nullptr), std::strtod(b[i].c_str(), nullptr))
        << a[i] << " " << b[i];
    const auto is_number = [](const std::string& t) { return t[0] == '-' || std::isdigit(t[0]); };
    EXPECT_TRUE(is_number(a[i]) && is_number(b[i]) && a[i].size() <= b[i].size())
        << a[i] << " " << b[i];
  }
}

// Realistic groups and awkward ones (ids beyond 9, numbers not finite or of any size, a name to
// escape), with and without silhouettes and markers: the text nlohmann::json wrote.
TEST(FrameJson, TheLineIsTheTextNlohmannJsonWroteOnRandomGroups) {
  std::mt19937 rng(2026);
  for (int i = 0; i < 120; ++i) {
    test::SampleGroupOptions o;
    o.awkward = i % 2 == 1;
    o.silhouettes = i % 4 >= 2;
    o.cameras = 1 + i % 12;
    o.blobs_per_camera = i % 41;
    o.markers = i % 34;
    const pipeline::FrameWork w = test::sample_group(rng, o);
    const bool with_markers = i % 8 < 6;
    SCOPED_TRACE("group " + std::to_string(i));
    expect_same_line(frame_line(w, with_markers),
                     test::reference_frame_json(w, with_markers).dump());
  }
}

TEST(FrameJson, LinesAppendToTheBuffer) {
  std::mt19937 rng(1);
  const pipeline::FrameWork a = test::sample_group(rng), b = test::sample_group(rng);
  std::string out = "x";
  append_frame_line(out, a, true);
  append_frame_line(out, b, false);
  EXPECT_EQ(out, "x" + frame_line(a, true) + frame_line(b, false));
}

// The stage reuses its buffer: a short line after a long one holds nothing of the long one.
TEST(FrameJson, TheStageWritesEachGroupAsOneLine) {
  std::mt19937 rng(3);
  const pipeline::FrameWork long_group = test::sample_group(rng);
  const pipeline::FrameWork short_group = sample_work();
  std::ostringstream out;
  outputs::JsonLinesStage stage(out, true);
  for (const auto* w : {&long_group, &short_group}) {
    pipeline::FrameWork work = *w;
    stage.process(work);
  }
  stage.finish();
  EXPECT_EQ(out.str(), frame_line(long_group, true) + "\n" + frame_line(short_group, true) + "\n");
}

TEST(FrameJson, WithoutMarkersTheLineHasNone) {
  pipeline::FrameWork w = sample_work();
  w.rigid_bodies.clear();
  const FrameRecord r = parse_frame_line(frame_line(w, false), "g:1");
  EXPECT_FALSE(r.markers);
  EXPECT_TRUE(r.rigid_bodies.empty());
}

TEST(FrameJson, AShortLineTakesTheDefaults) {
  const FrameRecord r =
      parse_frame_line(R"({"frame":4,"complete":true,"cameras":{"2":{"blobs":[{"x":1,"y":2}]}},)"
                       R"("markers":[{"x":1,"y":2,"z":3,"cameras":[0,2]}]})",
                       "g:1");
  EXPECT_TRUE(r.missing_cameras.empty());
  EXPECT_FALSE(r.trigger_monotonic_ns);
  EXPECT_EQ(r.cameras.at(2).processing_us, 0);
  EXPECT_EQ((*r.cameras.at(2).blobs)[0].area, 0);
  ASSERT_EQ(r.markers->size(), 1u);
  EXPECT_EQ((*r.markers)[0].id, -1);
  EXPECT_EQ((*r.markers)[0].covariance, Eigen::Matrix3d::Zero());
  EXPECT_FALSE((*r.markers)[0].predicted);
}

TEST(FrameJson, ANumberThatIsNotFiniteIsWrittenAsNullAndReadsBackAsNaN) {
  pipeline::FrameWork w = sample_work();
  w.group.blobs.at(0).blobs[0].x = std::numeric_limits<float>::quiet_NaN();
  w.group.blobs.at(0).blobs[0].area = std::numeric_limits<float>::infinity();
  w.markers[0].residual_px = std::numeric_limits<double>::quiet_NaN();
  w.markers[0].covariance(2, 2) = -1;  // its sigma: sqrt(-1)
  const std::string line = frame_line(w, true);
  EXPECT_NE(line.find(R"({"area":null,"x":null,"y":2.5})"), std::string::npos) << line;
  const FrameRecord r = parse_frame_line(line, "g:1");
  EXPECT_TRUE(std::isnan((*r.cameras.at(0).blobs)[0].x));
  EXPECT_TRUE(std::isnan((*r.cameras.at(0).blobs)[0].area));
  EXPECT_TRUE(std::isnan((*r.markers)[0].residual_px));
  EXPECT_TRUE(std::isnan((*r.markers)[0].covariance(2, 2)));
  EXPECT_EQ((*r.markers)[0].covariance(1, 1), w.markers[0].covariance(1, 1));
}

std::string error_of(const std::function<void()>& read) {
  try {
    read();
  } catch (const FrameLineError& e) {
    return e.what();
  }
  return "no error";
}

// A scratch file, removed at the end of the test.
class LinesFile {
 public:
  explicit LinesFile(const std::string& text)
      : path_(std::filesystem::temp_directory_path() /
              ("syncap_frame_json_test_" + std::to_string(getpid()) + ".jsonl")) {
    std::ofstream(path_) << text;
  }
  ~LinesFile() { std::filesystem::remove(path_); }
  const std::filesystem::path& path() const { return path_; }
  std::string read_error() const {
    return error_of([&] { read_frame_lines(path_); });
  }

 private:
  std::filesystem::path path_;
};

const char* kLine = R"({"frame":3,"complete":false,"cameras":{"0":{"blobs":[]}}})";

TEST(FrameJson, AMalformedLineIsNamedByFileAndLine) {
  const LinesFile file(std::string(kLine) + "\n\n{\"frame\": 4,\n");
  EXPECT_EQ(file.read_error(), file.path().string() + ":3: not JSON");
}

TEST(FrameJson, ABadFieldIsNamedByItsPath) {
  const auto error = [](const std::string& line) {
    const LinesFile file(line + "\n");
    const std::string text = file.read_error();
    return text.substr(std::min(text.size(), file.path().string().size()));
  };
  EXPECT_EQ(error(R"({"complete":true,"cameras":{}})"), ":1: field \"frame\" is missing");
  EXPECT_EQ(error(R"({"frame":1.5,"complete":true,"cameras":{}})"),
            ":1: frame is not a whole number");
  EXPECT_EQ(error(R"({"frame":1,"complete":true,"cameras":{"one":{"blobs":[]}}})"),
            ":1: camera key \"one\" is not an id");
  EXPECT_EQ(error(R"({"frame":1,"complete":true,"cameras":{"2":{"blobs":[{"x":1,"y":"a"}]}}})"),
            ":1: cameras.2.blobs[0].y is not a number");
  EXPECT_EQ(error(R"({"frame":1,"complete":true,"cameras":{"2":{}}})"),
            ":1: field \"cameras.2.blobs\" is missing");
  EXPECT_EQ(error(R"({"frame":1,"complete":true,"cameras":{},"markers":[{"x":1,"y":2,"z":3}]})"),
            ":1: field \"markers[0].cameras\" is missing");
  EXPECT_EQ(error(R"({"frame":1,"complete":true,"cameras":{},)"
                  R"("rigid_sets":[{"name":"t","found":true,"translation":[1,2]}]})"),
            ":1: rigid_sets[0].translation does not hold 3 numbers");
}

TEST(FrameJson, AFrameTwiceOrAMissingFileIsNamed) {
  const LinesFile twice(std::string(kLine) + "\n" + kLine + "\n");
  EXPECT_EQ(twice.read_error(), twice.path().string() + ":2: frame 3 again (first on line 1)");
  EXPECT_EQ(error_of([] { read_frame_lines("/nonexistent/groups.jsonl"); }),
            "/nonexistent/groups.jsonl: cannot read");
}

}  // namespace
}  // namespace syncap::io
