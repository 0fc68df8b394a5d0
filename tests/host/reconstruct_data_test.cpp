// `syncap reconstruct` with every default on a real 4-camera studio no one here rendered
// (multiview/uu-infomcv-4cam-person: per camera a video of a seated person, a clip of the empty
// studio and one of a checkerboard on the floor, the cameras' OpenCV intrinsics), the cameras
// calibrated on the board in the same run. A few frames around frame 200 (the whole recording:
// docs/results/segmentation.md). Checked: the board's verdict good, each view's mask against the
// others' hull (the report's cross-view check) and against an independent reference (colour
// distance to the background's median, tests/host/studio_reference_mask.hpp), the hull's height
// and its floor.
#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "hull/silhouette.hpp"
#include "reconstruct_command.hpp"
#include "studio_reference_mask.hpp"
#include "subcommand.hpp"
#include "syncap_test_data.hpp"
#include "util/printf_string.hpp"

namespace syncap::tools {
namespace {

namespace fs = std::filesystem;

// "camera C median M" of the summary's views line.
double view_median(const std::string& out, int camera) {
  const std::string key = "camera " + std::to_string(camera) + " median ";
  const std::size_t at = out.find(key);
  return at == std::string::npos ? 0.0 : std::stod(out.substr(at + key.size()));
}

TEST(ReconstructData, TheStudioFromItsVideosWithEveryDefault) {
  SYNCAP_REQUIRE_DATA(data, "multiview/uu-infomcv-4cam-person");
  const fs::path dir = fs::path(::testing::TempDir()) / "reconstruct_data";
  fs::remove_all(dir);
  std::vector<std::string> args{"--board",       "8x6x115",
                                "--camera-ids",  "1,2,3,4",
                                "--volume",      "-3000,-3000,0,3000,3000,2500",
                                "--first-frame", "198",
                                "--frames",      "5",
                                "--no-body",     "--mask-images",
                                "--out-dir",     dir.string()};
  for (int c = 1; c <= 4; ++c) {
    const fs::path camera = data / ("cam" + std::to_string(c));
    args.insert(args.end(), {"--capture", (camera / "video.avi").string(), "--background",
                             (camera / "background.avi").string(), "--board-clip",
                             (camera / "checkerboard.avi").string(), "--intrinsics",
                             (camera / "config.xml").string()});
  }
  std::ostringstream out, err;
  const int status = reconstruct_command(args, out, err);
  const std::string text = out.str();
  ASSERT_NE(status, kExitUsage) << text << err.str();
  EXPECT_NE(text.find("verdict: good"), std::string::npos) << text;
  EXPECT_NE(text.find("5 frames in"), std::string::npos) << text;
  // The hull stands on the floor, as tall as the seated person.
  EXPECT_NE(text.find("lowest point 0 mm above the floor"), std::string::npos) << text;
  const std::size_t height = text.find("hull height ");
  ASSERT_NE(height, std::string::npos) << text;
  const double height_m = std::stod(text.substr(height + 12));
  EXPECT_GT(height_m, 1.35);
  EXPECT_LT(height_m, 1.45);
  RecordProperty("hull_height_m", std::to_string(height_m));
  for (int c = 1; c <= 4; ++c) {
    const double cross_view = view_median(text, c);
    const cv::Mat mask =
        cv::imread((dir / "masks" / ("cam" + std::to_string(c)) / "mask_000200.png").string(),
                   cv::IMREAD_GRAYSCALE);
    ASSERT_FALSE(mask.empty()) << c;
    const cv::Mat truth =
        test::studio_reference_mask(data / ("cam" + std::to_string(c)), test::kStudioFrame);
    const double reference = hull::mask_iou(mask, truth);
    const double both = cv::countNonZero(mask & truth);
    const double precision = both / cv::countNonZero(mask), recall = both / cv::countNonZero(truth);
    // Measured 2026-12-02 (docs/results/segmentation.md, "syncap reconstruct on the studio"):
    // cross-view 0.87-0.98, reference 0.73-0.79; the bounds hold what is reached, the issue's
    // goals (0.95, 0.90) are not.
    EXPECT_GT(cross_view, 0.8) << "camera " << c << "\n" << text;
    EXPECT_GT(reference, 0.7) << "camera " << c << ": precision " << precision << ", recall "
                              << recall;
    RecordProperty(util::printf_string("reference_precision_camera_%d", c),
                   std::to_string(precision));
    RecordProperty(util::printf_string("reference_recall_camera_%d", c), std::to_string(recall));
    RecordProperty(util::printf_string("cross_view_iou_camera_%d", c), std::to_string(cross_view));
    RecordProperty(util::printf_string("reference_iou_camera_%d", c), std::to_string(reference));
  }
}

}  // namespace
}  // namespace syncap::tools
