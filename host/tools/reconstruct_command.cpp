#include "reconstruct_command.hpp"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>

#include "app/host_options.hpp"
#include "board_calibrate_command.hpp"
#include "controllers/recording_reconstruction.hpp"
#include "motion_files.hpp"
#include "reconstruction_report.hpp"
#include "sensor/camera_file.hpp"
#include "subcommand.hpp"
#include "syncap/cli/options.hpp"
#include "syncap/segmentation/background_clip.hpp"
#include "syncap/segmentation/mask_images.hpp"
#include "syncap/segmentation/mask_options.hpp"
#include "util/file_extension.hpp"
#include "util/printf_string.hpp"

namespace syncap::tools {
namespace {

namespace fs = std::filesystem;
constexpr const char* kName = "syncap reconstruct";

struct ReconstructArgs {
  std::vector<std::string> captures, backgrounds;
  std::string calibration;
  std::string board;
  std::vector<std::string> board_clips, intrinsics;
  std::string camera_ids;
  std::string out;
  bool mask_images = false;
  bool no_body = false;
  std::vector<double> volume;
  controllers::ReconstructionOptions run;
};

constexpr const char* kDescription =
    "usage: syncap reconstruct --capture VIDEO|DIR --background VIDEO|DIR ... "
    "(--calibration FILE | --board BOARD --board-clip VIDEO|DIR ... --intrinsics FILE ...) "
    "--out-dir DIR [options]\n"
    "Reconstructs a person from synchronised recordings, one --capture and one --background (the "
    "empty scene) per camera, in the same camera order: every frame masked as syncap-edge masks "
    "(trained on the background, aligned to the capture), the hull of every frame, the body "
    "fitted and tracked, as syncap-host does live. The cameras come from --calibration (any "
    "camera file syncap reads, cameras in the captures' order unless --camera-ids) or from a "
    "checkerboard or ChArUco board lying on the floor (--board with a clip and OpenCV intrinsics "
    "per camera: as "
    "syncap calibrate --board, into DIR/calibration). Writes DIR/hulls/hull_<frame>.ply, "
    "DIR/frames.jsonl (each frame's hull and pose), DIR/body.bvh, DIR/joints.c3d, "
    "DIR/joints.trc, with --mask-images DIR/masks/camN/mask_NNNNNN.png, and DIR/report.html: "
    "each view's agreement with the others, the hull's size and floor, the calibration's "
    "verdict and warnings where a figure is implausible.\n";

constexpr const char* kFooter =
    "Exit status: 0 reconstructed, 1 reconstructed with warnings (printed and in the report), 2 "
    "usage error or unreadable input (named).";

void add_input_options(cli::App& app, ReconstructArgs& a) {
  app.add_option("--capture", a.captures,
                 "one camera's recording of the person (repeat per camera)")
      ->option_text("VIDEO|DIR")
      ->required()
      ->check(CLI::ExistingPath);
  app.add_option("--background", a.backgrounds,
                 "that camera's recording of the empty scene (repeat, in --capture order)")
      ->option_text("VIDEO|DIR")
      ->required()
      ->check(CLI::ExistingPath);
  app.add_option("--calibration", a.calibration,
                 "the cameras: cameras.json, OpenCV YAML/JSON or anipose/Pose2Sim TOML")
      ->option_text("FILE")
      ->check(CLI::ExistingPath);
  app.add_option("--board", a.board,
                 "calibrate from a board instead: a checkerboard's inner corners and square "
                 "(COLSxROWSxMM) or a ChArUco board (charuco:SXxSYxMMxMM[:DICT]), as syncap "
                 "calibrate --board")
      ->option_text("BOARD");
  app.add_option("--board-clip", a.board_clips, "with --board: one camera's clip of the board")
      ->option_text("VIDEO|DIR")
      ->check(CLI::ExistingPath);
  app.add_option("--intrinsics", a.intrinsics,
                 "with --board: the cameras' OpenCV intrinsics, one file per camera or one for all")
      ->option_text("FILE")
      ->check(CLI::ExistingFile);
  app.add_option("--camera-ids", a.camera_ids,
                 "the cameras' ids in --capture order, e.g. 1,2,3,4 (default: the calibration's "
                 "in file order; with --board 0, 1, ...)");
  app.add_option("--out-dir", a.out, "the output folder (created)")->option_text("DIR")->required();
}

void add_run_options(cli::App& app, ReconstructArgs& a) {
  controllers::ReconstructionOptions& r = a.run;
  cli::add_checked(app, "--first-frame", r.first_frame, "F",
                   cli::whole_in<int64_t>(0, int64_t{1} << 40), "the first frame (default 0)");
  cli::add_checked(app, "--frames", r.frames, "N", cli::whole_in<int64_t>(1, int64_t{1} << 40),
                   "N frames (default: to the end of the shortest capture)");
  cli::add_checked(app, "--every", r.every, "N", cli::whole_in<int>(1, 100000),
                   "every Nth frame (default 1)");
  app.add_option("--rate-hz", r.rate_hz,
                 "the recordings' frame rate (default: the first video's, else 30)")
      ->check(cli::number_in(0.01, 1000));
  app.add_flag("--mask-images", a.mask_images,
               "write every mask as DIR/masks/camN/mask_NNNNNN.png");
  app.add_flag("--no-body", a.no_body, "hulls only, no body fit");
  app.add_flag_callback(
      "--all-regions", [&r] { r.masking.largest_region = false; },
      "keep every region of each mask (default: the largest only, one person)");
  cli::add_checked(app, "--train-frames", r.masking.train_frames, "N", cli::whole_in<int>(2, 10000),
                   "frames of each background clip the masking trains on (default " +
                       std::to_string(segmentation::kBackgroundClipFrames) + ")");
  segmentation::add_mask_options(app, r.masking.options, "");
  controllers::PipelineOptions& p = r.pipeline;
  host_app::add_hull_options(app, p.hull);
  host_app::add_body_options(app, p.body);
  host_app::add_volume_option(app, a.volume);
}

// The defaults of an offline reconstruction, set before the parse so that options override them.
void set_defaults(ReconstructArgs& a) {
  controllers::PipelineOptions& p = a.run.pipeline;
  a.run.rate_hz = 0;  // the video's
  p.markers.enabled = false;
  p.hull.enabled = true;
  p.hull.stage.max_wait_ms = 0;  // every frame gets its hull, however long it took
  p.hull.stage.view_iou = true;  // the report's cross-view check
  p.body.enabled = true;
}

void check_args(ReconstructArgs& a) {
  if (a.backgrounds.size() != a.captures.size())
    throw CLI::ValidationError("--background", "one per --capture");
  if (a.calibration.empty() == a.board.empty())
    throw CLI::ValidationError("--calibration", "give it or --board (one of the two)");
  if (!a.board.empty() && a.board_clips.size() != a.captures.size())
    throw CLI::ValidationError("--board-clip", "one per --capture");
  if (!a.board.empty() && a.intrinsics.empty())
    throw CLI::ValidationError("--intrinsics", "--board needs the cameras' intrinsics");
  if (a.no_body) a.run.pipeline.body.enabled = false;
  host_app::set_capture_volume(a.volume, a.run.pipeline);
  const fs::path out(a.out);
  if (a.run.pipeline.hull.stage.mesh_dir.empty())
    a.run.pipeline.hull.stage.mesh_dir = out / "hulls";
  if (a.mask_images) a.run.mask_dir = out / "masks";
}

std::optional<int> parse_args(std::span<const std::string> args, ReconstructArgs& a,
                              std::ostream& out, std::ostream& err) {
  cli::App app(kName, kDescription, kFooter);
  set_defaults(a);
  add_input_options(app, a);
  add_run_options(app, a);
  return cli::parse(app, args, out, err, [&a] { check_args(a); });
}

std::string join_ids(const std::vector<int>& ids) {
  std::string text;
  for (const int id : ids) text += (text.empty() ? "" : ",") + std::to_string(id);
  return text;
}

// The middle of the frames the run takes: of every capture's, from --first-frame, --frames long.
int64_t middle_frame(const ReconstructArgs& a) {
  int64_t first = a.run.first_frame, last = std::numeric_limits<int64_t>::max();
  for (const std::string& capture : a.captures) {
    const auto images = segmentation::open_image_sequence(capture);
    first = std::max(first, images->first_frame());
    last = std::min(last, images->last_frame());
  }
  if (a.run.frames > 0) last = std::min(last, first + a.run.frames - 1);
  return first + std::max<int64_t>(last - first, 0) / 2;
}

// The board calibration, as syncap calibrate --board, with the person's masks of one frame (the
// middle of the run) telling a symmetric board's half turn. Its status; the cameras in
// DIR/calibration/cameras.json.
int calibrate_on_board(const ReconstructArgs& a, const std::vector<int>& ids, std::ostream& out,
                       std::ostream& err) {
  const fs::path dir = fs::path(a.out) / "calibration";
  std::vector<std::string> args{"--board",    a.board,        "--out-dir",
                                dir.string(), "--camera-ids", join_ids(ids)};
  const int64_t middle = middle_frame(a);
  for (std::size_t i = 0; i < a.captures.size(); ++i) {
    controllers::CameraRecording r{ids[i], a.captures[i], a.backgrounds[i]};
    controllers::RecordingMasker masker(r, a.run.masking, a.run.first_frame);
    const auto masked = masker.mask(middle);
    if (!masked)
      throw segmentation::ImageSequenceError(a.captures[i] + ": no frame " +
                                             std::to_string(middle) + " (the board's masks)");
    const fs::path masks = dir / "masks" / ("cam" + std::to_string(ids[i]));
    segmentation::write_mask_image(masks, middle, masked->mask);
    for (const std::string& s :
         {std::string("--clip"), a.board_clips[i], std::string("--masks"), masks.string()})
      args.push_back(s);
  }
  for (const std::string& file : a.intrinsics) {
    args.push_back("--intrinsics");
    args.push_back(file);
  }
  out << kName << ": calibrating on the board into " << dir.string() << '\n';
  return board_calibrate_command(args, out, err);
}

// The cameras' ids in --capture order: --camera-ids, else the calibration's (or 0, 1, ... before
// a board calibration).
std::vector<int> capture_ids(const ReconstructArgs& a,
                             const std::vector<sensor::CameraModel>* cameras) {
  std::vector<int> ids;
  if (!a.camera_ids.empty()) {
    for (const int id : host_app::parse_camera_list(a.camera_ids)) ids.push_back(id);
  } else if (cameras != nullptr) {
    for (std::size_t i = 0; i < std::min(cameras->size(), a.captures.size()); ++i)
      ids.push_back((*cameras)[i].id);
  } else {
    for (std::size_t i = 0; i < a.captures.size(); ++i) ids.push_back(static_cast<int>(i));
  }
  if (ids.size() != a.captures.size())
    throw CLI::ValidationError("--camera-ids",
                               "one id per --capture (" + std::to_string(a.captures.size()) + ")");
  return ids;
}

// A progress line on err about once a second: on a terminal rewritten in place, else a line.
class Progress {
 public:
  explicit Progress(std::ostream& err) : err_(err), tty_(isatty(STDERR_FILENO) != 0) {}
  void operator()(int64_t processed, int64_t fed, int64_t total) {
    const auto now = std::chrono::steady_clock::now();
    const bool done = processed == total;
    if (!done && now - last_ < std::chrono::seconds(1)) return;
    last_ = now;
    const double s = std::chrono::duration<double>(now - start_).count();
    const double share =
        static_cast<double>(processed) / static_cast<double>(std::max<int64_t>(total, 1));
    std::string line =
        util::printf_string("%s: %lld/%lld frames (%.0f %%), %lld masked, %.0f s", kName,
                            static_cast<long long>(processed), static_cast<long long>(total),
                            100.0 * share, static_cast<long long>(fed), s);
    if (processed > 0 && !done) line += util::printf_string(", about %.0f s left", s / share - s);
    err_ << (tty_ ? "\r" : "") << line << (tty_ && !done ? "" : "\n") << std::flush;
  }

