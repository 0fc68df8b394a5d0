// Silhouettes the host received against the simulator's true masks: the outlines are filled back
// into masks and scored by intersection over union (IoU).
#pragma once

#include <filesystem>
#include <optional>
#include <vector>

#include <opencv2/core.hpp>

#include "groups.hpp"
#include "truth.hpp"

namespace syncap::compare {

// The mask an edge's outlines describe: outer contours filled, holes cleared. The points are the
// centres of the boundary pixels of the foreground (cv::findContours), so the boundary pixels of
// a hole belong to the foreground and are drawn back after the hole is cleared.
cv::Mat silhouette_mask(const std::vector<Outline>& outlines, const ImageSize& image);

// |a and b| / |a or b| over nonzero pixels; nullopt when both are empty.
std::optional<double> intersection_over_union(const cv::Mat& a, const cv::Mat& b);

// DIR/truth/masks/cameraNN/mask_KKKKKK.png (written for the person phases only); nullopt when
// absent. Throws InputError when the file exists but is not a mask of the camera's size.
std::optional<cv::Mat> read_truth_mask(const std::filesystem::path& truth_dir, long frame,
                                       int camera, const ImageSize& image);

}  // namespace syncap::compare
