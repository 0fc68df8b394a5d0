#include <gtest/gtest.h>

#include "groups.hpp"
#include "input_error.hpp"
#include "scratch_files.hpp"
#include "truth.hpp"

namespace syncap::compare {
namespace {

using testing::cameras_json;
using testing::ScratchDir;

// The message of the InputError `read` throws; fails the test when it throws none.
template <typename Read>
std::string error_of(Read read) {
  try {
    read();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError";
  return "";
}

const char* kFramesHeader = "frame,time_s,phase,phase_type,led_on,gain\n";
const char* kProjectionsHeader = "frame,camera,target,x_px,y_px,radius_px,visible\n";

TEST(ReadFrames, ReadsEveryRow) {
  ScratchDir dir;
  const auto file = dir.write(
      "frames.csv", std::string(kFramesHeader) + "0,0,0,wand,0,1\n1,0.0333,1,led,1,0.97\n");
  const TruthFrames frames = read_frames(file);
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames.at(1).phase_type, "led");
  EXPECT_TRUE(frames.at(1).led_on);
  EXPECT_DOUBLE_EQ(frames.at(1).gain, 0.97);
}

TEST(ReadFrames, NamesFileAndLine) {
  ScratchDir dir;
  const auto wrong_header = dir.write("a.csv", "frame,time\n0,0\n");
  EXPECT_NE(error_of([&] { read_frames(wrong_header); }).find("a.csv:1: expected the header"),
            std::string::npos);
  const auto short_row = dir.write("b.csv", std::string(kFramesHeader) + "0,0,0,wand,0,1\n1,0,0\n");
  EXPECT_EQ(error_of([&] { read_frames(short_row); }),
            short_row.string() + ":3: expected 6 fields, got 3");
  const auto bad_number = dir.write("c.csv", std::string(kFramesHeader) + "0,soon,0,wand,0,1\n");
  EXPECT_EQ(error_of([&] { read_frames(bad_number); }),
            bad_number.string() + ":2: field time_s 'soon' is not a finite number");
  const auto twice =
      dir.write("d.csv", std::string(kFramesHeader) + "4,0,0,wand,0,1\n4,0,0,wand,0,1\n");
  EXPECT_EQ(error_of([&] { read_frames(twice); }), twice.string() + ":3: frame 4 appears twice");
  const auto empty = dir.write("e.csv", "");
  EXPECT_NE(error_of([&] { read_frames(empty); }).find("e.csv:1: empty"), std::string::npos);
  EXPECT_EQ(error_of([&] { read_frames(dir.path() / "none.csv"); }),
            (dir.path() / "none.csv").string() + ": cannot read");
}

class ReadProjections : public ::testing::Test {
 protected:
  TruthFrames frames{{0, {0, 0, 0, "wand", false, 1}}, {1, {1, 0.04, 0, "wand", false, 1}}};
  ImageSizes images{{0, {640, 480}}, {1, {640, 480}}};
  ScratchDir dir;
};

TEST_F(ReadProjections, ReadsRowsWithWindowsLineEnds) {
  const auto file = dir.write("projections.csv", std::string(kProjectionsHeader) +
                                                     "0,1,2,10.5,20.25,4.5,1\r\n1,0,0,0,0,0,0\r\n");
  const auto p = read_projections(file, frames, images);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p[0].camera, 1);
  EXPECT_EQ(p[0].target, 2);
  EXPECT_DOUBLE_EQ(p[0].y_px, 20.25);
  EXPECT_TRUE(p[0].visible);
  EXPECT_FALSE(p[1].visible);
}

TEST_F(ReadProjections, NamesFileAndLine) {
  const auto read = [&](const std::string& rows) {
    const auto file = dir.write("projections.csv", kProjectionsHeader + rows);
    return error_of([&] { read_projections(file, frames, images); });
  };
  const std::string file = (dir.path() / "projections.csv").string();
  EXPECT_EQ(read("0,0,0,1,1,1,1\n0,0,1,1,1,1\n"), file + ":3: expected 7 fields, got 6");
  EXPECT_EQ(read("0,0,0,1,1,1,yes\n"), file + ":2: field visible 'yes' must be 0 or 1");
  EXPECT_EQ(read("7,0,0,1,1,1,1\n"), file + ":2: frame 7 is not in frames.csv");
  EXPECT_EQ(read("0,5,0,1,1,1,1\n"), file + ":2: camera 5 is not in cameras.json");
  EXPECT_EQ(read("0,0,0.5,1,1,1,1\n"), file + ":2: field target '0.5' is not an integer");
  EXPECT_EQ(read("0,0,0,1,1,1,1\n0,0,0,1,1,1,1\n"),
            file + ":3: frame 0 camera 0 target 0 appears twice");
}

TEST(ReadImageSizes, ReadsSizesAndNamesTheFileOnErrors) {
  ScratchDir dir;
  const auto good = dir.write("cameras.json", cameras_json(2, 1280, 1024));
  const ImageSizes images = read_image_sizes(good);
  ASSERT_EQ(images.size(), 2u);
  EXPECT_EQ(images.at(1).width_px, 1280);
  EXPECT_EQ(images.at(1).height_px, 1024);
  const auto bad = dir.write("bad.json", "{\"cameras\": [");
  EXPECT_EQ(error_of([&] { read_image_sizes(bad); }).rfind(bad.string() + ": not valid JSON", 0),
            0u);
}

TEST(ReadTruth, NamesTheMissingFile) {
  ScratchDir dir;
  EXPECT_EQ(error_of([&] { read_truth(dir.path()); }),
            (dir.path() / "truth" / "frames.csv").string() + ": cannot read");
}

const char* kGroup =
    R"({"frame":3,"complete":false,"missing_cameras":[2],"trigger_monotonic_ns":12,)"
    R"("cameras":{"0":{"processing_us":210,"blobs":[{"x":1.5,"y":2.5,"area":30}]},)"
    R"("1":{"processing_us":190,"blobs":[]}}})";

TEST(ReadGroups, ReadsTheHostsLines) {
  ScratchDir dir;
  const auto file = dir.write("groups.jsonl", std::string(kGroup) + "\n\n");
  const auto groups = read_groups(file);
  ASSERT_EQ(groups.size(), 1u);
  const Group& g = groups[0];
  EXPECT_EQ(g.frame, 3);
  EXPECT_FALSE(g.complete);
  EXPECT_EQ(g.missing_cameras, std::vector<int>{2});
  ASSERT_EQ(g.cameras.size(), 2u);
  EXPECT_DOUBLE_EQ(g.cameras.at(0).processing_us, 210);
  ASSERT_EQ(g.cameras.at(0).blobs.size(), 1u);
  EXPECT_DOUBLE_EQ(g.cameras.at(0).blobs[0].y, 2.5);
  EXPECT_DOUBLE_EQ(g.cameras.at(0).blobs[0].area, 30);
  EXPECT_TRUE(g.cameras.at(1).blobs.empty());
}

// A group whose camera's blob frame was lost but whose silhouette arrived (a network fault): the
// camera is missing, not a camera that saw nothing.
TEST(ReadGroups, ACameraWithOnlyASilhouetteDidNotReport) {
  ScratchDir dir;
  const auto file =
      dir.write("groups.jsonl",
                R"({"frame":5,"complete":false,"missing_cameras":[1],"cameras":{"0":{"blobs":[]},)"
                R"("1":{"silhouette":{"width":4,"height":4,"contours":[]}}}})"
                "\n");
  const auto groups = read_groups(file);
  ASSERT_EQ(groups.size(), 1u);
  EXPECT_EQ(groups[0].cameras.size(), 1u);
  EXPECT_TRUE(groups[0].cameras.contains(0));
  EXPECT_EQ(groups[0].missing_cameras, std::vector<int>{1});
}

TEST(ReadGroups, NamesFileAndLine) {
  ScratchDir dir;
  const auto read = [&](const std::string& lines) {
    const auto file = dir.write("groups.jsonl", lines);
    return error_of([&] { read_groups(file); });
  };
  const std::string file = (dir.path() / "groups.jsonl").string();
  EXPECT_EQ(read(std::string(kGroup) + "\n\n{\"frame\": 4,\n"), file + ":3: not JSON");
  EXPECT_EQ(read(R"({"complete":true,"cameras":{}})"), file + ":1: field \"frame\" is missing");
  EXPECT_EQ(read(R"({"frame":1,"complete":1,"cameras":{}})"),
            file + ":1: complete is not true or false");
  EXPECT_EQ(read(R"({"frame":1,"complete":true,"cameras":{"one":{"blobs":[]}}})"),
            file + ":1: camera key \"one\" is not an id");
  EXPECT_EQ(read(R"({"frame":1,"complete":true,"cameras":{"2":{"blobs":[{"x":1,"y":"a"}]}}})"),
            file + ":1: cameras.2.blobs[0].y is not a number");
  EXPECT_EQ(read(std::string(kGroup) + "\n" + kGroup + "\n"),
            file + ":2: frame 3 again (first on line 1)");
  EXPECT_EQ(error_of([&] { read_groups(dir.path() / "none.jsonl"); }),
            (dir.path() / "none.jsonl").string() + ": cannot read");
}

}  // namespace
}  // namespace syncap::compare
