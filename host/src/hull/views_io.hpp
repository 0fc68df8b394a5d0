// Reading a hull's input from files: cameras (our cameras.json, an OpenCV-style YAML or JSON
// file, or a folder of 3x4 projection matrices, `*.pa`) and one mask image per camera.
#pragma once

#include <filesystem>
#include <optional>
#include <vector>

#include "hull/visual_hull.hpp"

namespace syncap::hull {

struct ViewFiles {
  double simplify_px = kDefaultSimplifyPx;
  // Foreground: grey value > threshold; none: any non-zero pixel.
  std::optional<int> threshold;
  // Keep only the largest 8-connected foreground component of each mask: one object in front
  // of a background that thresholding does not remove everywhere (a turntable's rim, lamps).
  bool largest_only = false;
};

// One mask image as a binary mask (255 foreground) by the options' threshold and largest-only;
// throws HullError naming the file when it cannot be read.
cv::Mat read_mask(const std::filesystem::path& file, const ViewFiles& options);

// The image files of a folder (png, jpg, jpeg, pgm, ppm, bmp, tif, tiff) in name order.
std::vector<std::filesystem::path> mask_files(const std::filesystem::path& folder);

// A 3x4 projection matrix file: 12 numbers, row by row (x_pixel ~ P (X, 1)).
cv::Matx34d read_projection_matrix(const std::filesystem::path& file);

// The views of `cameras` (cameras.json: its cameras in file order; an OpenCV-style file, .yaml,
// .yml or .json with K: its `cameras` in order, each with its OpenCV lens kept exactly
// (CameraModel::opencv_lens); any file sensor::read_cameras reads; a folder: its *.pa files in name
// order, cameras without distortion of the masks' size) with the masks of `masks` in name order,
// one per camera. Throws HullError naming the file: unreadable, a count that differs, a mask of the
// wrong size, an empty mask.
std::vector<HullView> read_views(const std::filesystem::path& cameras,
                                 const std::filesystem::path& masks, const ViewFiles& options);

// The cameras of `cameras` as read_views reads them, without masks: one per image of `images`
// (name order), which sizes the cameras of a *.pa folder; names as read_views gives
// them, silhouettes and masks empty (for a hull read from a file). Throws HullError naming the
// file: unreadable, a count that differs.
std::vector<HullView> read_camera_views(const std::filesystem::path& cameras,
                                        const std::filesystem::path& images);

}  // namespace syncap::hull
