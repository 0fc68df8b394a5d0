#include "syncap/segmentation/scene_eval.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include <opencv2/imgcodecs.hpp>

namespace syncap::segmentation {
namespace {

struct ScenePhases {
  std::vector<int> room;    // the first room phase's frames
  std::vector<int> frames;  // every frame
};

// truth/frames.csv: frame,time_s,phase,phase_type,...
ScenePhases read_phases(const std::filesystem::path& dir) {
  const std::filesystem::path path = dir / "truth" / "frames.csv";
  std::ifstream in(path);
  if (!in) throw std::runtime_error("scene: cannot read " + path.string());
  ScenePhases phases;
  std::string line, room_phase;
  std::getline(in, line);
  for (int number = 2; std::getline(in, line); ++number) {
    std::stringstream fields(line);
    std::string frame, time, phase, type;
    std::getline(fields, frame, ',');
    std::getline(fields, time, ',');
    std::getline(fields, phase, ',');
    std::getline(fields, type, ',');
    try {
      phases.frames.push_back(std::stoi(frame));
    } catch (const std::exception&) {
      throw std::runtime_error("scene: " + path.string() + ":" + std::to_string(number) +
                               ": frame '" + frame + "' is not a number");
    }
    if (type == "room" && (room_phase.empty() || room_phase == phase)) {
      room_phase = phase;
      phases.room.push_back(phases.frames.back());
    }
  }
  if (phases.room.size() < 2) {
    throw std::runtime_error("scene: " + path.string() + " has no room phase of 2 frames or more");
  }
  return phases;
}

std::filesystem::path numbered(const std::filesystem::path& folder, const char* prefix, int frame,
                               const char* suffix) {
  char name[64];
  std::snprintf(name, sizeof name, "%s%06d%s", prefix, frame, suffix);
  return folder / name;
}

std::string camera_folder(int camera) {
  char name[32];
  std::snprintf(name, sizeof name, "camera%02d", camera);
  return name;
}

cv::Mat read_grey(const std::filesystem::path& path) {
  cv::Mat image = cv::imread(path.string(), cv::IMREAD_UNCHANGED);
  if (image.empty() || image.type() != CV_8UC1) {
    throw std::runtime_error("scene: " + path.string() + " is not a readable 8-bit grey image");
  }
  return image;
}

// The search region of `camera` for `frame` (empty when none applies).
std::vector<cv::Point> search_region_at(const std::vector<SceneRegion>& regions, int camera,
                                        int frame) {
  std::vector<cv::Point> found;
  for (const SceneRegion& r : regions) {
    if (r.camera == camera && r.kind == SceneRegion::Kind::kSearch && frame >= r.first_frame &&
        frame < r.first_frame + r.frames) {
      found = r.polygon;
    }
  }
  return found;
}

SceneCameraScore score_camera(const std::filesystem::path& dir, int camera,
                              const ScenePhases& phases, MediPictureOptions options,
                              const std::vector<SceneRegion>& regions) {
  for (const SceneRegion& r : regions) {
    if (r.camera != camera) continue;
    if (r.kind == SceneRegion::Kind::kClip) options.clip_polygon = r.polygon;
    if (r.kind == SceneRegion::Kind::kFloor) options.floor_polygon = r.polygon;
  }
  const std::filesystem::path images = dir / camera_folder(camera);
  const std::filesystem::path masks = dir / "truth" / "masks" / camera_folder(camera);
  std::vector<cv::Mat> training;
  for (int frame : phases.room)
    training.push_back(read_grey(numbered(images, "frame_", frame, ".pgm")));
  MediPicture medi(train_medi_picture(training, options), options);
  SceneCameraScore score;
  score.camera = camera;
  score.iou_min = 1;
  double iou_sum = 0, false_positives = 0, false_negatives = 0, truth_pixels = 0;
  for (int frame : phases.frames) {
    const std::filesystem::path mask_path = numbered(masks, "mask_", frame, ".png");
    if (!std::filesystem::exists(mask_path)) continue;
    const cv::Mat truth = read_grey(mask_path) != 0;
    std::vector<cv::Point> search = search_region_at(regions, camera, frame);
    if (!search.empty()) ++score.frames_searched;
    // Set only when it changes, as the edge does: a region set again would count as new (its
    // masks drawn again, a cut by it forgotten).
    if (search != medi.options().search_polygon) medi.set_search_region(std::move(search));
    const cv::Mat mask = medi.apply(read_grey(numbered(images, "frame_", frame, ".pgm"))) != 0;
    const int either = cv::countNonZero(mask | truth);
    const double iou = either == 0 ? 1.0 : cv::countNonZero(mask & truth) / double(either);
    iou_sum += iou;
    score.iou_min = std::min(score.iou_min, iou);
    false_positives += cv::countNonZero(mask & ~truth);
    false_negatives += cv::countNonZero(truth & ~mask);
    truth_pixels += cv::countNonZero(truth);
    ++score.frames;
  }
  if (score.frames == 0) throw std::runtime_error("scene: no true mask in " + masks.string());
  score.iou_mean = iou_sum / score.frames;
  score.false_positives = false_positives / score.frames;
  score.false_negatives = false_negatives / score.frames;
  score.truth_pixels = truth_pixels / score.frames;
  return score;
}

}  // namespace

std::vector<SceneCameraScore> evaluate_scene(const std::filesystem::path& dir,
                                             const MediPictureOptions& options,
                                             const std::vector<SceneRegion>& regions) {
  const ScenePhases phases = read_phases(dir);
  std::vector<SceneCameraScore> scores;
  for (int camera = 0; std::filesystem::is_directory(dir / camera_folder(camera)); ++camera) {
    scores.push_back(score_camera(dir, camera, phases, options, regions));
  }
  if (scores.empty()) throw std::runtime_error("scene: no camera00 folder in " + dir.string());
  return scores;
}

}  // namespace syncap::segmentation
