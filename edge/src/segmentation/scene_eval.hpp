// Scoring medi-picture on a scene rendered by syncap-sim against its exact silhouettes: per
// camera, the model trains on the first room phase's frames (the empty room) and masks every
// frame that has a true mask (the person phases); IoU = |mask and truth| / |mask or truth|.
// This is the edge's masking without the transport, so a bench result can be split into
// segmentation and delivery.
#pragma once

#include <filesystem>
#include <vector>

#include "segmentation/medi_picture.hpp"

namespace syncap::edge {

struct SceneCameraScore {
  int camera = 0;
  int frames = 0;  // frames with a true mask
  double iou_mean = 0, iou_min = 0;
  double false_positives = 0;  // per frame, pixels
  double false_negatives = 0;  // per frame, pixels
  double truth_pixels = 0;     // per frame
};

// DIR as syncap-sim writes it (cameraNN/frame_KKKKKK.pgm, truth/frames.csv,
// truth/masks/cameraNN/mask_KKKKKK.png). Throws std::runtime_error naming the file (and line)
// when the folder has no room phase, no mask, or an unreadable file.
std::vector<SceneCameraScore> evaluate_scene(const std::filesystem::path& dir,
                                             const MediPictureOptions& options);

}  // namespace syncap::edge
