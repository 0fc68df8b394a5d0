// The simulator's ground truth (hil/sim/src/truth_writer.cpp), as far as the comparison in the
// image needs it: frames.csv (phase of every frame), projections.csv (every target's disc in
// every camera) and cameras.json (image sizes; the true cameras, for the markers' reference).
// targets.csv (object space) is not needed here.
#pragma once

#include <array>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "sensor/camera_model.hpp"

namespace syncap::compare {

struct TruthFrame {
  long frame = 0;
  double time_s = 0;
  int phase = 0;           // index of the phase in the scenario
  std::string phase_type;  // wand | led | room | person
  bool led_on = false;
  double gain = 1;
};

// A target's disc as one camera sees it, in pixels: (0, 0) is the centre of the top-left pixel
// (docs/reference/camera-model.md), so the image spans [-0.5, width - 0.5) x [-0.5, height - 0.5).
struct Projection {
  long frame = 0;
  int camera = 0;
  int target = 0;
  double x_px = 0, y_px = 0, radius_px = 0;
  // centre in front of the camera and inside the image, and >= 98 % of the disc not hidden by
  // the person; a target behind the camera has radius 0 (no disc)
  bool visible = false;
};

struct ImageSize {
  int width_px = 0, height_px = 0;
};

using TruthFrames = std::map<long, TruthFrame>;  // by frame number
using ImageSizes = std::map<int, ImageSize>;     // by camera id
using FrameCamera = std::pair<long, int>;        // (frame, camera)

struct Truth {
  std::filesystem::path dir;  // the simulator's output folder (masks are read from it on demand)
  TruthFrames frames;
  ImageSizes images;
  std::map<int, sensor::CameraModel> cameras;  // by id: the true cameras (cameras.json)
  std::map<FrameCamera, std::vector<Projection>> projections;  // in target order
};

// Each throws InputError naming the file and line of the first problem.
TruthFrames read_frames(const std::filesystem::path& file);
ImageSizes read_image_sizes(const std::filesystem::path& cameras_json);
std::map<int, sensor::CameraModel> read_true_cameras(const std::filesystem::path& cameras_json);
// Every row must name a frame of `frames` and a camera of `images`, each (frame, camera,
// target) once.
std::vector<Projection> read_projections(const std::filesystem::path& file,
                                         const TruthFrames& frames, const ImageSizes& images);

// DIR/truth/frames.csv, DIR/truth/projections.csv, DIR/cameras.json.
Truth read_truth(const std::filesystem::path& dir);

// Every target position of truth/targets.csv [mm] (frame,target,X_mm,Y_mm,Z_mm,radius_mm), in
// file order: the points a calibration is checked by.
std::vector<std::array<double, 3>> read_target_positions(const std::filesystem::path& file);

}  // namespace syncap::compare
