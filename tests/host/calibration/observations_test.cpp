// Reading the observations of `syncap calibrate`: CSV, MultiCamSelfCal folders and blob frames.
#include "calibration/observations.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>

namespace syncap::calibration {
namespace {

namespace fs = std::filesystem;

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const ObservationError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(CsvObservations, ReadsSpotsByFrameAndCamera) {
  const Observations obs = parse_csv_observations(
      "frame,camera,x,y\n"
      "7,0,100.5,200.25\n"
      "7,0,300,400\n"
      "7,2, 10 ,20\n"
      "# a comment\n"
      "\n"
      "9,1,1,2\n",
      "wand.csv");
  EXPECT_EQ(obs.source, "csv:wand.csv");
  ASSERT_EQ(obs.frames.size(), 2u);
  ASSERT_EQ(obs.frames.at(7).at(0).size(), 2u);
  EXPECT_DOUBLE_EQ(obs.frames.at(7).at(0)[0].x, 100.5);
  EXPECT_DOUBLE_EQ(obs.frames.at(7).at(0)[0].y, 200.25);
  EXPECT_EQ(obs.frames.at(7).at(0)[0].target, -1);  // to identify
  EXPECT_DOUBLE_EQ(obs.frames.at(7).at(2)[0].x, 10.0);
  EXPECT_EQ(obs.spot_count(), 4);
  EXPECT_EQ(obs.cameras(), (std::set<int>{0, 1, 2}));
}

TEST(CsvObservations, AFifthColumnLabelsTheTarget) {
  const Observations obs = parse_csv_observations("3,1,5,6,2\n3,1,7,8,0\n", "p.csv");
  EXPECT_EQ(obs.frames.at(3).at(1)[0].target, 2);
  EXPECT_EQ(obs.frames.at(3).at(1)[1].target, 0);
}

TEST(CsvObservations, ErrorsNameFileLineAndColumn) {
  EXPECT_EQ(error_of([] { parse_csv_observations("1,0,5,6\n2,0,x,6\n", "a.csv"); }),
            "a.csv:2:5: x must be a number [px]");
  EXPECT_EQ(error_of([] { parse_csv_observations("1,100,5,6\n", "a.csv"); }),
            "a.csv:1:3: camera must be an integer from 0 to 99");
  EXPECT_EQ(error_of([] { parse_csv_observations("1,0,5\n", "a.csv"); }),
            "a.csv:1: expected frame,camera,x,y[,point], got 3 fields");
  EXPECT_EQ(error_of([] { parse_csv_observations("1,0,5,6\n1,0,5,6,1\n", "a.csv"); }),
            "a.csv:2: 5 fields where earlier lines have 4");
  EXPECT_EQ(error_of([] { parse_csv_observations("1.5,0,5,6\n", "a.csv"); }),
            "a.csv:1:1: frame must be an integer");
  EXPECT_EQ(error_of([] { parse_csv_observations("frame,camera,x,y\n", "a.csv"); }),
            "a.csv: no observations");
  EXPECT_EQ(error_of([] { read_csv_observations("/nonexistent/w.csv"); }),
            "/nonexistent/w.csv: cannot open for reading");
}

struct McscFolder {
  fs::path dir = fs::temp_directory_path() / ("syncap-mcsc-" + std::to_string(getpid()));
  McscFolder(const std::string& points, const std::string& res, const std::string& order) {
    fs::create_directories(dir);
    std::ofstream(dir / "points.dat") << points;
    std::ofstream(dir / "Res.dat") << res;
    std::ofstream(dir / "camera_order.txt") << order;
  }
  ~McscFolder() { fs::remove_all(dir); }
};

TEST(McscObservations, ReadsOnePointPerFrameAndCameraSkippingNan) {
  const McscFolder f(
      " 1.0e+01 2.0e+01 nan\n 5.0 6.0 nan\n 1 1 1\n"
      " 3.0 NaN 4.5\n 7.0 NaN 8.5\n 1 1 1\n",
      "752 480\n640 480\n", "cam_a\ncam_b\n");
  const Observations obs = read_mcsc_observations(f.dir);
  EXPECT_EQ(obs.image_sizes.at(0).width, 752);
  EXPECT_EQ(obs.image_sizes.at(1).width, 640);
  EXPECT_EQ(obs.camera_names.at("cam_b"), 1);
  ASSERT_EQ(obs.frames.size(), 3u);
  EXPECT_EQ(obs.frames.at(0).size(), 2u);
  EXPECT_EQ(obs.frames.at(1).size(), 1u);  // camera 1 lost it
  EXPECT_EQ(obs.frames.at(2).count(0), 0u);
  EXPECT_DOUBLE_EQ(obs.frames.at(2).at(1)[0].y, 8.5);
  EXPECT_EQ(obs.frames.at(2).at(1)[0].target, 0);  // identified: the LED
}

TEST(McscObservations, ErrorsNameTheFileAndLine) {
  {
    const McscFolder f("1 2\n3 4\n1 1\n", "752 480\n752 480\n", "a\nb\n");
    EXPECT_EQ(error_of([&] { read_mcsc_observations(f.dir); }),
              (f.dir / "points.dat").string() + ": 3 rows, expected 3 per camera of Res.dat (6)");
  }
  {
    const McscFolder f("1 2\n3 x\n1 1\n", "752 480\n", "a\n");
    EXPECT_EQ(error_of([&] { read_mcsc_observations(f.dir); }),
              (f.dir / "points.dat").string() + ":2: value 2 ('x') is not a number");
  }
  {
    const McscFolder f("1 2\n3 4\n1 1\n", "752\n", "a\n");
    EXPECT_EQ(error_of([&] { read_mcsc_observations(f.dir); }),
              (f.dir / "Res.dat").string() +
                  ":1: expected the image width and height in pixels (1 to 100000)");
  }
  EXPECT_EQ(error_of([] { read_mcsc_observations("/nonexistent"); }),
            "/nonexistent: not a MultiCamSelfCal folder (not a directory)");
}

// Found by the fuzzer (issue 15): an image height beyond int's range was converted to int
// (undefined behaviour; INT_MIN with gcc, a camera with a negative image size).
TEST(McscObservations, ImageSizeBeyondAnySensorIsAnError) {
  EXPECT_EQ(error_of([] {
              parse_mcsc_observations({"", "320 2999999999940\n", "150\n250\n1\n"}, "mcsc");
            }),
            "mcsc/Res.dat:1: expected the image width and height in pixels (1 to 100000)");
}

blob_frame_t blob_frame(int camera, int64_t frame, std::vector<std::pair<float, float>> xy,
                        int part_index = 0, int part_count = 1, int total = -1) {
  blob_frame_t f{};
  f.camera_id = static_cast<int16_t>(camera);
  f.frame_number = frame;
  f.image_width = 640;
  f.image_height = 480;
  f.part_index = static_cast<int16_t>(part_index);
  f.part_count = static_cast<int16_t>(part_count);
  f.total_blobs = static_cast<int16_t>(total < 0 ? static_cast<int>(xy.size()) : total);
  for (const auto& [x, y] : xy) {
    blob_t b{};
    b.x = x;
    b.y = y;
    b.area = 30;
    b.flags = blob_t::FLAG_SATURATED;
    f.blobs.push_back(b);
  }
  f.num_blobs = static_cast<int16_t>(f.blobs.size());
  return f;
}

TEST(BlobFrameCollector, GroupsByFrameNumberAndJoinsParts) {
  BlobFrameCollector collector("lcmlog:x", {0, 1});
  for (int64_t frame = 10; frame < 13; ++frame) {
    trigger_t t{};
    t.frame_number = frame;
    collector.add_trigger(t);
    EXPECT_TRUE(collector.add_blob_frame(blob_frame(0, frame, {{1.0f, 2.0f}, {3.0f, 4.0f}})));
    if (frame != 11) {  // camera 1 lost frame 11
      EXPECT_TRUE(collector.add_blob_frame(blob_frame(1, frame, {{5.0f, 6.0f}}, 0, 2, 2)));
      EXPECT_TRUE(collector.add_blob_frame(blob_frame(1, frame, {{7.0f, 8.0f}}, 1, 2, 2)));
    }
  }
  const Observations obs = collector.finish();
  EXPECT_EQ(obs.source, "lcmlog:x");
  ASSERT_EQ(obs.frames.size(), 3u);
  EXPECT_EQ(obs.frames.at(10).at(1).size(), 2u);  // both parts
  EXPECT_DOUBLE_EQ(obs.frames.at(12).at(1)[1].x, 7.0);
  EXPECT_EQ(obs.frames.at(11).count(1), 0u);
  EXPECT_EQ(obs.incomplete_groups, 1);
  EXPECT_EQ(obs.frames.at(10).at(0)[0].flags, blob_t::FLAG_SATURATED);
  EXPECT_DOUBLE_EQ(obs.frames.at(10).at(0)[0].area, 30.0);
  EXPECT_EQ(obs.image_sizes.at(1).height, 480);
}

}  // namespace
}  // namespace syncap::calibration
