// `syncap match`: a textured sphere seen by five cameras from files (cameras.json, PGM images,
// PNG masks) gives points.ply and points.csv on the sphere; every seed is accounted for; bad
// input is named.
#include "match_command.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "help_check.hpp"
#include "hull/mesh.hpp"
#include "hull/polyhedral_hull.hpp"
#include "hull/views_io.hpp"
#include "sensor/camera_file.hpp"
#include "subcommand.hpp"
#include "surface/textured_scene.hpp"

namespace syncap::tools {
namespace {

namespace fs = std::filesystem;
namespace ms = surface;

struct MatchRun {
  int status = -1;
  std::string out, err;
};

MatchRun run(const std::vector<std::string>& args) {
  std::ostringstream out, err;
  MatchRun r;
  r.status = match_command(args, out, err);
  r.out = out.str();
  r.err = err.str();
  return r;
}

class MatchCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("syncap_match_command_" +
            std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "images");
    fs::create_directories(dir_ / "masks");
    const ms::test::Sphere sphere;
    const auto cameras = ms::test::arc_cameras(5, 30.0, sphere);
    sensor::write_cameras(dir_ / "cameras.json", cameras);
    for (std::size_t i = 0; i < cameras.size(); ++i) {
      cv::Mat mask;
      const cv::Mat image =
          ms::test::render(cameras[i], sphere, 2.0, 17u + static_cast<unsigned>(i), &mask);
      cv::imwrite(image_file(i).string(), image);
      cv::imwrite((dir_ / "masks" / ("cam0" + std::to_string(i) + ".png")).string(), mask);
    }
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path image_file(std::size_t i) const {
    return dir_ / "images" / ("cam0" + std::to_string(i) + ".pgm");
  }
  std::vector<std::string> args() const {
    return {"--cameras",   (dir_ / "cameras.json").string(),
            "--images",    (dir_ / "images").string(),
            "--masks",     (dir_ / "masks").string(),
            "--out",       (dir_ / "out").string(),
            "--min-views", "1"};
  }
  fs::path dir_;
};

std::vector<std::string> lines_of(const fs::path& file) {
  std::ifstream in(file);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

TEST_F(MatchCommand, WritesThePointsOnTheSphereWithTheirSigmas) {
  const MatchRun r = run(args());
  ASSERT_EQ(r.status, kExitOk) << r.err;
  EXPECT_NE(r.out.find("rejected, occluded (facet-ID)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("points/s"), std::string::npos);
  const auto csv = lines_of(dir_ / "out" / "points.csv");
  ASSERT_GT(csv.size(), 300u);
  EXPECT_EQ(csv[0].rfind("x,y,z,sigma_ray_mm,", 0), 0u);
  const ms::test::Sphere sphere;
  double sum2 = 0;
  for (std::size_t i = 1; i < csv.size(); ++i) {
    std::istringstream row(csv[i]);
    Eigen::Vector3d p;
    char comma;
    row >> p.x() >> comma >> p.y() >> comma >> p.z();
    const double e = (p - sphere.centre).norm() - sphere.radius;
    sum2 += e * e;
  }
  EXPECT_LT(std::sqrt(sum2 / static_cast<double>(csv.size() - 1)), 1.0);
  const hull::Mesh surface = hull::read_mesh(dir_ / "out" / "surface.ply");
  EXPECT_GT(surface.number_of_faces(), csv.size());
  EXPECT_NE(r.out.find("surface mesh: "), std::string::npos);
  const auto ply = lines_of(dir_ / "out" / "points.ply");
  ASSERT_GT(ply.size(), 10u);
  EXPECT_EQ(ply[0], "ply");
  EXPECT_NE(std::find(ply.begin(), ply.end(), "element vertex " + std::to_string(csv.size() - 1)),
            ply.end());
}

TEST_F(MatchCommand, AHullMeshInsteadOfMasks) {
  // The hull of the masks, written as a file (as `syncap hull` would).
  hull::ViewFiles files;
  const auto views = hull::read_views(dir_ / "cameras.json", dir_ / "masks", files);
  hull::write_mesh(dir_ / "hull.ply", hull::polyhedral_visual_hull(views));
  auto a = args();
  a[4] = "--hull";
  a[5] = (dir_ / "hull.ply").string();
  const MatchRun r = run(a);
  ASSERT_EQ(r.status, kExitOk) << r.err;
  const auto csv = lines_of(dir_ / "out" / "points.csv");
  EXPECT_GT(csv.size(), 200u);
  // Without masks nothing to check the points against.
  EXPECT_EQ(r.out.find("inside the visual hull"), std::string::npos) << r.out;
  // Without masks the images are only images: one black everywhere is no "empty mask".
  const cv::Mat last = cv::imread(image_file(4).string(), cv::IMREAD_GRAYSCALE);
  cv::imwrite(image_file(4).string(), cv::Mat::zeros(last.size(), CV_8UC1));
  const MatchRun black = run(a);
  EXPECT_EQ(black.status, kExitOk) << black.err;
  cv::imwrite(image_file(4).string(), last);
  a[5] = (dir_ / "missing.ply").string();
  const MatchRun missing = run(a);
  EXPECT_EQ(missing.status, kExitUsage);
  EXPECT_NE(missing.err.find("missing.ply"), std::string::npos) << missing.err;
}

TEST_F(MatchCommand, SweepOnlyIsLessPrecise) {
  auto a = args();
  a.push_back("--sweep-only");
  const MatchRun r = run(a);
  ASSERT_EQ(r.status, kExitOk) << r.err;
  EXPECT_NE(r.out.find("least squares 0.000 s"), std::string::npos) << r.out;
}

TEST_F(MatchCommand, BadInputIsNamed) {
  auto no_hull = args();
  no_hull.erase(no_hull.begin() + 4, no_hull.begin() + 6);  // --masks DIR
  const MatchRun a = run(no_hull);
  EXPECT_EQ(a.status, kExitUsage);
  EXPECT_NE(a.err.find("--hull"), std::string::npos) << a.err;

  std::ofstream(image_file(1), std::ios::trunc) << "not an image";
  const MatchRun b = run(args());
  EXPECT_EQ(b.status, kExitUsage);
  EXPECT_NE(b.err.find(image_file(1).string()), std::string::npos) << b.err;

  fs::remove(image_file(1));
  const MatchRun c = run(args());
  EXPECT_EQ(c.status, kExitUsage);
  EXPECT_NE(c.err.find("4 image(s) for 5 camera(s)"), std::string::npos) << c.err;
}

TEST(MatchCommandUsage, HelpListsEveryOption) {
  const MatchRun help = run({"--help"});
  EXPECT_EQ(help.status, kExitOk);
  test::expect_help_mentions(
      help.out, {"--calibration", "--images", "--masks", "--hull", "--out", "--threshold",
                 "--largest", "--spacing", "--half-window", "--search-depth", "--search-front",
                 "--min-sncc", "--min-views", "--max-angle", "--sweep-only", "Exit status"});
}

}  // namespace
}  // namespace syncap::tools
