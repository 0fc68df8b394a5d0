#include "board_calibrate_command.hpp"

#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <array>
#include <filesystem>
#include <optional>
#include <set>
#include <vector>

#include "app/host_options.hpp"
#include "board/board_pose.hpp"
#include "board/corner_detection.hpp"
#include "board/half_turn.hpp"
#include "calibration/exports.hpp"
#include "hull/hull_view.hpp"
#include "hull/views_io.hpp"
#include "io/atomic_file.hpp"
#include "sensor/camera_file.hpp"
#include "sensor/opencv_camera_file.hpp"
#include "subcommand.hpp"
#include "syncap/cli/options.hpp"
#include "util/printf_string.hpp"

namespace syncap::tools {
namespace {

namespace fs = std::filesystem;

constexpr const char* kPrefix = "syncap calibrate --board: ";
// A board corner is found to 0.1-0.3 px; a camera whose corners the board's pose misses by more
// than this (RMS) has intrinsics that do not fit it, or a board that moved.
constexpr double kGoodRmsPx = 1.0;
constexpr double kWeakRmsPx = 2.0;
// The chosen half turns' hull against the best other turns': its worst view's IoU at least this
// much higher (on a real studio with the default masks: 0.81 against 0.43).
constexpr double kHalfTurnMargin = 0.1;

struct BoardArgs {
  board::BoardSpec board;
  std::vector<std::string> clips;
  std::vector<std::string> intrinsics;
  std::vector<std::string> masks;
  std::string camera_ids;
  std::string out;
  int frames = 20;
};

constexpr const char* kDescription =
    "usage: syncap calibrate --board COLSxROWSxMM|charuco:SXxSYxMMxMM[:DICT] --clip FILE|DIR... "
    "--intrinsics FILE... --out-dir DIR [--masks DIR...]\n"
    "Poses every camera on a checkerboard or ChArUco board lying in the scene: per camera (in "
    "--clip order) a video or image folder of the board, which must not move, and the camera's "
    "OpenCV intrinsics. A checkerboard must be seen whole; a ChArUco board in part (its markers "
    "name its corners). The world frame is the board's: origin at its first inner corner, x along "
    "its COLS corners, z = 0 the board (the floor when it lies on it), z towards the cameras. "
    "Checkerboards whose corner counts are both even look the same after a half turn: --masks (one "
    "folder of "
    "the person's masks per camera, the same file names at the same instants, e.g. syncap mask's) "
    "tells the cameras' turns apart by the hull they give. Writes DIR/cameras.json, "
    "DIR/cameras.opencv.yaml and DIR/calibration.toml.\n";

constexpr const char* kFooter =
    "Exit status: 0 good, 1 a weak or failed verdict (written, the reasons printed), 2 usage "
    "error or unreadable input (named).";

std::optional<int> parse_board_args(std::span<const std::string> args, BoardArgs& a,
                                    std::ostream& out, std::ostream& err) {
  cli::App app("syncap calibrate --board", kDescription, kFooter);
  app.add_option_function<std::string>(
         "--board",
         [&a](const std::string& t) {
           const auto spec = board::parse_board_spec(t);
           if (!spec)
             throw CLI::ValidationError("--board",
                                        "'" + t + "': expected " + board::kBoardSpecGrammar);
           a.board = *spec;
         },
         "the board: a checkerboard's inner corners COLS x ROWS and its square's side in mm, "
         "or charuco: a ChArUco board's squares, their side, its markers' side in mm and its "
         "ArUco dictionary (default 4x4_50)")
      ->option_text("COLSxROWSxMM|charuco:SXxSYxMMxMM[:DICT]")
      ->required();
  app.add_option("--clip", a.clips, "one camera's clip of the board (repeat per camera)")
      ->option_text("FILE|DIR")
      ->required()
      ->check(CLI::ExistingPath);
  app.add_option("--intrinsics", a.intrinsics,
                 "the cameras' OpenCV intrinsics: one file per camera (camera_matrix or "
                 "CameraMatrix, distortion_coefficients or DistortionCoeffs) or one file with a "
                 "'cameras' sequence for all")
      ->option_text("FILE")
      ->required()
      ->check(CLI::ExistingFile);
  app.add_option("--masks", a.masks,
                 "one folder of the person's masks per camera: tells a symmetric board's half "
                 "turn")
      ->option_text("DIR")
      ->check(CLI::ExistingDirectory);
  app.add_option("--camera-ids", a.camera_ids,
                 "the cameras' ids, e.g. 1,2,3,4 (default 0, 1, ...)");
  app.add_option("--out-dir", a.out, "the calibration folder (created)")
      ->option_text("DIR")
      ->required();
  app.add_option("--frames", a.frames,
                 "board frames read per clip, every 5th, their corners' median used (default 20)")
      ->check(cli::whole_in<int>(1, 10000));
  return cli::parse(app, args, out, err, [&a] {
    if (!a.masks.empty() && a.masks.size() != a.clips.size())
      throw CLI::ValidationError("--masks", "one folder per --clip");
  });
}

std::vector<int> camera_ids(const BoardArgs& a) {
  std::vector<int> ids;
  if (a.camera_ids.empty()) {
    for (std::size_t i = 0; i < a.clips.size(); ++i) ids.push_back(static_cast<int>(i));
    return ids;
  }
  for (const int id : host_app::parse_camera_list(a.camera_ids)) ids.push_back(id);
  if (ids.size() != a.clips.size()) throw CLI::ValidationError("--camera-ids", "one id per --clip");
  return ids;
}

// Each camera's intrinsics, as the files give them.
std::vector<sensor::OpenCvCamera> read_intrinsics(const BoardArgs& a) {
  std::vector<sensor::OpenCvCamera> cameras;
  if (a.intrinsics.size() == 1 && a.clips.size() > 1) {
    for (const sensor::OpenCvCameraEntry& e : sensor::read_opencv_intrinsics(a.intrinsics[0]))
      cameras.push_back(e.camera);
    if (cameras.size() != a.clips.size())
      throw sensor::CameraFileError(util::printf_string("%s: %zu camera(s) for %zu clip(s)",
                                                        a.intrinsics[0].c_str(), cameras.size(),
                                                        a.clips.size()));
  } else if (a.intrinsics.size() == a.clips.size()) {
    for (const std::string& file : a.intrinsics)
      cameras.push_back(sensor::read_opencv_intrinsics(file).at(0).camera);
  } else {
    throw CLI::ValidationError("--intrinsics", "one file per --clip, or one file for all");
  }
  return cameras;
}

// The intrinsics sized by their clips where the files give no size; a size that differs named.
void check_image_sizes(const BoardArgs& a, const std::vector<board::BoardView>& views,
                       std::vector<sensor::OpenCvCamera>& cameras) {
  for (std::size_t i = 0; i < cameras.size(); ++i) {
    if (cameras[i].image_size.area() == 0) cameras[i].image_size = views[i].image_size;
    if (cameras[i].image_size != views[i].image_size)
      throw sensor::CameraFileError(util::printf_string(
          "%s: the intrinsics are for %dx%d images, the clip's are %dx%d", a.clips[i].c_str(),
          cameras[i].image_size.width, cameras[i].image_size.height, views[i].image_size.width,
          views[i].image_size.height));
  }
}

// One mask per camera at the same instant: the middle file name all folders share.
std::vector<cv::Mat> read_masks(const BoardArgs& a) {
  std::vector<std::set<std::string>> names;
  for (const std::string& dir : a.masks) {
    std::set<std::string> n;
    for (const fs::path& f : hull::mask_files(dir)) n.insert(f.filename().string());
    names.push_back(std::move(n));
  }
  std::vector<std::string> common(names[0].begin(), names[0].end());
  for (const auto& n : names)
    std::erase_if(common, [&n](const std::string& name) { return !n.contains(name); });
  if (common.empty())
    throw hull::HullError("--masks: the folders share no file name (one instant in every view)");
  const std::string name = common[common.size() / 2];
  // The person is the largest region of each mask: the others (a shadow apart, a moved chair)
  // would lower every turn's IoU alike and hide the difference.
  hull::ViewFiles files;
  files.largest_only = true;
  std::vector<cv::Mat> masks;
  for (const std::string& dir : a.masks)
    masks.push_back(hull::read_mask(fs::path(dir) / name, files));
  return masks;
}

struct Verdict {
  std::string word = "good";
  std::vector<std::string> reasons;
  void weak(const std::string& why) {
    if (word == "good") word = "weak";
    reasons.push_back(why);
  }
  void failed(const std::string& why) {
    word = "failed";
    reasons.insert(reasons.begin(), why);
  }
};

void write_outputs(const fs::path& dir, const sensor::CameraSet& set, std::ostream& out) {
  fs::create_directories(dir);
  const auto put = [&dir](const char* name, const std::string& text) {
    io::write_file_atomically((dir / name).string(), [&text](std::ostream& f) { f << text; });
  };
  put("cameras.json", sensor::format_camera_set(set));
  put("cameras.opencv.yaml", calibration::format_opencv_yaml(set.cameras));
  put("calibration.toml", calibration::format_calibration_toml(set.cameras, set.quality->rms_px));
  out << "wrote " << (dir / "cameras.json").string() << ", cameras.opencv.yaml, calibration.toml\n";
}

std::vector<board::BoardView> observe_boards(const BoardArgs& a, const std::vector<int>& ids,
                                             const std::vector<sensor::OpenCvCamera>& intrinsics,
                                             std::ostream& out) {
  std::vector<board::BoardView> views;
  for (std::size_t i = 0; i < a.clips.size(); ++i) {
    views.push_back(board::observe_board(a.clips[i], a.board, a.frames, 5, &intrinsics[i]));
    out << util::printf_string(
        "camera %d: board in %d of %d frames read, %zu of %zu corners, corner spread %.3f px\n",
        ids[i], views.back().frames_found, views.back().frames_read, views.back().corners.size(),
        board::board_points(a.board).size(), views.back().spread_px);
  }
  return views;
}

// Per camera its pose from the corners in the detector's order and reversed (the half turn).
std::vector<std::array<board::BoardPose, 2>> board_poses(
    const BoardArgs& a, const std::vector<int>& ids, const std::vector<board::BoardView>& views,
    const std::vector<sensor::OpenCvCamera>& intrinsics) {
  const bool z_up =
      board::cameras_below_board(intrinsics[0], views[0].corners, a.board, views[0].point_ids);
  std::vector<std::array<board::BoardPose, 2>> poses;
  for (std::size_t i = 0; i < views.size(); ++i) {
    const board::BoardView& v = views[i];
    poses.push_back(
        {board::pose_on_board(intrinsics[i], v.corners, a.board, ids[i], false, z_up, v.point_ids),
         board::has_half_turn_symmetry(a.board)
             ? board::pose_on_board(intrinsics[i], v.corners, a.board, ids[i], true, z_up)
             : board::BoardPose{}});
  }
  return poses;
}

// Which cameras' corners to take reversed: a symmetric board's half turn from the masks.
std::vector<bool> chosen_turns(const BoardArgs& a,
                               const std::vector<std::array<board::BoardPose, 2>>& poses,
                               Verdict& verdict, std::ostream& out) {
  if (!board::has_half_turn_symmetry(a.board) || poses.size() < 2)
    return std::vector<bool>(poses.size(), false);
  if (a.masks.empty()) {
    verdict.weak(
        "the board looks the same after a half turn and no --masks tell the cameras' "
        "turns apart: each camera may be turned half about the board's centre");
    return std::vector<bool>(poses.size(), false);
  }
  const board::HalfTurn turn = board::resolve_half_turn(poses, read_masks(a));
  out << util::printf_string(
      "half turn: %d hulls tried; the chosen turns' hull reprojects at a mean IoU of %.3f, "
      "the best other turns' at %.3f; each camera against the others' hull, the share of "
      "its projection inside the camera's mask ahead of the other turn's by",
      turn.hulls_built, turn.mean_iou, turn.runner_up_iou);
  for (const double m : turn.camera_margins) out << util::printf_string(" %.3f", m);
  out << '\n';
  if (turn.margin < kHalfTurnMargin)
    verdict.weak(util::printf_string(
        "the masks barely tell the board's half turns apart (a camera's turn ahead of the "
        "other by %.3f of the others' hull inside its mask, %.2f wanted): check the masks "
        "(one person, the same instant) and each camera's turn",
        turn.margin, kHalfTurnMargin));
  return turn.reversed;
}

// The chosen poses as a camera set with its quality block, each camera's RMS judged.
sensor::CameraSet camera_set(const std::vector<int>& ids,
                             const std::vector<board::BoardView>& views,
                             const std::vector<std::array<board::BoardPose, 2>>& poses,
                             const std::vector<bool>& reversed, Verdict& verdict,
                             std::ostream& out) {
  sensor::CameraSet set;
  set.quality.emplace();
  double sum_squares = 0.0;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const board::BoardPose& p = poses[i][reversed[i] ? 1 : 0];
    set.cameras.push_back(p.camera);
    set.quality->per_camera_rms_px[ids[i]] = p.rms_px;
    sum_squares += p.rms_px * p.rms_px;
    const Eigen::Vector3d c = p.camera.projection_centre();
    const std::string left_out =
        p.corners_used < p.corners_seen
            ? util::printf_string(", %d of %d corners left out (far off the pose)",
                                  p.corners_seen - p.corners_used, p.corners_seen)
            : "";
    out << util::printf_string(
        "camera %d: board RMS %.3f px (max %.3f)%s%s, centre %.0f %.0f %.0f mm\n", ids[i], p.rms_px,
        p.max_px, reversed[i] ? ", corners turned half" : "", left_out.c_str(), c.x(), c.y(),
        c.z());
    if (p.rms_px > kWeakRmsPx) {
      verdict.failed(
          util::printf_string("camera %d misses the board's corners by %.2f px RMS "
                              "(intrinsics of another camera? a board that moved?)",
                              ids[i], p.rms_px));
    } else if (p.rms_px > kGoodRmsPx) {
      verdict.weak(util::printf_string("camera %d: board RMS %.2f px (%.1f wanted)", ids[i],
                                       p.rms_px, kGoodRmsPx));
    }
  }
  set.quality->rms_px = std::sqrt(sum_squares / static_cast<double>(poses.size()));
  set.quality->sigma0_px = set.quality->rms_px;
  set.quality->observations = 0;
  for (const board::BoardView& v : views) set.quality->observations += std::ssize(v.corners);
  set.quality->verdict = verdict.word;
  set.quality->verdict_reasons = verdict.reasons;
  return set;
}

int run(const BoardArgs& a, std::ostream& out, std::ostream& err) {
  const std::vector<int> ids = camera_ids(a);
  std::vector<sensor::OpenCvCamera> intrinsics = read_intrinsics(a);
  const std::vector<board::BoardView> views = observe_boards(a, ids, intrinsics, out);
  check_image_sizes(a, views, intrinsics);
  const std::vector<std::array<board::BoardPose, 2>> poses = board_poses(a, ids, views, intrinsics);
  Verdict verdict;
  const std::vector<bool> reversed = chosen_turns(a, poses, verdict, out);
  const sensor::CameraSet set = camera_set(ids, views, poses, reversed, verdict, out);
  write_outputs(a.out, set, out);
  out << "verdict: " << verdict.word << '\n';
  for (const std::string& r : verdict.reasons) out << "  " << r << '\n';
  if (verdict.word != "good")
    err << kPrefix << "verdict " << verdict.word << ": " << verdict.reasons.front() << '\n';
  return verdict.word == "good" ? kExitOk : kExitReportedErrors;
}

}  // namespace

bool is_board_calibration(std::span<const std::string> args) {
  return std::ranges::any_of(
      args, [](const std::string& a) { return a == "--board" || a.starts_with("--board="); });
}

int board_calibrate_command(std::span<const std::string> args, std::ostream& out,
                            std::ostream& err) {
  BoardArgs a;
  // `syncap calibrate --board --help`: the help, not "--help" taken as the board.
  const bool help =
      std::ranges::any_of(args, [](const std::string& s) { return s == "--help" || s == "-h"; });
  const std::vector<std::string> help_only{"--help"};
  if (const auto status =
          parse_board_args(help ? std::span<const std::string>(help_only) : args, a, out, err))
    return *status;
  try {
    return run(a, out, err);
  } catch (const CLI::ValidationError& e) {
    err << kPrefix << e.what() << '\n';
  } catch (const std::exception& e) {  // BoardError, CameraFileError, HullError, a file not written
    err << kPrefix << e.what() << '\n';
  }
  return kExitUsage;
}

}  // namespace syncap::tools
