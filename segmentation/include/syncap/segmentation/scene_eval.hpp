// Scoring medi-picture on a scene rendered by syncap-sim against its exact silhouettes: per
// camera, the model trains on the first room phase's frames (the empty room) and masks every
// frame that has a true mask (the person phases); IoU = |mask and truth| / |mask or truth|.
// This is the edge's masking without the transport, so a bench result can be split into
// segmentation and delivery.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include "syncap/segmentation/medi_picture.hpp"

namespace syncap::segmentation {

// A region from the host for one camera (clip_polygon_t as `syncap clip` prints it): a clip, a
// floor, or a search region applying to frames first_frame .. first_frame + frames - 1.
struct SceneRegion {
  enum class Kind { kClip = 0, kFloor = 1, kSearch = 2 };
  int camera = 0;
  Kind kind = Kind::kClip;
  int64_t first_frame = 0;
  int frames = 0;
  std::vector<cv::Point> polygon;
};

struct SceneCameraScore {
  int camera = 0;
  int frames = 0;  // frames with a true mask
  double iou_mean = 0, iou_min = 0;
  double false_positives = 0;  // per frame, pixels
  double false_negatives = 0;  // per frame, pixels
  double truth_pixels = 0;     // per frame
  int frames_searched = 0;     // frames masked inside a search region
};

// DIR as syncap-sim writes it (cameraNN/frame_KKKKKK.pgm, truth/frames.csv,
// truth/masks/cameraNN/mask_KKKKKK.png). Throws std::runtime_error naming the file (and line)
// when the folder has no room phase, no mask, or an unreadable file.
// With `regions`, each camera's clip and floor regions apply to every frame and its search
// regions to their frames (the last given for a frame wins).
std::vector<SceneCameraScore> evaluate_scene(const std::filesystem::path& dir,
                                             const MediPictureOptions& options,
                                             const std::vector<SceneRegion>& regions = {});

}  // namespace syncap::segmentation
