// `syncap calibrate --board` on a real 4-camera studio no one here rendered
// (multiview/uu-infomcv-4cam-person: a 8x6-corner board of 115 mm squares lying on the floor,
// seen at a grazing angle in three views; the cameras' OpenCV intrinsics in cam*/config.xml).
// The person's masks come from a second, independent method (each pixel's colour distance to the
// background clip's median, the largest region), not from syncap's masking. Checked: the board's
// corners reprojected within 0.6 px RMS per camera, the symmetric board's half turn told (a good
// verdict), and the hull of those masks with these cameras standing on the floor, 1.35-1.45 m
// tall, reprojecting onto every view.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <filesystem>
#include <sstream>

#include "board_calibrate_command.hpp"
#include "hull/polyhedral_hull.hpp"
#include "hull/reprojection.hpp"
#include "hull/views_io.hpp"
#include "sensor/camera_file.hpp"
#include "studio_reference_mask.hpp"
#include "subcommand.hpp"
#include "syncap_test_data.hpp"

namespace syncap::tools {
namespace {

namespace fs = std::filesystem;

TEST(BoardCalibrationData, TheStudioIsPosedOnItsBoardAndItsPersonStandsOnTheFloor) {
  SYNCAP_REQUIRE_DATA(data, "multiview/uu-infomcv-4cam-person");
  const fs::path dir = fs::path(::testing::TempDir()) / "board_calibration_data";
  fs::remove_all(dir);
  std::vector<std::string> args{"--board", "8x6x115",   "--camera-ids",
                                "1,2,3,4", "--out-dir", (dir / "calib").string()};
  for (int c = 1; c <= 4; ++c) {
    const fs::path camera = data / ("cam" + std::to_string(c));
    fs::create_directories(dir / ("masks" + std::to_string(c)));
    fs::create_directories(dir / "frame");
    const cv::Mat mask = test::studio_reference_mask(camera, test::kStudioFrame);
    cv::imwrite((dir / ("masks" + std::to_string(c)) / "frame.png").string(), mask);
    cv::imwrite((dir / "frame" / ("cam" + std::to_string(c) + ".png")).string(), mask);
    args.insert(args.end(), {"--clip", (camera / "checkerboard.avi").string(), "--intrinsics",
                             (camera / "config.xml").string(), "--masks",
                             (dir / ("masks" + std::to_string(c))).string()});
  }
  std::ostringstream out, err;
  ASSERT_EQ(board_calibrate_command(args, out, err), kExitOk) << out.str() << err.str();
  EXPECT_NE(out.str().find("verdict: good"), std::string::npos) << out.str();
  const sensor::CameraSet set = sensor::read_camera_set(dir / "calib" / "cameras.json");
  ASSERT_EQ(set.cameras.size(), 4u);
  for (const auto& [id, rms] : set.quality->per_camera_rms_px) {
    EXPECT_LT(rms, 0.6) << "camera " << id;
    RecordProperty("board_rms_px_camera_" + std::to_string(id), std::to_string(rms));
  }
  // Every camera above the floor, round the board.
  for (const sensor::CameraModel& c : set.cameras) EXPECT_GT(c.exterior.Z0, 1000.0) << c.id;

  hull::HullOptions options;
  options.capture_volume =
      Eigen::AlignedBox3d(Eigen::Vector3d(-3000, -3000, 0), Eigen::Vector3d(3000, 3000, 2500));
  const std::vector<hull::HullView> views =
      hull::read_views(dir / "calib" / "cameras.json", dir / "frame", {});
  const hull::Mesh mesh = hull::polyhedral_visual_hull(views, options);
  Eigen::AlignedBox3d box;
  for (const hull::Point3& p : mesh.points()) box.extend(Eigen::Vector3d(p.x(), p.y(), p.z()));
  EXPECT_GT(box.sizes().z(), 1350.0);
  EXPECT_LT(box.sizes().z(), 1450.0);
  EXPECT_NEAR(box.min().z(), 0.0, 20.0);
  RecordProperty("hull_height_mm", std::to_string(box.sizes().z()));
  for (const hull::HullView& v : views) {
    const double iou = hull::mask_iou(hull::render_mask(mesh, v.camera), v.mask);
    EXPECT_GT(iou, 0.85) << v.name;
    RecordProperty("hull_iou_camera_" + std::to_string(v.camera.id), std::to_string(iou));
  }
}

}  // namespace
}  // namespace syncap::tools