 private:
  std::ostream& err_;
  bool tty_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now(), last_{};
};

std::optional<sensor::CalibrationQuality> quality_of(const fs::path& file) {
  if (util::lower_extension(file) != ".json") return std::nullopt;
  try {
    return sensor::read_camera_set(file).quality;
  } catch (const std::exception&) {  // an OpenCV JSON file: no quality block
    return std::nullopt;
  }
}

// The report's pictures: each capture's frame `k` as recorded (colour where it is) with the mask
// kept of it.
void add_pictures(const ReconstructArgs& a, const std::vector<int>& ids, int64_t k,
                  std::map<int, cv::Mat>& masks, ReportInputs& report) {
  report.picture_frame = k;
  for (std::size_t i = 0; i < a.captures.size(); ++i) {
    const auto capture = segmentation::open_image_sequence(a.captures[i]);
    const std::optional<cv::Mat> image = capture->read(k, segmentation::ImageColour::kAsRecorded);
    if (image && masks.contains(ids[i])) report.pictures.push_back({ids[i], *image, masks[ids[i]]});
  }
  const fs::path mesh =
      fs::path(a.run.pipeline.hull.stage.mesh_dir) / ("hull_" + std::to_string(k) + ".ply");
  if (fs::exists(mesh)) report.picture_hull = hull::read_mesh(mesh);
}

int run(ReconstructArgs& a, const std::string& command_line, std::ostream& out, std::ostream& err) {
  const fs::path dir(a.out);
  fs::create_directories(dir);
  int calibration_status = kExitOk;
  if (!a.board.empty()) {
    calibration_status = calibrate_on_board(a, capture_ids(a, nullptr), out, err);
    if (calibration_status == kExitUsage) return kExitUsage;
    a.calibration = (dir / "calibration" / "cameras.json").string();
  }
  const std::vector<sensor::CameraModel> cameras = sensor::read_cameras(a.calibration);
  const std::vector<int> ids = capture_ids(a, a.board.empty() ? &cameras : nullptr);
  a.run.recordings.clear();
  for (std::size_t i = 0; i < a.captures.size(); ++i)
    a.run.recordings.push_back({ids[i], a.captures[i], a.backgrounds[i]});
  if (a.run.rate_hz <= 0) {
    const double video_rate = segmentation::open_image_sequence(a.captures[0])->frame_rate_hz();
    a.run.rate_hz = video_rate > 0 ? video_rate : 30.0;
  }
  std::ofstream jsonl(dir / "frames.jsonl");
  outputs::PoseRecord record;
  controllers::Sinks sinks;
  sinks.json_lines = &jsonl;
  sinks.poses = &record;
  auto figures = std::make_unique<FrameFiguresStage>();
  const FrameFiguresStage& kept = *figures;
  std::vector<std::unique_ptr<pipeline::Stage>> extra;
  extra.push_back(std::move(figures));
  // The report's frame: the middle of the run; its masks are kept as they pass.
  int64_t picture_frame = -1;
  std::map<int, cv::Mat> picture_masks;
  Progress progress(err);
  controllers::ReconstructionCallbacks callbacks;
  callbacks.started = [&](int64_t first, int64_t last) {
    picture_frame = first + (last - first) / a.run.every / 2 * a.run.every;
  };
  callbacks.progress = [&progress](int64_t processed, int64_t fed, int64_t total) {
    progress(processed, fed, total);
  };
  callbacks.masked = [&](int64_t k, int id, const controllers::RecordingMasker::Masked& m) {
    if (k == picture_frame) picture_masks[id] = m.mask.clone();
  };
  controllers::Reconstruction result =
      controllers::reconstruct_recording(cameras, a.run, sinks, std::move(extra), callbacks);
  bool export_failed = false;
  const std::vector<std::string> written =
      a.run.pipeline.body.enabled
          ? export_motion(result.chain.body->parameters(), record, dir, kName, err, export_failed)
          : std::vector<std::string>{};

  ReportInputs report;
  report.command_line = command_line;
  report.calibration_file = a.calibration;
  report.cameras = cameras;
  report.quality = quality_of(a.calibration);
  report.alignments = result.alignments;
  report.notes = result.notes;
  report.frames = kept.frames();
  report.frames_fed = result.frames_fed;
  report.body_fitted = a.run.pipeline.body.enabled;
  if (a.run.pipeline.hull.stage.hull.capture_volume)
    report.floor_z_mm = a.run.pipeline.hull.stage.hull.capture_volume->min().z();
  if (picture_frame >= 0) add_pictures(a, ids, picture_frame, picture_masks, report);
  report.hull_summary = result.chain.hull->summary();
  if (result.chain.body != nullptr) report.body_summary = result.chain.body->summary();
  report.mask_ms_per_frame = result.mask_ms_per_frame;
  report.wall_s = result.wall_s;
  report.files = {"frames.jsonl", "hulls/"};
  for (const std::string& w : written) report.files.push_back(w);
  if (a.mask_images) report.files.push_back("masks/");
  const ReportFigures f = summarise(report);
  write_report(dir, report, f);

  for (const std::string& line : result.alignments) out << kName << ": " << line << '\n';
  for (const std::string& line : result.notes) out << kName << ": " << line << '\n';
  out << util::printf_string(
      "%s: %lld frames in %.1f s (%.1f ms a frame; masking %.1f ms a camera and frame)\n", kName,
      static_cast<long long>(result.frames_fed), result.wall_s,
      1e3 * result.wall_s / static_cast<double>(std::max<int64_t>(result.frames_fed, 1)),
      result.mask_ms_per_frame);
  out << report.hull_summary << report.body_summary << summary_lines(f);
  out << kName << ": " << (dir / "report.html").string() << ", frames.jsonl, hulls/"
      << written_list(written) << '\n';
  const bool warned = !f.warnings.empty() || calibration_status != kExitOk || export_failed;
  return warned ? kExitReportedErrors : kExitOk;
}

}  // namespace

int reconstruct_command(std::span<const std::string> args, std::ostream& out, std::ostream& err) {
  ReconstructArgs a;
  if (const auto status = parse_args(args, a, out, err)) return *status;
  std::string command_line = "syncap reconstruct";
  for (const std::string& s : args) command_line += " " + s;
  try {
    return run(a, command_line, out, err);
  } catch (const CLI::ValidationError& e) {
    err << kName << ": " << e.what() << '\n';
  } catch (const std::exception& e) {  // a recording or camera file that cannot be read
    err << kName << ": " << e.what() << '\n';
  }
  return kExitUsage;
}

}  // namespace syncap::tools
